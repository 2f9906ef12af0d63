// Dispersion: the named glasses against their catalogue, a prism that
// spreads a white line into a spectrum where Snell's law puts each
// wavelength, and the estimators agreeing where light crosses dispersive
// glass and a medium.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <optional>
#include <string>

#include "color/cie1931.h"
#include "color/glass.h"
#include "color/spectrum_conversion.h"
#include "integrator/dispersion.h"
#include "lantern/render.h"
#include "lantern/scene.h"
#include "sanitizer.h"
#include "stat_compare.h"

namespace lantern {
namespace {

// n_d and the Abbe number V_d = (n_d - 1) / (n_F - n_C) that the SCHOTT
// catalogue lists for each glass (F: 486.1327 nm, C: 656.2725 nm), from
// the Sellmeier coefficients: a wrong digit in a coefficient shows here.
TEST(Dispersion, NamedGlassesMatchTheirCatalogue) {
  struct Listed {
    const char* name;
    double n_d, v_d;
  };
  const Listed listed[] = {{"glass-BK7", 1.51680, 64.17},  {"glass-BAF10", 1.67003, 47.11}, {"glass-FK51A", 1.48656, 84.47},
                           {"glass-LASF9", 1.85025, 32.17}, {"glass-F5", 1.67271, 32.25},   {"glass-F10", 1.72828, 28.53},
                           {"glass-F11", 1.78472, 25.68}};
  for (const Listed& g : listed) {
    const std::optional<SellmeierGlass> glass = named_glass(g.name);
    ASSERT_TRUE(glass) << g.name;
    const double n_d = glass->index(kHeliumDLine);
    EXPECT_NEAR(n_d, g.n_d, 1e-5) << g.name;
    EXPECT_NEAR((n_d - 1.0) / (glass->index(486.1327) - glass->index(656.2725)), g.v_d, 0.01) << g.name;
    EXPECT_GT(glass->index(400.0), glass->index(700.0)) << g.name << ": normal dispersion";
  }
  EXPECT_FALSE(named_glass("glass-XYZ"));
}

// A throughput reduced to its first wavelength (integrator/dispersion.h)
// is, on the film, what pbrt-v4's terminated wavelengths make of it.
TEST(Dispersion, ReducedThroughputIsTerminatedWavelengths) {
  for (float u : {0.05f, 0.37f, 0.81f}) {
    const SampledWavelengths l = SampledWavelengths::sample_visible(u);
    SampledWavelengths terminated = l;
    terminated.terminate_secondary();
    const Spectrum s(0.7f, 0.2f, 1.3f, 0.4f);
    const RGB a = film_rgb(first_wavelength_only(s), l), b = film_rgb(s, terminated);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(a[c], b[c], 1e-5f * std::fabs(b[c]) + 1e-7f) << u << " " << c;
  }
  EXPECT_EQ(joined_dispersion(true, true), 1.f / float(kSpectrumSamples));
  EXPECT_EQ(joined_dispersion(true, false), 1.f);
}

// --- The prism ------------------------------------------------------------
//
// A camera at the origin looks along +z through a 40-degree prism of SF11
// (glass-F11), its edges vertical, at a thin vertical white line that it
// can see only through the prism. Each wavelength is refracted by its own
// index, so the line shows as a spectrum across the image. Everything
// happens in the horizontal plane; a ray of the middle rows is traced here
// in two dimensions, (x, z), by Snell's law and the Fresnel equations.

struct V2 {
  double x, z;
};
V2 operator+(V2 a, V2 b) { return {a.x + b.x, a.z + b.z}; }
V2 operator-(V2 a, V2 b) { return {a.x - b.x, a.z - b.z}; }
V2 operator*(double s, V2 a) { return {s * a.x, s * a.z}; }
double dot(V2 a, V2 b) { return a.x * b.x + a.z * b.z; }
V2 unit(V2 a) { return (1.0 / std::sqrt(dot(a, a))) * a; }

const double kHalfApex = 20.0 * M_PI / 180.0;
const V2 kApex{1.0, 3.0}, kBaseNear{-1.0, 3.0 - 2.0 * std::tan(kHalfApex)}, kBaseFar{-1.0, 3.0 + 2.0 * std::tan(kHalfApex)};
constexpr int kWidth = 400, kHeight = 40;
constexpr double kFovDegrees = 4.0;  // across the shorter side, the height
const double kTanHalfX = std::tan(kFovDegrees * M_PI / 360.0) * double(kWidth) / double(kHeight);
constexpr double kLineDistance = 10.0, kLineHalfWidth = 0.02;

// Unpolarised Fresnel transmittance from a medium of index n1 into n2.
double fresnel_transmittance(double cos_i, double n1, double n2) {
  const double sin_t = n1 / n2 * std::sqrt(std::max(0.0, 1.0 - cos_i * cos_i));
  if (sin_t >= 1.0) return 0.0;
  const double cos_t = std::sqrt(1.0 - sin_t * sin_t);
  const double rs = (n1 * cos_i - n2 * cos_t) / (n1 * cos_i + n2 * cos_t);
  const double rp = (n2 * cos_i - n1 * cos_t) / (n2 * cos_i + n1 * cos_t);
  return 1.0 - 0.5 * (rs * rs + rp * rp);
}

// Refraction of unit d at a surface of unit normal m facing against it,
// from index n1 into n2; nothing on total internal reflection.
std::optional<V2> refract(V2 d, V2 m, double n1, double n2) {
  const double eta = n1 / n2, c = -dot(d, m), k = 1.0 - eta * eta * (1.0 - c * c);
  if (k < 0.0) return std::nullopt;
  return unit(eta * d + (eta * c - std::sqrt(k)) * m);
}

// Where ray o + t d meets segment [a, b] (t > 0), if it does.
std::optional<double> meet(V2 o, V2 d, V2 a, V2 b) {
  const V2 e = b - a, r = a - o;
  const double den = d.z * e.x - d.x * e.z;
  if (std::fabs(den) < 1e-15) return std::nullopt;
  const double t = (r.z * e.x - r.x * e.z) / den, s = (r.z * d.x - r.x * d.z) / den;
  if (t > 1e-9 && s >= 0.0 && s <= 1.0) return t;
  return std::nullopt;
}

struct Exit {
  V2 p, d;
  double transmittance;  // both faces' Fresnel factors
};

// Ray o + t d into the prism through one face and out through another.
std::optional<Exit> through_prism(V2 o, V2 d, double n) {
  const V2 corner[3] = {kApex, kBaseNear, kBaseFar};
  const V2 centre = (1.0 / 3.0) * (kApex + kBaseNear + kBaseFar);
  double T = 1.0;
  for (int crossing = 0; crossing < 2; ++crossing) {
    std::optional<double> t;
    V2 outward{};
    for (int e = 0; e < 3; ++e) {
      const V2 a = corner[e], b = corner[(e + 1) % 3];
      const auto te = meet(o, d, a, b);
      if (te && (!t || *te < *t)) {
        t = te;
        outward = unit({b.z - a.z, a.x - b.x});
        if (dot(outward, a - centre) < 0.0) outward = -1.0 * outward;
      }
    }
    if (!t) return std::nullopt;
    const double n1 = crossing == 0 ? 1.0 : n, n2 = crossing == 0 ? n : 1.0;
    const V2 facing = dot(outward, d) < 0.0 ? outward : -1.0 * outward;
    const auto refracted = refract(d, facing, n1, n2);
    if (!refracted) return std::nullopt;
    T *= fresnel_transmittance(std::fabs(dot(d, outward)), n1, n2);
    o = o + *t * d;
    d = *refracted;
  }
  return Exit{o, d, T};
}
// The camera ray through screen position sx (x over z).
std::optional<Exit> through_prism(double sx, double n) { return through_prism({0.0, 0.0}, unit({sx, 1.0}), n); }

struct Line {
  V2 centre, along;  // its middle and the unit direction across it
};

// The line: kLineDistance beyond the prism along the d-line ray through
// the middle of the image, facing it.
Line line_placement() {
  const double n_d = named_glass("glass-F11")->index(kHeliumDLine);
  const Exit e = *through_prism(0.0, n_d);
  return {e.p + kLineDistance * e.d, {e.d.z, -e.d.x}};
}

// The film column (raster x) of screen position sx.
double column(double sx) { return (sx / kTanHalfX + 1.0) * 0.5 * double(kWidth); }

// The column at which the camera sees the point `u` across the line, for
// index n: the offset the exit ray meets the line's plane at decreases
// along the image, so bisection finds it.
double column_seeing(double u, double n, const Line& line) {
  auto offset = [&](double sx) {
    const Exit e = *through_prism(sx, n);
    const double t = dot(line.centre - e.p, {-line.along.z, line.along.x}) / dot(e.d, {-line.along.z, line.along.x});
    return dot(e.p + t * e.d - line.centre, line.along);
  };
  double lo = -0.25 * kTanHalfX, hi = 0.25 * kTanHalfX;
  const bool rising = offset(hi) > offset(lo);
  for (int i = 0; i < 100; ++i) {
    const double mid = 0.5 * (lo + hi);
    ((offset(mid) < u) == rising ? lo : hi) = mid;
  }
  return column(0.5 * (lo + hi));
}

std::string prism_scene(const Line& line) {
  const double degrees = std::atan2(line.along.z, line.along.x) * 180.0 / M_PI;  // the quad's x axis to `along`
  char buf[2048];
  std::snprintf(buf, sizeof buf, R"(LookAt 0 0 0  0 0 1  0 1 0
Camera "perspective" "float fov" %g
Sampler "independent"
PixelFilter "box"
Film "rgb" "integer xresolution" %d "integer yresolution" %d
WorldBegin
AttributeBegin
  Material "dielectric" "spectrum eta" "glass-F11"
  Shape "trianglemesh" "point3 P" [%.9g -1 %.9g  %.9g -1 %.9g  %.9g -1 %.9g  %.9g 1 %.9g  %.9g 1 %.9g  %.9g 1 %.9g]
    "integer indices" [0 2 1  3 4 5  0 1 4  0 4 3  0 5 2  0 3 5  1 5 4  1 2 5]
AttributeEnd
AttributeBegin
  AreaLightSource "diffuse" "rgb L" [1 1 1] "bool twosided" true
  Translate %.9g 0 %.9g
  Rotate %.9g 0 -1 0
  Shape "trianglemesh" "point3 P" [-%g -3 0  %g -3 0  %g 3 0  -%g 3 0] "integer indices" [0 1 2 0 2 3]
AttributeEnd
)",
                kFovDegrees, kWidth, kHeight, kApex.x, kApex.z, kBaseNear.x, kBaseNear.z, kBaseFar.x, kBaseFar.z,
                kApex.x, kApex.z, kBaseNear.x, kBaseNear.z, kBaseFar.x, kBaseFar.z, line.centre.x, line.centre.z,
                degrees, kLineHalfWidth, kLineHalfWidth, kLineHalfWidth, kLineHalfWidth);
  return buf;
}

// Per channel, the image's centroid along x (in raster units) and its sum.
struct Centroids {
  double x[3], sum[3];
};
Centroids centroids(const Image& img) {
  Centroids c{};
  for (int ch = 0; ch < 3; ++ch) {
    double m = 0.0, s = 0.0;
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x) {
        const double v = img.at(x, y)[ch];
        m += (x + 0.5) * v;
        s += v;
      }
    c.x[ch] = m / s;
    c.sum[ch] = s;
  }
  return c;
}

