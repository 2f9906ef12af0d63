#include "film/checkpoint.h"

#include "imageio/replace_file.h"

#include <cmath>
#include <cstdio>
#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "lantern/error.h"
#include "math/fnv1a.h"

namespace lantern {

namespace {

constexpr char kMagic[8] = {'L', 'N', 'T', 'N', 'C', 'K', 'P', 'T'};
// 2: fixed-point sums, unit sets; 3: and what the integrator learnt; 4:
// the same, a guiding field with distributions for media too; 5: and which
// subpaths it guides, with the light subpaths' importance field; 6: its
// sums in fixed point, and what guided distances learnt; 7: and whether
// each field's guide pays (SDTree::judge). A render that learns nothing
// writes 2, which every version since reads; the guiding fields of 3 to 6
// are refused (they lack what 7 adds, and 3 to 5 summed in doubles).
constexpr uint32_t kVersion = 2, kLearntVersion = 7, kFirstGuidedVersion = 3;

class HashingWriter final : public StateWriter {
 public:
  explicit HashingWriter(std::ofstream& out) : out_(out) {}
  void write(const void* p, size_t n) override {
    hash.add(p, n);
    out_.write(static_cast<const char*>(p), std::streamsize(n));
  }
  Fnv1a hash;

 private:
  std::ofstream& out_;
};

class HashingReader final : public StateReader {
 public:
  HashingReader(std::ifstream& in, const std::string& path) : in_(in), path_(path) {}
  void read(void* p, size_t n) override {
    if (!in_.read(static_cast<char*>(p), std::streamsize(n)))
      throw InputError({path_, 0, 0}, "file is truncated");
    hash.add(p, n);
  }
  Fnv1a hash;

 private:
  std::ifstream& in_;
  const std::string& path_;
};

}  // namespace

// Compared by key (the text before '='), so that a line one side lacks is
// named as that, not as a shift of every line after it.
std::pair<std::string, std::string> fingerprint_difference(const std::string& a, const std::string& b) {
  auto lines = [](const std::string& text) {
    std::vector<std::pair<std::string, std::string>> out;  // key, line
    std::istringstream in(text);
    for (std::string l; std::getline(in, l);) out.emplace_back(l.substr(0, l.find('=')), l);
    return out;
  };
  const auto la = lines(a), lb = lines(b);
  auto find = [](const auto& v, const std::string& key) -> const std::string* {
    for (const auto& [k, l] : v)
      if (k == key) return &l;
    return nullptr;
  };
  for (const auto& [key, line] : lb) {
    const std::string* other = find(la, key);
    if (!other) return {"(no " + key + " line)", line};
    if (*other != line) return {*other, line};
  }
  for (const auto& [key, line] : la)
    if (!find(lb, key)) return {line, "(no " + key + " line)"};
  if (a != b) return {a, b};  // (the same lines in another order, or repeated)
  return {};
}

void write_checkpoint(const std::string& path, const CheckpointInfo& info, const Film& film) {
  std::string tmp = temporary_output(path, "");
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error("cannot write checkpoint \"" + tmp + "\"");
    HashingWriter w(out);
    w.write(kMagic, sizeof kMagic);
    w.put(info.learnt.empty() ? kVersion : kLearntVersion);
    w.put(uint32_t(info.fingerprint.size()));
    w.write(info.fingerprint.data(), info.fingerprint.size());
    w.put(info.share.index);
    w.put(info.share.count);
    w.put(info.passes);
    w.put(info.waves);
    w.put(info.elapsed_seconds);
    const auto& runs = info.done.intervals();
    w.put(uint32_t(runs.size()));
    for (const auto& [first, end] : runs) {
      w.put(first);
      w.put(end);
    }
    film.write_state(w);
    if (!info.learnt.empty()) {
      w.put(uint64_t(info.learnt.size()));
      w.write(info.learnt.data(), info.learnt.size());
    }
    uint64_t h = w.hash.h;
    out.write(reinterpret_cast<const char*>(&h), sizeof h);
    if (!out.flush()) {
      std::remove(tmp.c_str());
      throw std::runtime_error("cannot write checkpoint \"" + tmp + "\" (disk full?)");
    }
  }
  place_output(tmp, path);
}

