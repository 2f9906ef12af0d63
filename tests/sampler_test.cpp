// The samplers' promises, checked on their values: the range, purity,
// stratification in elementary intervals, decorrelation between pixels and
// between dimensions, and integration error that falls faster than
// independent sampling's.
#include "sampler/sampler.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <thread>
#include <vector>

#include "sampler/dimensions.h"
#include "sampler/zsobol.h"

namespace lantern {
namespace {

const char* const kKinds[] = {"independent", "stratified", "halton", "sobol", "paddedsobol", "zsobol"};
// sobol's later dimensions take a pixel's subsequence, not a block, so are
// not nets (in pbrt-v4's sobol either); its film dimensions are.
const char* const kSobolKinds[] = {"paddedsobol", "zsobol"};

SamplerSpec spec_for(const char* kind, const char* randomization = "", int spp = 64, int w = 64, int h = 48,
                     uint64_t seed = 3) {
  SamplerSettings st;
  st.type = parse_sampler(kind);
  st.randomization = randomization;
  st.xsamples = st.ysamples = int(std::lround(std::sqrt(double(spp))));
  return make_sampler_spec(st, w, h, uint32_t(spp), seed);
}

// Every elementary interval of area 2^-k holds exactly one of the 2^k points.
::testing::AssertionResult is_base2_net(const std::vector<Vec2>& pts) {
  const int k = ceil_log2(pts.size());
  for (int a = 0; a <= k; ++a) {
    const int nx = 1 << a, ny = 1 << (k - a);
    std::vector<int> count(size_t(nx) * ny, 0);
    for (Vec2 p : pts) ++count[size_t(int(p.y * ny)) * nx + size_t(int(p.x * nx))];
    for (size_t c = 0; c < count.size(); ++c)
      if (count[c] != 1)
        return ::testing::AssertionFailure() << count[c] << " points in interval " << c << " of " << nx << "x" << ny;
  }
  return ::testing::AssertionSuccess();
}

// zsobol's shortcuts: dimension 1 from a table of reversed columns under
// fastowen, and the index's bits reversed once per sample (PathSampler
// keeps them so), must give the values of the plain formulas: the scramble
// of the Sobol point for any index and seed, and a sampler's values those
// of the nested scramble of its unreversed index.
TEST(Sampler, ZSobolShortcutsGiveThePlainFormulasValues) {
  std::mt19937_64 rng(7);
  for (int i = 0; i < 200000; ++i) {
    const uint64_t index = rng() >> (rng() % 64), h = rng();
    ASSERT_EQ(sobol_bits_dim1_reversed(index), reverse_bits32(sobol_bits_dim1(index)));
    const Vec2 v = sobol_2d(index, Randomization::FastOwen, h);
    const uint64_t h2 = mix64(h);
    ASSERT_EQ(v.x, bits32_to_unit_float(fast_owen_scramble(sobol_bits_dim0(index), uint32_t(h2))));
    ASSERT_EQ(v.y, bits32_to_unit_float(fast_owen_scramble(sobol_bits_dim1(index), uint32_t(h2 >> 32))));
  }
  // PathSampler keeps the key reversed: its values are those of the key.
  const SamplerSpec s = spec_for("zsobol");
  for (uint32_t pixel : {0u, 77u, 3071u})
    for (uint64_t sample : {0u, 5u, 63u}) {
      const PathSampler p = PathSampler::make(s, pixel, sample);
      const uint64_t key = (morton_2d(pixel % 64, pixel / 64) << s.log2_spp) | sample;
      for (uint32_t d = 0; d < 12; ++d) {
        const uint64_t hd = dimension_hash(p.salt, d);
        EXPECT_EQ(p.get2d(d), sobol_2d(nested_scramble_index(key, s.index_bits, hd), s.randomize, hd));
      }
    }
}

TEST(Sampler, ValuesLieInTheUnitIntervalForEveryKindAndRandomization) {
  for (const char* kind : kKinds)
    for (const char* r : {"none", "permutedigits", "fastowen", "owen"}) {
      SamplerSpec spec = spec_for(kind, r);
      for (uint32_t pixel : {0u, 1u, 63u, 64u * 48u - 1u})
        for (uint64_t i = 0; i < 70; ++i) {
          PathSampler s = PathSampler::make(spec, pixel, i);
          for (uint32_t d = 0; d < 200; d += 3) {
            float u = s.get1d(d);
            Vec2 v = s.get2d(d);
            ASSERT_TRUE(u >= 0.f && u < 1.f) << kind << " " << r << " dim " << d << ": " << u;
            ASSERT_TRUE(v.x >= 0.f && v.x < 1.f && v.y >= 0.f && v.y < 1.f) << kind << " " << r << " dim " << d;
          }
        }
    }
}

// A pure function of (seed, pixel, index, dimension): the same on another
// thread, from another copy of the spec; and a different seed changes it.
TEST(Sampler, SameValueOnAnyThreadAndDifferentWithAnotherSeed) {
  for (const char* kind : kKinds) {
    SamplerSpec a = spec_for(kind), b = spec_for(kind), other = spec_for(kind, "", 64, 64, 48, 4);
    std::vector<float> here, there;
    int differ = 0;
    for (uint32_t i = 0; i < 64; ++i) {
      here.push_back(PathSampler::make(a, 100 + i, i).get1d(dims::vertex(2)));
      differ += here.back() != PathSampler::make(other, 100 + i, i).get1d(dims::vertex(2));
    }
    std::thread t([&] {
      for (uint32_t i = 0; i < 64; ++i) there.push_back(PathSampler::make(b, 100 + i, i).get1d(dims::vertex(2)));
    });
    t.join();
    EXPECT_EQ(here, there) << kind;
    EXPECT_GT(differ, 48) << kind;
  }
}

// The per-pixel Sobol samplers: a pixel's first 2^k samples of any 2D
// dimension pair form a (0, k, 2)-net, with every randomisation.
TEST(Sampler, SobolSamplersStratifyEveryPrefixOfPowerOfTwoLength) {
  for (const char* kind : kSobolKinds)
    for (const char* r : {"none", "permutedigits", "fastowen", "owen"})
      for (int k = 0; k <= 6; ++k) {
        SamplerSpec spec = spec_for(kind, r, 64);
        for (uint32_t pixel : {0u, 77u, 64u * 48u - 1u})
          for (uint32_t d : {dims::kFilm, dims::kLens, dims::vertex(1) + dims::kEyeBsdfDirection,
                             dims::vertex(5) + dims::kLightBsdfDirection}) {
            std::vector<Vec2> pts;
            for (uint32_t i = 0; i < (1u << k); ++i) pts.push_back(PathSampler::make(spec, pixel, i).get2d(d));
            EXPECT_TRUE(is_base2_net(pts)) << kind << " " << r << " pixel " << pixel << " dim " << d << " k " << k;
          }
      }
}

// The global samplers place a pixel's samples inside it: the offsets of the
// first 4^k (sobol) or 2^a 3^b (halton) samples are stratified too.
TEST(Sampler, GlobalSequencesStratifyThePixel) {
  SamplerSpec sobol = spec_for("sobol", "", 64, 37, 21);
  for (uint32_t pixel : {0u, 5u, 36u + 37u * 20u}) {
    std::vector<Vec2> pts;
    for (uint32_t i = 0; i < 64; ++i) pts.push_back(PathSampler::make(sobol, pixel, i).get2d(dims::kFilm));
    EXPECT_TRUE(is_base2_net(pts)) << "sobol film, pixel " << pixel;
  }
  // Halton: base-2 and base-3 digits after the pixel's; 2 x 3 strata of the
  // pixel get one of the first 6 samples each, and dimension 2 (base 5)
  // puts one of the first 25 samples in each 1/25.
  SamplerSpec halton = spec_for("halton", "", 64, 37, 21);
  for (uint32_t pixel : {0u, 5u, 36u + 37u * 20u}) {
    std::vector<int> film(6, 0), dim2(25, 0);
    for (uint32_t i = 0; i < 6; ++i) {
      Vec2 p = PathSampler::make(halton, pixel, i).get2d(dims::kFilm);
      ++film[size_t(int(p.y * 3)) * 2 + size_t(int(p.x * 2))];
    }
    for (uint32_t i = 0; i < 25; ++i) ++dim2[size_t(PathSampler::make(halton, pixel, i).get1d(2) * 25)];
    EXPECT_EQ(film, std::vector<int>(6, 1)) << "pixel " << pixel;
    EXPECT_EQ(dim2, std::vector<int>(25, 1)) << "pixel " << pixel;
  }
  // Stratified: each of the 8 x 8 strata once per 64 samples, in 2D and 1D.
  SamplerSpec strat = spec_for("stratified", "", 64);
  std::vector<int> cells(64, 0), strata(64, 0);
  for (uint32_t i = 0; i < 64; ++i) {
    Vec2 p = PathSampler::make(strat, 9, i).get2d(dims::kLens);
    ++cells[size_t(int(p.y * 8)) * 8 + size_t(int(p.x * 8))];
    ++strata[size_t(PathSampler::make(strat, 9, i).get1d(dims::vertex(1)) * 64)];
  }
  EXPECT_EQ(cells, std::vector<int>(64, 1));
  EXPECT_EQ(strata, std::vector<int>(64, 1));
}

// Pearson's chi-square of counts against a uniform expectation.
double chi_square(const std::vector<int>& counts, double expected) {
  double c = 0.0;
  for (int n : counts) c += (n - expected) * (n - expected) / expected;
  return c;
}

// No visible pattern across pixels: the first sample of every pixel of a
// 64 x 48 image, in one dimension, is uniform over 32 bins (chi-square
// below its 99.9% point, 56.4 for 31 degrees of freedom; low-discrepancy
// sets are more even than random, so only the upper tail is checked), and
// its correlation with the pixel 1, 2, 4 and 8 to the right, below and
// diagonally is small: |r| < 0.1, where independent values give a standard
// deviation of 0.018. Halton with one randomisation for all pixels, for
// example, has r = -0.41 at 8 pixels.
TEST(Sampler, PixelsAreDecorrelated) {
  for (const char* kind : kKinds)
    for (uint32_t d : {dims::kLens, dims::vertex(1) + dims::kEyeLightSelect, dims::vertex(3) + dims::kEyeRoulette}) {
      SamplerSpec spec = spec_for(kind);
      const int w = 64, h = 48;
      std::vector<double> u(size_t(w) * h);
      std::vector<int> bins(32, 0);
      for (int p = 0; p < w * h; ++p) {
        u[size_t(p)] = PathSampler::make(spec, uint32_t(p), 0).get1d(d);
        ++bins[size_t(u[size_t(p)] * 32)];
      }
      EXPECT_LT(chi_square(bins, w * h / 32.0), 56.4) << kind << " dim " << d;
      for (auto [dx, dy] : {std::pair{1, 0}, {0, 1}, {1, 1}, {2, 0}, {0, 2}, {4, 0}, {0, 4}, {8, 0}, {0, 8}}) {
        double sxy = 0.0, sxx = 0.0;
        for (int y = 0; y + dy < h; ++y)
          for (int x = 0; x + dx < w; ++x) {
            const double a = u[size_t(y * w + x)] - 0.5, b = u[size_t((y + dy) * w + x + dx)] - 0.5;
            sxy += a * b, sxx += a * a;
          }
        EXPECT_LT(std::fabs(sxy / sxx), 0.1) << kind << " dim " << d << " lag " << dx << ", " << dy;
      }
    }
}

// Dimensions are decorrelated: two 1D dimensions of a pixel's 1024 samples,
// taken as pairs, are uniform over 8 x 8 bins.
TEST(Sampler, DimensionsAreDecorrelated) {
  for (const char* kind : kKinds) {
    SamplerSpec spec = spec_for(kind, "", 1024);
    const uint32_t pairs[][2] = {{dims::vertex(1) + dims::kEyeLightSelect, dims::vertex(1) + dims::kEyeBsdfComponent},
                                 {dims::vertex(1) + dims::kEyeRoulette, dims::vertex(2) + dims::kEyeRoulette},
                                 {dims::kLightSelect, dims::vertex(1) + dims::kEyeLightSelect}};
    for (const auto& pr : pairs) {
      std::vector<int> cells(64, 0);
      for (uint32_t i = 0; i < 1024; ++i) {
        PathSampler s = PathSampler::make(spec, 1234, i);
        ++cells[size_t(int(s.get1d(pr[0]) * 8) * 8 + int(s.get1d(pr[1]) * 8))];
      }
      EXPECT_LT(chi_square(cells, 16.0), 99.6) << kind << " dims " << pr[0] << ", " << pr[1];
    }
  }
}

// Root-mean-square error, over 96 pixels (independent randomisations), of
// the n-sample estimate of the integral of f over the unit square, with
// the samples of 2D dimension d.
template <class F>
double rms_error(const char* kind, uint32_t d, int n, F f, double exact) {
  SamplerSpec spec = spec_for(kind, "", n);
  double sum2 = 0.0;
  for (uint32_t pixel = 0; pixel < 96; ++pixel) {
    double est = 0.0;
    for (int i = 0; i < n; ++i) {
      Vec2 u = PathSampler::make(spec, pixel * 31, uint64_t(i)).get2d(d);
      est += f(u.x, u.y);
    }
    est /= n;
    sum2 += (est - exact) * (est - exact);
  }
  return std::sqrt(sum2 / 96);
}

// Least-squares slope of log error against log sample count.
double error_slope(const char* kind, uint32_t d, const std::vector<int>& counts, double (*f)(float, float),
                   double exact) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (int n : counts) {
    double x = std::log(double(n)), y = std::log(rms_error(kind, d, n, f, exact));
    sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  const double m = double(counts.size());
  return (m * sxy - sx * sy) / (m * sxx - sx * sx);
}

double smooth(float x, float y) { return std::exp(-double(x) * x - double(y) * y); }
double disk(float x, float y) { return double(x) * x + double(y) * y < 1.0 ? 1.0 : 0.0; }

// Independent sampling's error falls as n^-1/2; low-discrepancy samplers'
// as about n^-1 on smooth integrands (n^-1.5 with Owen scrambling) and
// n^-3/4 on a step along a curve. The fitted slopes must show it, in the
// lens dimensions and in a vertex's. (Halton's bases there are 109 and
// 113, and sobol's take a pixel's subsequence: both converge more slowly
// than in the first dimensions, as in pbrt-v4.)
TEST(Sampler, ErrorFallsFasterThanIndependentSampling) {
  const double e = std::sqrt(kPi) / 2.0 * std::erf(1.0);
  const std::vector<int> counts = {16, 64, 256, 1024};
  for (uint32_t d : {dims::kLens, dims::vertex(1) + dims::kEyeBsdfDirection}) {
    const bool first = d == dims::kLens;
    const double indep_smooth = error_slope("independent", d, counts, smooth, e * e);
    const double indep_disk = error_slope("independent", d, counts, disk, kPi / 4.0);
    std::printf("  dim %u, independent: slope %.2f (smooth), %.2f (disk)\n", d, indep_smooth, indep_disk);
    EXPECT_NEAR(indep_smooth, -0.5, 0.12);
    EXPECT_NEAR(indep_disk, -0.5, 0.12);
    for (const char* kind : {"stratified", "halton", "sobol", "paddedsobol", "zsobol"}) {
      const double s = error_slope(kind, d, counts, smooth, e * e), k = error_slope(kind, d, counts, disk, kPi / 4.0);
      std::printf("  dim %u, %s: slope %.2f (smooth), %.2f (disk)\n", d, kind, s, k);
      const bool global = std::string(kind) == "halton" || std::string(kind) == "sobol";
      EXPECT_LT(s, first || !global ? -0.85 : -0.7) << kind << " dim " << d;
      EXPECT_LT(k, first || !global ? -0.65 : -0.58) << kind << " dim " << d;
      EXPECT_LT(rms_error(kind, d, 1024, smooth, e * e), 0.3 * rms_error("independent", d, 1024, smooth, e * e))
          << kind << " dim " << d;
    }
  }
}

// Under a time limit the light subpaths' first points are laid out
// pass-major in groups of four passes (make_light_start_spec): each group's
// points over the whole image are one net, and so are each pixel's four
// points of a group. The eye layout's same points are not a net (the test
// can tell the layouts apart).
TEST(Sampler, LightStartsOfATimedRenderAreStratifiedOverTheImage) {
  SamplerSettings st;
  st.type = SamplerKind::ZSobol;
  for (const char* r : {"none", "fastowen", "owen"}) {
    st.randomization = r;
    const SamplerSpec eye = make_sampler_spec(st, 32, 32, 0, 5);
    const SamplerSpec start = make_light_start_spec(eye, 32, 32);
    auto group = [&](const SamplerSpec& spec, uint32_t first, uint32_t groups) {
      std::vector<Vec2> pts;
      for (uint32_t pixel = 0; pixel < 32 * 32; ++pixel)
        for (uint32_t i = first; i < first + 4 * groups; ++i)
          pts.push_back(PathSampler::make(spec, pixel, i).get2d(dims::kLightPosition));
      return pts;
    };
    for (uint32_t first : {0u, 4u, 20u}) EXPECT_TRUE(is_base2_net(group(start, first, 1))) << r << " group at " << first;
    EXPECT_TRUE(is_base2_net(group(start, 0, 2))) << r << " two groups";
    EXPECT_FALSE(is_base2_net(group(eye, 0, 1))) << r << " the eye layout";
    for (uint32_t pixel : {0u, 333u, 1023u}) {
      std::vector<Vec2> own;
      for (uint32_t i = 8; i < 12; ++i) own.push_back(PathSampler::make(start, pixel, i).get2d(dims::kLightPosition));
      EXPECT_TRUE(is_base2_net(own)) << r << " pixel " << pixel;
    }
  }
  // A planned count keeps the eye layout, whose whole render is one block.
  const SamplerSpec planned = make_sampler_spec(st, 32, 32, 64, 5);
  EXPECT_EQ(make_light_start_spec(planned, 32, 32).pixel_bits, 0);
}

}  // namespace
}  // namespace lantern