// The spectrum each channel of the film sees of the white line through
// the prism: per wavelength (1 nm), where the line lands (the middle of
// its two edges' columns), weighted by how wide it lands, by the prism's
// transmittance and by the light's spectrum (D65 for RGB white) times the
// channel's response (the CIE 1931 observer, then sRGB). The centroid of
// those weights is where the channel's image of the line lies. (A box
// filter and a line of any width keep a centroid exact: the box-filtered
// image's centroid is that of the light landing.)
TEST(Dispersion, PrismSpreadsWavelengthsAsSnellsLawSays) {
  const Line line = line_placement();
  const auto scene = load_scene_from_string(prism_scene(line), "prism.pbrt");
  const SellmeierGlass glass = *named_glass("glass-F11");
  double expected[3] = {}, weight[3] = {}, blue_edge = 1e9, red_edge = -1e9;
  for (int nm = 360; nm <= 830; ++nm) {
    const double n = glass.index(nm);
    const double a = column_seeing(-kLineHalfWidth, n, line), b = column_seeing(kLineHalfWidth, n, line);
    const double T = through_prism((0.5 * (a + b) / kWidth * 2.0 - 1.0) * kTanHalfX, n)->transmittance;
    const RGB response = xyz_to_linear_srgb(cie1931_cmf(float(nm))) * cie_d65(float(nm));
    for (int c = 0; c < 3; ++c) {
      const double w = std::fabs(b - a) * T * response[c];
      expected[c] += w * 0.5 * (a + b);
      weight[c] += w;
    }
    if (nm == 450) blue_edge = 0.5 * (a + b);
    if (nm == 650) red_edge = 0.5 * (a + b);
  }
  // The spread the test rests on: 450 and 650 nm land columns apart.
  EXPECT_GT(std::fabs(blue_edge - red_edge), 10.0);

  RenderOptions o;
  o.integrator = Integrator::Path;
  o.maxdepth = 3;
  o.spp = LANTERN_ASAN ? 32 : 128;
  o.spectral = true;
  const RenderResult spectral = render(*scene, o);
  EXPECT_EQ(spectral.stats.nonfinite_samples, 0u);
  // The noise of 128 samples moves a centroid by about 0.15 columns; the
  // sums above agree with 1024 samples within 0.12 (the rows off the
  // middle and the transmittance taken at the line's middle).
  const double tolerance = LANTERN_ASAN ? 1.0 : 0.5;
  const Centroids got = centroids(spectral.image);
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(got.x[c], expected[c] / weight[c], tolerance) << "channel " << c << " (columns)";
  // red is seen on the side that blue is not (all that RGB could tell)
  EXPECT_GT(std::fabs(got.x[0] - got.x[2]), 5.0);

  // Without sampled wavelengths the line is where the d line's index puts
  // it, one colour.
  o.spectral = false;
  const Centroids rgb = centroids(render(*scene, o).image);
  const double n_d = glass.index(kHeliumDLine);
  const double at_d = 0.5 * (column_seeing(-kLineHalfWidth, n_d, line) + column_seeing(kLineHalfWidth, n_d, line));
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(rgb.x[c], at_d, tolerance) << "channel " << c;
}