namespace {

// The magic, the format version and the fingerprint.
std::string read_header(HashingReader& r, const std::string& path, uint32_t* version = nullptr) {
  char magic[sizeof kMagic];
  r.read(magic, sizeof magic);
  if (std::memcmp(magic, kMagic, sizeof kMagic) != 0) throw InputError({path, 0, 0}, "not a Lantern checkpoint or part file");
  const uint32_t v = r.get<uint32_t>();
  if (v >= kFirstGuidedVersion && v < kLearntVersion)
    throw InputError({path, 0, 0}, "file format version " + std::to_string(v) +
                                       " is a guided render's from an earlier Lantern version, whose guiding field "
                                       "this version cannot continue (its field now also judges whether its guide "
                                       "pays); resume it with the version that wrote it");
  if (v != kVersion && v != kLearntVersion)
    throw InputError({path, 0, 0}, "file format version " + std::to_string(v) + " is not " + std::to_string(kVersion) +
                                       " or " + std::to_string(kLearntVersion) + " (made by another Lantern version)");
  if (version) *version = v;
  const uint32_t n = r.get<uint32_t>();
  if (n > (1u << 20)) throw InputError({path, 0, 0}, "file is damaged (fingerprint length)");
  std::string fingerprint(n, '\0');
  r.read(fingerprint.data(), n);
  return fingerprint;
}

CheckpointInfo read_file(const std::string& path, const std::string* expected, Film& film) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError({path, 0, 0}, expected ? "cannot open checkpoint (nothing to resume)" : "cannot open film file");
  HashingReader r(in, path);
  CheckpointInfo info;
  uint32_t version = 0;
  info.fingerprint = read_header(r, path, &version);
  if (expected && info.fingerprint != *expected) {
    const auto [saved, now] = fingerprint_difference(info.fingerprint, *expected);
    throw InputError({path, 0, 0}, "checkpoint belongs to another render: it was made with \"" + saved +
                                       "\" but this render has \"" + now + "\"");
  }
  info.share.index = r.get<uint32_t>();
  info.share.count = r.get<uint32_t>();
  info.passes = r.get<uint64_t>();
  info.waves = r.get<uint32_t>();
  info.elapsed_seconds = r.get<double>();
  if (info.share.count == 0 || info.share.count > 1000000 || info.share.index >= info.share.count ||
      !std::isfinite(info.elapsed_seconds))
    throw InputError({path, 0, 0}, "file is damaged (share or time)");
  const uint32_t runs = r.get<uint32_t>();
  if (runs > (1u << 26)) throw InputError({path, 0, 0}, "file is damaged (unit list length)");
  std::vector<UnitSet::Interval> intervals(runs);
  for (auto& [first, end] : intervals) {
    first = r.get<uint64_t>();
    end = r.get<uint64_t>();
  }
  const bool bounded = info.passes > 0 && info.passes < (uint64_t(1) << 40);
  if (!UnitSet::valid(intervals) ||
      (!intervals.empty() && (info.waves == 0 || (bounded && intervals.back().second > info.passes * info.waves))))
    throw InputError({path, 0, 0}, "file is damaged (unit list)");
  info.done = UnitSet::of(std::move(intervals));
  film.read_state(r);
  if (version == kLearntVersion) {
    // No longer than what is left of the file.
    std::error_code ec;
    const uint64_t size = std::filesystem::file_size(path, ec);
    const std::streamoff at = in.tellg();
    const uint64_t left = ec || at < 0 || uint64_t(at) > size ? 0 : size - uint64_t(at);
    const uint64_t n = r.get<uint64_t>();
    if (n > left) throw InputError({path, 0, 0}, "file is damaged (the learnt state's length)");
    info.learnt.resize(size_t(n));
    r.read(info.learnt.data(), size_t(n));
  }
  uint64_t computed = r.hash.h, stored = 0;
  if (!in.read(reinterpret_cast<char*>(&stored), sizeof stored)) throw InputError({path, 0, 0}, "file is truncated");
  if (stored != computed) throw InputError({path, 0, 0}, "file is damaged (checksum mismatch)");
  if (in.peek() != std::ifstream::traits_type::eof()) throw InputError({path, 0, 0}, "file has trailing bytes");
  return info;
}

}  // namespace

