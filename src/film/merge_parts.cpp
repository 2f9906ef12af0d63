#include "film/merge_parts.h"

#include <stdexcept>

#include "lantern/error.h"

namespace lantern {

namespace {

std::string part_name(const UnitShare& s) { return std::to_string(s.index + 1) + "/" + std::to_string(s.count); }

}  // namespace

MergedParts merge_parts(const std::vector<std::string>& paths, bool preview) {
  if (paths.empty()) throw std::invalid_argument("no parts to merge");
  MergedParts m{Film(0, 0, PixelFilter{}), "", 0, {}, false, {}};
  std::vector<std::string> owner;  // file of each part index seen, "" if none
  uint64_t passes = 0;
  uint32_t waves = 0;
  std::vector<uint8_t> finished;
  for (const std::string& path : paths) {
    Film film(0, 0, PixelFilter{});
    const CheckpointInfo info = read_film_file(path, film);
    if (m.parts == 0) {
      m.fingerprint = info.fingerprint;
      m.parts = info.share.count;
      passes = info.passes;
      waves = info.waves;
      owner.assign(m.parts, "");
      finished.assign(m.parts, 0);
    } else {
      if (info.fingerprint != m.fingerprint) {
        const auto [here, first] = fingerprint_difference(info.fingerprint, m.fingerprint);
        throw InputError({path, 0, 0}, "is a part of another render: it has \"" + here + "\" where the first part has \"" +
                                           first + "\" (" + paths[0] + ")");
      }
      if (info.share.count != m.parts)
        throw InputError({path, 0, 0}, "is part " + part_name(info.share) + ", but " + paths[0] + " is one of " +
                                           std::to_string(m.parts) + " parts");
    }
    if (!owner[info.share.index].empty())
      throw InputError({path, 0, 0}, "is part " + part_name(info.share) + " again (already given as " +
                                         owner[info.share.index] + ")");
    if (m.done.overlaps(info.done))
      throw InputError({path, 0, 0}, "holds units another part also holds (the same work twice)");
    owner[info.share.index] = path;
    finished[info.share.index] = passes > 0 && info.done.size() == info.share.size_of(passes, waves);
    if (m.film.width() == 0) m.film = std::move(film);
    else m.film.add(film);
    m.done.add(info.done);
  }
  for (uint32_t k = 0; k < m.parts; ++k) {
    const std::string name = part_name(UnitShare{k, m.parts});
    if (owner[k].empty()) m.missing.push_back("part " + name + " is missing");
    else if (passes > 0 && !finished[k]) m.missing.push_back("part " + name + " (" + owner[k] + ") is unfinished");
  }
  m.complete = m.missing.empty();
  if (!m.complete && !preview)
    throw std::runtime_error(m.missing.front() + "; merge the parts there are with --preview");
  return m;
}

}  // namespace lantern
