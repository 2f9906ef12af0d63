// pbrt-v4's measured material: the bilinear warp it is built on, the tensor
// file reader, and BRDFs tabulated from a known analytic one
// (tabulated_bsdf.h) against that BRDF: values, albedo, sampling, and
// renders through every integrator.
#include "material/measured_bsdf.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>

#include "bsdf_checks.h"
#include "sanitizer.h"
#include "expect_error.h"
#include "lantern/render.h"
#include "lantern/scene.h"
#include "material/conductor_bsdf.h"
#include "material/tensor_file.h"
#include "math/piecewise_linear_2d.h"
#include "math/rng.h"
#include "stat_compare.h"
#include "tabulated_bsdf.h"

namespace lantern {
namespace {

namespace fs = std::filesystem;

fs::path temp_dir() {
  const fs::path d = fs::temp_directory_path() / ("lantern-measured-" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d;
}

// A grid of 7 x 5 values at 3 x 4 parameter points, none zero.
struct TestTable {
  std::vector<float> values;
  std::vector<std::vector<float>> params = {{0.f, 1.f, 3.f}, {-1.f, 0.f, 0.5f, 2.f}};
  TestTable() {
    RandomStream s = RandomStream::make(3, 0, 0);
    for (int i = 0; i < 3 * 4 * 7 * 5; ++i) values.push_back(0.05f + s.get1d());
  }
};

TEST(PiecewiseLinear2D, SampleAndInvertAreInverses) {
  const TestTable t;
  const PiecewiseLinear2D w(t.values.data(), 7, 5, t.params, true);
  RandomStream s = RandomStream::make(5, 0, 0);
  for (int i = 0; i < 2000; ++i) {
    const float param[2] = {3.5f * s.get1d() - 0.2f, 3.f * s.get1d() - 1.2f};
    const Vec2 u = s.get2d();
    const PiecewiseLinear2D::Sample a = w.sample(u, param);
    const PiecewiseLinear2D::Sample b = w.invert(a.p, param);
    EXPECT_NEAR(b.p.x, u.x, 2e-4f) << i;
    EXPECT_NEAR(b.p.y, u.y, 2e-4f) << i;
    EXPECT_NEAR(a.pdf, b.pdf, 1e-4f * a.pdf) << i;
    EXPECT_NEAR(w.evaluate(a.p, param), a.pdf, 1e-4f * a.pdf) << i;
  }
}

// The density integrates to 1 at any parameter point and the samples fall
// into 8 x 8 bins as it says (chi-square).
TEST(PiecewiseLinear2D, SamplesFollowTheDensity) {
  const TestTable t;
  const PiecewiseLinear2D w(t.values.data(), 7, 5, t.params, true);
  const float param[2] = {0.4f, 1.1f};
  constexpr int kBins = 8, kSub = 40, kSamples = 200000;
  std::vector<double> expected(kBins * kBins, 0.0), observed(kBins * kBins, 0.0);
  double total = 0.0;
  for (int by = 0; by < kBins; ++by)
    for (int bx = 0; bx < kBins; ++bx) {
      double sum = 0.0;
      for (int j = 0; j < kSub; ++j)
        for (int i = 0; i < kSub; ++i)
          sum += w.evaluate(Vec2((bx + (i + 0.5f) / kSub) / kBins, (by + (j + 0.5f) / kSub) / kBins), param);
      expected[size_t(by * kBins + bx)] = sum / (kSub * kSub * kBins * kBins);
      total += expected[size_t(by * kBins + bx)];
    }
  EXPECT_NEAR(total, 1.0, 1e-4);
  RandomStream s = RandomStream::make(9, 0, 0);
  for (int i = 0; i < kSamples; ++i) {
    const Vec2 p = w.sample(s.get2d(), param).p;
    observed[size_t(std::min(int(p.y * kBins), kBins - 1) * kBins + std::min(int(p.x * kBins), kBins - 1))] += 1;
  }
  double chi2 = 0.0;
  for (size_t b = 0; b < expected.size(); ++b)
    chi2 += sqr(float(observed[b] - expected[b] * kSamples)) / (expected[b] * kSamples);
  EXPECT_LT(chi2, bsdf_checks::chi2_critical(kBins * kBins - 1));
}

TEST(PiecewiseLinear2D, ValuesInterpolateBilinearlyAndAcrossParameters) {
  const TestTable t;
  const PiecewiseLinear2D v(t.values.data(), 7, 5, t.params, false);
  auto at = [&](int a, int b, int x, int y) { return t.values[size_t(((a * 4 + b) * 5 + y) * 7 + x)]; };
  const float p00[2] = {1.f, 0.5f};
  EXPECT_FLOAT_EQ(v.evaluate(Vec2(2.f / 6.f, 3.f / 4.f), p00), at(1, 2, 2, 3));
  // Half-way between two columns, and between two values of each parameter.
  EXPECT_NEAR(v.evaluate(Vec2(2.5f / 6.f, 3.f / 4.f), p00), 0.5f * (at(1, 2, 2, 3) + at(1, 2, 3, 3)), 1e-6f);
  const float mid[2] = {2.f, 0.25f};
  float expect = 0.f;
  for (int a : {1, 2})
    for (int b : {1, 2}) expect += 0.25f * at(a, b, 2, 3);
  EXPECT_NEAR(v.evaluate(Vec2(2.f / 6.f, 3.f / 4.f), mid), expect, 1e-6f);
  // Outside a parameter's range: its nearest grid.
  const float beyond[2] = {7.f, -5.f};
  EXPECT_FLOAT_EQ(v.evaluate(Vec2(0.f, 0.f), beyond), at(2, 0, 0, 0));
  // A grid of zeros samples uniformly.
  const std::vector<float> zeros(4, 0.f);
  const PiecewiseLinear2D z(zeros.data(), 2, 2, {}, true);
  EXPECT_FLOAT_EQ(z.sample(Vec2(0.3f, 0.7f), nullptr).pdf, 1.f);
}

// The analytic BRDF the files tabulate: GGX with Smith's height-correlated
// masking and the Fresnel factor of a conductor whose eta and k vary with
// wavelength, so the tabulated spectra differ per wavelength.
float eta_at(float nm) { return 0.2f + (nm - 360.f) / 470.f; }
float k_at(float nm) { return 3.5f - 1.5f * (nm - 360.f) / 470.f; }
tabulated::Brdf conductor_brdf(const TrowbridgeReitz& d) {
  return [d](const Vec3& wo, const Vec3& wi, float nm) {
    const Vec3 wm = glm::normalize(wo + wi);
    return d.D(wm) * fr_complex(glm::dot(wo, wm), eta_at(nm), k_at(nm)) * d.G(wo, wi) / (4.f * wo.z * wi.z);
  };
}
// The same BRDF at four of the file's wavelengths, as Lantern's conductor.
const std::array<float, 4> kNm = {420.f, 540.f, 600.f, 720.f};
ConductorBSDF analytic(const TrowbridgeReitz& d) {
  Spectrum eta, k;
  for (int i = 0; i < 4; ++i) eta[i] = eta_at(kNm[size_t(i)]), k[i] = k_at(kNm[size_t(i)]);
  return ConductorBSDF{d, eta, k, Spectrum(1.f), false};
}

struct Tabulated {
  TrowbridgeReitz d;
  std::shared_ptr<const MeasuredBRDF> brdf;
  MeasuredBSDF bsdf() const { return MeasuredBSDF{brdf.get(), kNm}; }
};
Tabulated tabulate(const TrowbridgeReitz& d, int phi_i, const std::string& name) {
  tabulated::Grid g;
  g.phi_i = phi_i;
  const fs::path path = temp_dir() / name;
  tabulated::write_file(path.string(), tabulated::file_bytes(d, conductor_brdf(d), g));
  return {d, MeasuredBRDF::load(path.string())};
}
const Tabulated& isotropic() {
  static const Tabulated t = tabulate({0.3f, 0.3f}, 1, "iso.bsdf");
  return t;
}
const Tabulated& anisotropic() {
  static const Tabulated t = tabulate({0.2f, 0.45f}, 13, "aniso.bsdf");
  return t;
}

// f against the analytic BRDF over directions up to 80 degrees from the
// normal, where the BRDF is not tiny: the grids' interpolation error only.
TEST(MeasuredBSDF, ValuesMatchTheBRDFTheyTabulate) {
  for (const Tabulated* t : {&isotropic(), &anisotropic()}) {
    const MeasuredBSDF m = t->bsdf();
    const ConductorBSDF c = analytic(t->d);
    RandomStream s = RandomStream::make(2, 0, 0);
    std::vector<float> errors;
    for (int i = 0; errors.size() < 4000 && i < 1000000; ++i) {
      const Vec3 wo = bsdf_checks::dir_from_angles(80.f * s.get1d(), 360.f * s.get1d());
      const Vec3 wi = bsdf_checks::dir_from_angles(80.f * s.get1d(), 360.f * s.get1d());
      const Spectrum a = c.f(wo, wi, TransportMode::Radiance), b = m.f(wo, wi, TransportMode::Radiance);
      if (a[0] < 0.05f) continue;
      for (int k = 0; k < 4; ++k) errors.push_back(std::fabs(b[k] / a[k] - 1.f));
    }
    std::sort(errors.begin(), errors.end());
    EXPECT_LT(errors[errors.size() / 2], 0.01f) << "median, " << (t == &isotropic() ? "isotropic" : "anisotropic");
    EXPECT_LT(errors[errors.size() * 9 / 10], 0.04f) << "90th percentile";
    // Mirrored below the surface (two-sided), zero across it.
    const Vec3 wo = bsdf_checks::dir_from_angles(30.f, 10.f), wi = bsdf_checks::dir_from_angles(40.f, 200.f);
    EXPECT_EQ(m.f(-wo, -wi, TransportMode::Radiance)[1], m.f(wo, wi, TransportMode::Radiance)[1]);
    EXPECT_EQ(m.f(wo, -wi, TransportMode::Radiance)[1], 0.f);
  }
}

// The directional albedo per wavelength, by sampling, against the analytic
// BRDF's: within 1.5% from head-on to 75 degrees.
TEST(MeasuredBSDF, AlbedoMatchesTheAnalyticBRDF) {
  // (SamplesFollowTheirDensity runs the same sampling under the sanitizers.)
  if (LANTERN_ASAN) GTEST_SKIP() << "statistics only: the Release suite runs it";
  auto albedo = [](const auto& bsdf, const Vec3& wo, int seed) {
    RandomStream s = RandomStream::make(uint64_t(seed), 0, 0);
    Spectrum sum(0.f);
    const int n = 100000;
    for (int i = 0; i < n; ++i)
      if (auto bs = bsdf.sample_f(wo, s.get1d(), s.get2d(), TransportMode::Radiance); bs && bs->pdf > 0.f)
        sum += bs->f * (std::fabs(bs->wi.z) / bs->pdf);
    return sum / float(n);
  };
  for (const Tabulated* t : {&isotropic(), &anisotropic()})
    for (float theta : {0.f, 30.f, 60.f, 75.f}) {
      const Vec3 wo = bsdf_checks::dir_from_angles(theta, 25.f);
      const Spectrum a = albedo(analytic(t->d), wo, 1), b = albedo(t->bsdf(), wo, 2);
      for (int k = 0; k < 4; ++k)
        EXPECT_NEAR(b[k], a[k], 0.015f * a[k] + 0.005f) << "theta " << theta << ", wavelength " << k;
    }
}

TEST(MeasuredBSDF, SamplesFollowTheirDensity) {
  for (const Tabulated* t : {&isotropic(), &anisotropic()})
    for (float theta : {0.f, 45.f, 75.f}) {
      const Vec3 wo = bsdf_checks::dir_from_angles(theta, 60.f);
      bsdf_checks::expect_sampling_matches_pdf(t->bsdf(), wo, TransportMode::Radiance,
                                               "theta " + std::to_string(theta));
      RandomStream s = RandomStream::make(4, 0, 0);
      for (int i = 0; i < 200; ++i) {
        auto bs = t->bsdf().sample_f(wo, s.get1d(), s.get2d(), TransportMode::Radiance);
        if (!bs) continue;
        EXPECT_NEAR(t->bsdf().pdf(wo, bs->wi, TransportMode::Radiance), bs->pdf, 2e-3f * bs->pdf);
        EXPECT_NEAR(t->bsdf().f(wo, bs->wi, TransportMode::Radiance)[2], bs->f[2], 2e-3f * bs->f[2]);
      }
    }
}

// The RGB renderer reads each tabulated spectrum as a reflectance under
// white light: a file whose spectra are the same at every wavelength gives
// that value in every channel.
TEST(MeasuredBSDF, RgbRendererReadsTheSpectraAsColour) {
  const TrowbridgeReitz d{0.3f, 0.3f};
  const ConductorBSDF grey{d, Spectrum(0.5f), Spectrum(3.f), Spectrum(1.f), false};
  const tabulated::Brdf f = [&](const Vec3& wo, const Vec3& wi, float) {
    return grey.f(wo, wi, TransportMode::Radiance)[0];
  };
  const fs::path path = temp_dir() / "grey.bsdf";
  tabulated::write_file(path.string(), tabulated::file_bytes(d, f, {}));
  const auto brdf = MeasuredBRDF::load(path.string());
  const MeasuredBSDF rgb{brdf.get(), {}}, spectral{brdf.get(), kNm};
  const Vec3 wo = bsdf_checks::dir_from_angles(35.f, 0.f), wi = bsdf_checks::dir_from_angles(20.f, 170.f);
  const Spectrum a = rgb.f(wo, wi, TransportMode::Radiance), b = spectral.f(wo, wi, TransportMode::Radiance);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(a[c], b[0], 1e-3f * b[0]) << c;
}

TEST(MeasuredBSDF, BadFilesAreClearErrors) {
  const fs::path dir = temp_dir();
  auto load_error = [&](const std::vector<uint8_t>& bytes, const std::string& name) {
    tabulated::write_file((dir / name).string(), bytes);
    try {
      MeasuredBRDF::load((dir / name).string());
    } catch (const std::runtime_error& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  const std::vector<uint8_t> good = tabulated::file_bytes({0.3f, 0.3f}, conductor_brdf({0.3f, 0.3f}), {});
  EXPECT_NE(load_error({'n', 'o', 'p', 'e'}, "a.bsdf").find("not a tensor file"), std::string::npos);
  std::vector<uint8_t> truncated(good.begin(), good.begin() + 40);
  EXPECT_NE(load_error(truncated, "b.bsdf").find("ends inside"), std::string::npos);
  std::vector<uint8_t> short_data(good.begin(), good.end() - 100);
  EXPECT_NE(load_error(short_data, "c.bsdf").find("past the end of the file"), std::string::npos);
  std::vector<uint8_t> version = good;
  version[12] = 2;
  EXPECT_NE(load_error(version, "d.bsdf").find("version 2.0 (expected 1.0)"), std::string::npos);
  using T = TensorFile::Type;
  const std::vector<uint8_t> missing = tensor_file_bytes({{"theta_i", T::Float32, {1}, {0, 0, 0, 0}}});
  EXPECT_NE(load_error(missing, "e.bsdf").find("no field \"phi_i\""), std::string::npos);
  // Through a scene: the file and line of the Material, and the problem.
  expect_load_error("WorldBegin\nMaterial \"measured\" \"string filename\" \"" + (dir / "c.bsdf").string() + "\"\n",
                    "m.pbrt", {"m.pbrt:2", "past the end"});
  expect_load_error("WorldBegin\nMaterial \"measured\"\n", "m.pbrt", {"m.pbrt:2", "needs a \"filename\""});
}

// A sphere of the tabulated conductor on a diffuse floor under an area
// light, with sampled wavelengths: the same image as pbrt's conductor with
// the analytic constants it tabulates (region means within 2% and noise),
// and path, bdpt, light tracing and vcm agree on it (measured: the
// conductor's regions within 1.1%).
TEST(MeasuredBSDF, RendersAsTheConductorItTabulates) {
  const TrowbridgeReitz d{0.3f, 0.3f};
  const ConductorBSDF grey{d, Spectrum(0.6f), Spectrum(2.5f), Spectrum(1.f), false};
  const fs::path file = temp_dir() / "sphere.bsdf";
  tabulated::write_file(
      file.string(),
      tabulated::file_bytes(
          d, [&](const Vec3& wo, const Vec3& wi, float) { return grey.f(wo, wi, TransportMode::Radiance)[0]; }, {}));
  auto scene_with = [&](const std::string& material) {
    return load_scene_from_string(tabulated::sphere_on_floor(material), "measured.pbrt", {});
  };
  auto measured = scene_with("Material \"measured\" \"string filename\" \"" + file.string() + "\"");
  auto conductor = scene_with(
      "Material \"conductor\" \"float eta\" 0.6 \"float k\" 2.5 \"float roughness\" 0.3 \"bool remaproughness\" false");
  // The sphere's upper and lower halves and the floor; not the sky around
  // the sphere's top, which light tracing cannot render: no light subpath
  // reaches the camera straight from a light at infinity.
  const std::vector<Region> regions = {{9, 5, 6, 4}, {8, 9, 8, 3}, {0, 12, 24, 4}};
  auto options = [](const char* integrator) {
    RenderOptions o;
    o.integrator = parse_integrator(integrator);
    o.spp = 64;
    o.maxdepth = 5;
    o.spectral = true;
    return o;
  };
  const RegionStats ref = stats_of(render_runs(*conductor, options("path"), 4, 1), regions);
  const RegionStats path = stats_of(render_runs(*measured, options("path"), 4, 11), regions);
  expect_means_agree(ref, path, 0.02, "measured against conductor");
  for (const char* integrator : {"bdpt", "lt", "vcm"}) {
    const RegionStats other = stats_of(render_runs(*measured, options(integrator), 4, 21), regions);
    expect_means_agree(path, other, 0.02, integrator);
  }
}

}  // namespace
}  // namespace lantern
