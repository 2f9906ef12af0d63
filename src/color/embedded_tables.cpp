// The tables the build fitted (lantern-rgb-table) and embedded
// (rgb_tables.S): a 32-bit resolution, then the coefficients, read where
// they lie (4-byte aligned: the assembler aligns the start to 16).
#include <cstdint>
#include <cstring>
#include <stdexcept>

#include "color/rgb_spectrum_table.h"

extern "C" const unsigned char lantern_srgb_spectrum_table[];
extern "C" const unsigned char lantern_srgb_spectrum_table_end[];

namespace lantern {

namespace {

RGBToSpectrumTable embedded(const unsigned char* begin, const unsigned char* end) {
  int32_t res = 0;
  const size_t bytes = size_t(end - begin);
  if (bytes >= sizeof res) std::memcpy(&res, begin, sizeof res);
  if (res < 2 || bytes != sizeof res + RGBToSpectrumTable::index(res, 3, 0, 0, 0) * sizeof(float))
    throw std::logic_error("the embedded RGB-to-spectrum table is malformed");
  const auto* c = reinterpret_cast<const float*>(begin + sizeof res);
  return RGBToSpectrumTable(res, std::span<const float>(c, RGBToSpectrumTable::index(res, 3, 0, 0, 0)));
}

}  // namespace

const RGBToSpectrumTable& RGBToSpectrumTable::srgb() {
  static const RGBToSpectrumTable table = embedded(lantern_srgb_spectrum_table, lantern_srgb_spectrum_table_end);
  return table;
}

}  // namespace lantern