// The prism the other way round: a narrow spot light where the line was
// shines back through it onto a white screen, and a camera looks at the
// screen. Here only the light subpaths cross the glass (light tracing,
// bdpt's light-tracing strategy, vcm's merges): each wavelength lands
// where Snell's law sends the spot's axis, so each channel's centroid on
// the film is the response-weighted mean of those landing points as the
// camera sees them.
TEST(Dispersion, PrismCastsASpectrumWhereSnellsLawSays) {
  const Line line = line_placement();
  const double n_d = named_glass("glass-F11")->index(kHeliumDLine);
  const V2 aim = through_prism(0.0, n_d)->p;  // where the d line's ray left the prism
  constexpr int kW = 100, kH = 50;
  constexpr double kFov = 15.0, kScreenZ = -1.0;
  const double camera[3] = {0.0, 0.8, 1.5}, target[3] = {0.0, 0.0, kScreenZ};
  char buf[2048];
  std::snprintf(buf, sizeof buf, R"(LookAt %g %g %g  %g %g %g  0 1 0
Camera "perspective" "float fov" %g
Film "rgb" "integer xresolution" %d "integer yresolution" %d
WorldBegin
LightSource "spot" "point3 from" [%.9g 0 %.9g] "point3 to" [%.9g 0 %.9g] "float coneangle" 0.4
  "float conedeltaangle" 0.1 "rgb I" [500 500 500]
AttributeBegin
  Material "dielectric" "spectrum eta" "glass-F11"
  Shape "trianglemesh" "point3 P" [%.9g -1 %.9g  %.9g -1 %.9g  %.9g -1 %.9g  %.9g 1 %.9g  %.9g 1 %.9g  %.9g 1 %.9g]
    "integer indices" [0 2 1  3 4 5  0 1 4  0 4 3  0 5 2  0 3 5  1 5 4  1 2 5]
AttributeEnd
Material "diffuse" "rgb reflectance" [0.8 0.8 0.8]
Shape "trianglemesh" "point3 P" [-2 -1 %g  2 -1 %g  2 1 %g  -2 1 %g] "integer indices" [0 1 2 0 2 3]
)",
                camera[0], camera[1], camera[2], target[0], target[1], target[2], kFov, kW, kH, line.centre.x,
                line.centre.z, aim.x, aim.z, kApex.x, kApex.z, kBaseNear.x, kBaseNear.z, kBaseFar.x, kBaseFar.z, kApex.x,
                kApex.z, kBaseNear.x, kBaseNear.z, kBaseFar.x, kBaseFar.z, kScreenZ, kScreenZ, kScreenZ, kScreenZ);
  const auto scene = load_scene_from_string(buf, "prism-spot.pbrt");

  // The film column of screen point (x, 0, kScreenZ): pbrt's LookAt frame
  // (right = up x forward) and a perspective projection.
  const double fx = target[0] - camera[0], fy = target[1] - camera[1], fz = target[2] - camera[2];
  const double fl = std::sqrt(fx * fx + fy * fy + fz * fz);
  const double f[3] = {fx / fl, fy / fl, fz / fl};
  const double rl = std::sqrt(f[2] * f[2] + f[0] * f[0]);
  const double r[3] = {f[2] / rl, 0.0, -f[0] / rl};  // (0, 1, 0) x f, normalised
  const double tan_half_x = std::tan(kFov * M_PI / 360.0) * double(kW) / double(kH);
  auto column_of = [&](double x) {
    const double p[3] = {x - camera[0], -camera[1], kScreenZ - camera[2]};
    const double xc = p[0] * r[0] + p[1] * r[1] + p[2] * r[2], zc = p[0] * f[0] + p[1] * f[1] + p[2] * f[2];
    return (xc / zc / tan_half_x + 1.0) * 0.5 * double(kW);
  };
  double expected[3] = {}, weight[3] = {};
  for (int nm = 360; nm <= 830; ++nm) {
    const std::optional<Exit> e = through_prism(line.centre, unit(aim - line.centre), named_glass("glass-F11")->index(nm));
    ASSERT_TRUE(e) << nm;
    const double x = e->p.x + (kScreenZ - e->p.z) / e->d.z * e->d.x;
    const RGB response = xyz_to_linear_srgb(cie1931_cmf(float(nm))) * cie_d65(float(nm));
    for (int c = 0; c < 3; ++c) {
      expected[c] += e->transmittance * response[c] * column_of(x);
      weight[c] += e->transmittance * response[c];
    }
  }
  for (const char* integrator : {"lt", "bdpt", "vcm"}) {
    RenderOptions o;
    o.integrator = parse_integrator(integrator);
    o.maxdepth = 4;
    o.spp = LANTERN_ASAN ? 4 : 16;
    o.spectral = true;
    // vcm's waves share one set of wavelengths: many small waves, many sets
    o.wave_size = 256;
    const Image image = render(*scene, o).image;
    o.threads = 1;  // and the same image with one thread as with all
    EXPECT_EQ(render(*scene, o).image.rgb, image.rgb) << integrator;
    const Centroids got = centroids(image);
    // Over seeds the light tracer's centroids spread by about 0.1 columns
    // and vcm's by 0.4 (a few hundred sets of wavelengths); red and blue
    // lie 10 columns apart.
    const double tolerance = (o.integrator == Integrator::Vcm ? 0.8 : 0.3) * (LANTERN_ASAN ? 2.0 : 1.0);
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(got.x[c], expected[c] / weight[c], tolerance) << integrator << ", channel " << c << " (columns)";
  }
}

