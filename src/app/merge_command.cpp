#include "app/merge_command.h"

#include <cstdio>

#include "app/log.h"
#include "app/outputs.h"
#include "app/provenance.h"
#include "film/merge_parts.h"

namespace lantern {

int run_merge(const MergeArgs& a, const Provenance& provenance) {
  check_image_path(a.output);  // before reading parts that may be large
  MergedParts m = merge_parts(a.parts, a.preview);
  for (const std::string& gap : m.missing) logging::warning("warning: preview: %s", gap.c_str());
  const Image image = m.film.resolve();
  ImageMetadata md = {{"lantern:parts", std::to_string(a.parts.size()) + " of " + std::to_string(m.parts)},
                            {"lantern:preview", m.complete ? "false" : "true"},
                            {"lantern:spp", std::to_string(m.film.min_samples_per_pixel())},
                            {"lantern:samples", std::to_string(m.film.total_samples())},
                            {"lantern:render", m.fingerprint}};
  add_provenance(md, provenance);  // of the merge; the parts' settings are in lantern:render
  if (m.film.cropped())  // where the crop lies in the whole image (EXR data and display windows)
    md.emplace_back("pixelbounds", std::to_string(int(m.film.raster_offset().x)) + " " +
                                       std::to_string(int(m.film.raster_offset().y)) + " " +
                                       std::to_string(m.film.full_width()) + " " + std::to_string(m.film.full_height()));
  const ImageWrite written = write_image_or_rescue(a.output, image, md, "");
  if (!written.written) {
    logging::error("error: %s", written.error.c_str());
    if (!written.rescue.empty()) logging::error("the merged image is saved instead in %s", written.rescue.c_str());
    return 1;
  }
  if (!a.quiet)
    logging::info("%s: %dx%d, %zu of %u parts, %llu samples, %u spp (min)%s", a.output.c_str(), image.width,
                 image.height, a.parts.size(), m.parts, (unsigned long long)m.film.total_samples(),
                 m.film.min_samples_per_pixel(), m.complete ? "" : " (preview)");
  return 0;
}

}  // namespace lantern
