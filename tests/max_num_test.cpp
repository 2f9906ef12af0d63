// max_num and min_num (math/max_num.h) against the C library.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

#include "math/max_num.h"

namespace lantern {
namespace {

// max_num and min_num are std::fmax and std::fmin inline: the same bits for
// every pair of the values where they could part (signed zeros, infinities,
// NaN, subnormals, the largest floats), in both orders, so that the change
// from the C library's calls left every image as it was. (The library's
// results are computed at run time: the values pass through volatiles,
// where the compiler cannot fold the calls with rules of its own.)
TEST(MaxNum, SameBitsAsTheCLibrary) {
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  const float values[] = {0.f, -0.f, 1.f, -1.f, inf, -inf, nan, 1e-40f, -1e-40f,
                          std::numeric_limits<float>::max(), -std::numeric_limits<float>::max(), 0.5f};
  auto bits = [](float f) {
    uint32_t b;
    std::memcpy(&b, &f, sizeof b);
    return b;
  };
  for (float x : values)
    for (float y : values) {
      volatile float a = x, b = y;
      const float lib_max = std::fmax(a, b), lib_min = std::fmin(a, b);
      if (std::isnan(lib_max)) EXPECT_TRUE(std::isnan(max_num(a, b))) << x << " " << y;
      else EXPECT_EQ(bits(max_num(a, b)), bits(lib_max)) << x << " " << y;
      if (std::isnan(lib_min)) EXPECT_TRUE(std::isnan(min_num(a, b))) << x << " " << y;
      else EXPECT_EQ(bits(min_num(a, b)), bits(lib_min)) << x << " " << y;
      volatile double c = x, d = y;
      const double dlib_max = std::fmax(c, d);
      if (std::isnan(dlib_max)) EXPECT_TRUE(std::isnan(max_num(double(c), double(d))));
      else EXPECT_EQ(std::signbit(max_num(double(c), double(d))), std::signbit(dlib_max)) << x << " " << y;
      if (!std::isnan(dlib_max)) EXPECT_EQ(max_num(double(c), double(d)), dlib_max);
    }
}

}  // namespace
}  // namespace lantern