CheckpointInfo read_checkpoint(const std::string& path, const std::string& expected, Film& film) {
  return read_file(path, &expected, film);
}

CheckpointInfo read_film_file(const std::string& path, Film& film) { return read_file(path, nullptr, film); }

std::string read_checkpoint_fingerprint(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError({path, 0, 0}, "cannot open checkpoint (nothing to resume)");
  HashingReader r(in, path);
  return read_header(r, path);
}

std::vector<std::string> checkpoint_pieces(const std::string& path) {
  namespace fs = std::filesystem;
  std::vector<std::string> pieces;
  std::error_code ec;
  const fs::path p(path);
  const fs::path dir = p.has_parent_path() ? p.parent_path() : fs::path(".");
  const std::string prefix = p.filename().string() + ".rank";
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(prefix, 0) == 0 && name.find(".partial") == std::string::npos)
      pieces.push_back((dir / name).string());
  }
  std::sort(pieces.begin(), pieces.end());
  if (fs::exists(path, ec)) pieces.insert(pieces.begin(), path);
  return pieces;
}

CheckpointInfo read_checkpoint_pieces(const std::string& path, const std::string& expected, Film& film,
                                      std::vector<std::string>& pieces, const JoinLearnt& join_learnt) {
  pieces = checkpoint_pieces(path);
  if (pieces.empty()) throw InputError({path, 0, 0}, "cannot open checkpoint (nothing to resume)");
  // Two readings, so that memory holds two films, not one per piece: the
  // units of every piece first, then the sums of those that count.
  std::vector<CheckpointInfo> infos;
  for (const std::string& piece : pieces) {
    Film scratch(0, 0, PixelFilter{});
    infos.push_back(read_checkpoint(piece, expected, scratch));
  }
  CheckpointInfo all;
  std::vector<std::string> learnt;  // of the pieces joined
  bool first = true;
  for (size_t i = 0; i < infos.size(); ++i) {
    bool absorbed = false;
    for (size_t j = 0; j < infos.size() && !absorbed; ++j) {
      if (j == i || !infos[i].done.overlaps(infos[j].done)) continue;
      UnitSet both = infos[j].done;
      both.add(infos[i].done);
      if (both == infos[j].done && (infos[i].done.size() < infos[j].done.size() || j < i)) {
        absorbed = true;  // i's units are all in j: j took i in
      } else if (!(both == infos[i].done)) {
        throw InputError({pieces[i], 0, 0}, "shares some but not all of its units with " + pieces[j] +
                                                ": the checkpoint's pieces do not fit together");
      }
    }
    if (absorbed) continue;
    // (A learnt state belongs to the units of one process: pieces of
    // several are joined by the integrator, which knows what they hold.)
    if (!first && (!learnt[0].empty() || !infos[i].learnt.empty()) && !join_learnt)
      throw InputError({pieces[i], 0, 0}, "holds what its render learnt (a guiding field), as does another piece: "
                                          "pieces of a render that learns cannot be joined");
    if (!first && learnt[0].empty() != infos[i].learnt.empty())
      throw InputError({pieces[i], 0, 0}, "holds what its render learnt and another piece does not");
    learnt.push_back(std::move(infos[i].learnt));
    if (first) {
      all = infos[i];
      first = false;
    } else {
      if (infos[i].share.index != all.share.index || infos[i].share.count != all.share.count)
        throw InputError({pieces[i], 0, 0}, "is a piece of another part of the render than " + pieces[0]);
      all.done.add(infos[i].done);
      all.elapsed_seconds = std::max(all.elapsed_seconds, infos[i].elapsed_seconds);
    }
    Film sums(0, 0, PixelFilter{});
    read_checkpoint(pieces[i], expected, sums);
    film.add(sums);
  }
  if (learnt.size() == 1) {
    all.learnt = std::move(learnt[0]);
  } else if (learnt.size() > 1 && !learnt[0].empty()) {
    try {
      all.learnt = join_learnt(learnt);
    } catch (const std::runtime_error& e) {
      throw InputError({path, 0, 0}, std::string("the checkpoint's pieces cannot be joined: ") + e.what());
    }
  }
  return all;
}

}  // namespace lantern
