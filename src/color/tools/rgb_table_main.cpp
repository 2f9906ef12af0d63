// lantern-rgb-table SPACE RES OUT: fits the RGB-to-spectrum table of colour
// space SPACE at RES nodes per axis (color/rgb_spectrum_fit.h) and writes
// it to OUT as the build embeds it: the resolution as a 32-bit integer,
// then 3 * RES^3 * 3 floats, both in the machine's byte order.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

#include "color/rgb_spectrum_fit.h"

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: lantern-rgb-table SPACE RES OUT\n");
    return 2;
  }
  const lantern::ColorSpace* cs = lantern::ColorSpace::named(argv[1]);
  const int res = std::atoi(argv[2]);
  if (!cs || res < 2 || res > 256) {
    std::fprintf(stderr, "lantern-rgb-table: unknown colour space '%s' or resolution '%s'\n", argv[1], argv[2]);
    return 2;
  }
  const lantern::RGBToSpectrumTable table = lantern::fit_rgb_to_spectrum_table(*cs, res);
  const std::string tmp = std::string(argv[3]) + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary);
    const int32_t r = res;
    out.write(reinterpret_cast<const char*>(&r), sizeof r);
    out.write(reinterpret_cast<const char*>(table.coefficients().data()),
              std::streamsize(table.coefficients().size() * sizeof(float)));
    if (!out) {
      std::fprintf(stderr, "lantern-rgb-table: cannot write %s\n", tmp.c_str());
      return 1;
    }
  }
  if (std::rename(tmp.c_str(), argv[3]) != 0) {
    std::fprintf(stderr, "lantern-rgb-table: cannot write %s\n", argv[3]);
    return 1;
  }
  return 0;
}