// Light from above through a ball of rough dispersive glass (SF11) that
// holds a hazy medium, onto a floor under a dispersive coat (BAF10): the path tracer, bdpt and the
// light tracer agree within 5 standard errors over 16 runs, and vcm with
// bdpt within 1% more (its merges' blur), as in spectral_test.cpp. Rough
// glass is where both subpaths of a connection can have scattered at the
// glass already (each reduced to its first wavelength: the factor must
// count once).
TEST(Dispersion, IntegratorsAgreeThroughDispersiveGlassAndMedia) {
  if (LANTERN_ASAN) GTEST_SKIP() << "the Release suite runs it";
  const auto scene = load_scene_from_string(R"(
LookAt 0 3 -4  0 0.5 0  0 1 0
Camera "perspective" "float fov" 45
Film "rgb" "integer xresolution" 32 "integer yresolution" 32
WorldBegin
AttributeBegin
  AreaLightSource "diffuse" "rgb L" [6 6 6]
  Translate 0 3 0.5
  Rotate 90 1 0 0
  Shape "disk" "float radius" 0.6
AttributeEnd
Material "coateddiffuse" "rgb reflectance" [0.7 0.5 0.3] "spectrum eta" "glass-BAF10" "float roughness" 0.2
Shape "trianglemesh" "point3 P" [-4 0 -4  4 0 -4  4 0 4  -4 0 4] "integer indices" [0 1 2 0 2 3]
MakeNamedMedium "haze" "string type" "homogeneous" "rgb sigma_a" [0.1 0.3 0.6] "rgb sigma_s" [0.8 0.8 0.8]
AttributeBegin
  MediumInterface "haze" ""
  Material "dielectric" "spectrum eta" "glass-F11" "float roughness" 0.15
  Translate 0 0.8 0
  Shape "sphere" "float radius" 0.7
AttributeEnd
)",
                                            "dispersive-glass.pbrt");
  const std::vector<Region> regions = {{0, 0, 32, 32}, {10, 10, 12, 12}, {4, 22, 8, 8}, {20, 22, 8, 8}, {12, 24, 8, 8}};
  auto stats = [&](const char* integrator) {
    RenderOptions o;
    o.integrator = parse_integrator(integrator);
    o.spp = 16;
    o.maxdepth = 6;
    o.spectral = true;
    return stats_of(render_runs(*scene, o, 16, 2000), regions);
  };
  const RegionStats path = stats("path"), bdpt = stats("bdpt");
  EXPECT_LT(max_z(bdpt, path), 5.0);
  EXPECT_LT(max_z(stats("lt"), path), 5.0);
  expect_means_agree(bdpt, stats("vcm"), 0.01, "vcm against bdpt");
}

}  // namespace
}  // namespace lantern
