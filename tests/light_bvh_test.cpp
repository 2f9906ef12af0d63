// The light samplers on a scene of many small lights of every kind: the
// probability each reports for a light is the frequency with which it
// chooses it, the probabilities sum to one, a light gets probability zero
// only where it cannot light the point, and renders with the BVH agree in
// the mean with power sampling and with bdpt, with less variance.
#include "light/light_bvh.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "lantern/render.h"
#include "lantern/scene.h"
#include "light/light_sampler.h"
#include "math/rng.h"
#include "scene/scene.h"
#include "stat_compare.h"

namespace lantern {
namespace {

// A floor and a back wall lit by a 6 x 4 grid of small one-sided quads
// facing down at several heights and colours, two sphere lights, a point
// light, a spot light, a distant light and a dim sky. The point light is
// out of view: the light tracer would show it as a dot, which camera rays
// cannot find.
std::string many_lights_scene(int resolution, bool at_infinity = true) {
  // World space: the tests place reference points in world coordinates.
  std::string s = "Option \"string renderingcoordinatesystem\" \"world\"\nLookAt 0 5 -9  0 0.5 0  0 1 0\nCamera \"perspective\" \"float fov\" [ 50 ]\n";
  s += "Film \"rgb\" \"integer xresolution\" [ " + std::to_string(resolution) + " ] \"integer yresolution\" [ " +
       std::to_string(resolution) + " ]\nWorldBegin\n";
  if (at_infinity) {
    s += "LightSource \"infinite\" \"rgb L\" [ 0.02 0.03 0.05 ]\n";
    s += "LightSource \"distant\" \"point3 from\" [ 1 3 -1 ] \"point3 to\" [ 0 0 0 ] \"rgb L\" [ 0.1 0.1 0.08 ]\n";
  }
  s += "LightSource \"point\" \"point3 from\" [ -6 1.5 0.5 ] \"rgb I\" [ 0.8 0.5 0.3 ]\n";
  s += "LightSource \"spot\" \"point3 from\" [ 3 3 -2 ] \"point3 to\" [ 2 0 1 ] \"float coneangle\" [ 20 ] "
       "\"float conedeltaangle\" [ 5 ] \"rgb I\" [ 3 3 4 ]\n";
  s += "Material \"diffuse\" \"rgb reflectance\" [ 0.5 0.5 0.5 ]\n";
  s += "Shape \"trianglemesh\" \"point3 P\" [ -8 0 -8  8 0 -8  8 0 8  -8 0 8 ] \"integer indices\" [ 0 1 2 0 2 3 ]\n";
  s += "Shape \"trianglemesh\" \"point3 P\" [ -8 0 4  8 0 4  8 6 4  -8 6 4 ] \"integer indices\" [ 0 1 2 0 2 3 ]\n";
  char buf[512];
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 4; ++j) {
      const float x = -6.25f + 2.5f * float(i), z = -3.f + 2.1f * float(j), y = 0.3f + 0.15f * float((i + j) % 4);
      const float h = 0.12f;
      std::snprintf(buf, sizeof buf,
                    "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [ %g %g %g ]\n"
                    "Shape \"trianglemesh\" \"point3 P\" [ %g %g %g  %g %g %g  %g %g %g  %g %g %g ] "
                    "\"integer indices\" [ 0 1 2 0 2 3 ]\nAttributeEnd\n",
                    4.0 + 3.0 * (i % 3), 3.0 + 2.0 * (j % 2), 2.0 + 4.0 * ((i + j) % 2), x - h, y, z - h, x + h, y,
                    z - h, x + h, y, z + h, x - h, y, z + h);  // wound to face down
      s += buf;
    }
  s += "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [ 3 2 1 ]\nTranslate -1 2 2\n"
       "Shape \"sphere\" \"float radius\" [ 0.2 ]\nAttributeEnd\n";
  s += "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [ 1 2 3 ] \"bool twosided\" [ true ]\nTranslate 2.5 0.4 0\n"
       "Shape \"sphere\" \"float radius\" [ 0.1 ]\nAttributeEnd\n";
  return s;
}

Vec3 random_unit_vector(RandomStream& r) {
  Vec2 u = r.get2d();
  float z = 1.f - 2.f * u.x, s = safe_sqrt(1.f - z * z), phi = 2.f * kPi * u.y;
  return Vec3(s * std::cos(phi), s * std::sin(phi), z);
}

// Shading points in and around the lit region, some with no normal.
std::vector<std::pair<Vec3, Vec3>> shading_points(int count) {
  RandomStream r = RandomStream::make(5, 6, 7);
  std::vector<std::pair<Vec3, Vec3>> pts;
  for (int k = 0; k < count; ++k) {
    Vec2 a = r.get2d(), b = r.get2d();
    Vec3 p(-6.f + 12.f * a.x, 2.5f * a.y, -5.f + 9.f * b.x);
    if (k % 5 == 0) p.y = 0.f;  // on the floor
    Vec3 n = k % 7 == 3 ? Vec3(0.f) : (k % 5 == 0 ? Vec3(0, 1, 0) : random_unit_vector(r));
    pts.push_back({p, n});
  }
  return pts;
}

// With the BVH a descent can end in a node whose children both have
// importance zero (their bounds are tighter than the node's): the sample
// then fails, and the probabilities sum to one minus that chance. It is
// unbiased, since no light in such a node can reach the point (checked
// below); power and uniform selection always choose.
TEST(LightSampler, ProbabilitiesSumToOneAndMatchSampledFrequencies) {
  auto scene = load_scene_from_string(many_lights_scene(16), "many.pbrt");
  const size_t n = scene->lights.all.size();
  ASSERT_EQ(n, 2u * 24u + 2u + 4u);  // two triangles per quad
  for (LightSamplerKind kind : {LightSamplerKind::Bvh, LightSamplerKind::Power, LightSamplerKind::Uniform}) {
    LightSampler sampler(scene->lights, scene->shapes, scene->textures, kind);
    for (const auto& [p, nrm] : shading_points(40)) {
      std::vector<double> pmf(n);
      double sum = 0.0;
      for (uint32_t l = 0; l < n; ++l) sum += pmf[l] = sampler.pmf(p, nrm, l);
      // Stratified u: the frequencies match the pmf up to the strata's
      // granularity, 1/N per boundary crossed along the descent.
      const int N = 20000;
      std::vector<int> count(n, 0);
      int failed = 0;
      for (int k = 0; k < N; ++k) {
        uint32_t light;
        float q;
        if (!sampler.sample(p, nrm, (float(k) + 0.5f) / float(N), &light, &q)) {
          ++failed;
          continue;
        }
        ASSERT_EQ(q, sampler.pmf(p, nrm, light)) << "the pmf a sample reports is the pmf of its light";
        ++count[light];
      }
      if (kind != LightSamplerKind::Bvh) EXPECT_EQ(failed, 0);
      EXPECT_NEAR(sum + double(failed) / N, 1.0, 64.0 / N) << name(kind);
      for (uint32_t l = 0; l < n; ++l)
        EXPECT_NEAR(double(count[l]) / N, pmf[l], 64.0 / N) << name(kind) << " light " << l;
    }
  }
}

// Probability zero exactly where the light sends nothing to the point: a
// one-sided quad seen from behind, a point outside a spot's cone. A light
// behind the receiving surface keeps its probability (the surface may
// transmit). The constant sky is never chosen (BSDF sampling finds it; see
// light_sampler.h), and that is the only exception.
TEST(LightSampler, ZeroProbabilityOnlyWhereTheLightCannotReach) {
  auto scene = load_scene_from_string(many_lights_scene(16), "many.pbrt");
  const LightPools& L = scene->lights;
  LightSampler sampler(L, scene->shapes, scene->textures, LightSamplerKind::Bvh);
  RandomStream r = RandomStream::make(1, 2, 3);
  int zeros = 0, behind_surface = 0;
  for (const auto& [p, nrm] : shading_points(200)) {
    for (uint32_t l = 0; l < L.all.size(); ++l) {
      if (L.all[l].kind == LightKind::Infinite && L.infinite[L.all[l].index].image < 0) {
        EXPECT_EQ(sampler.pmf(p, nrm, l), 0.f);
        continue;
      }
      if (sampler.pmf(p, nrm, l) > 0.f) {
        const LightKind k = L.all[l].kind;
        if (nrm != Vec3(0.f) && k == LightKind::Point && glm::dot(L.point[L.all[l].index].p - p, nrm) < 0.f)
          ++behind_surface;
        continue;
      }
      ++zeros;
      for (int k = 0; k < 64; ++k) {
        auto ls = sample_light_from(L, scene->shapes, scene->textures, l, p, r.get2d(), SampledWavelengths::rgb());
        if (!ls) continue;
        const bool grazing = nrm != Vec3(0.f) && glm::dot(nrm, ls->wi) == 0.f;
        EXPECT_TRUE(is_black(ls->L) || grazing) << "light " << l << " has probability 0 at (" << p.x << ", " << p.y
                                                << ", " << p.z << ") but sends light there";
      }
    }
  }
  std::printf("  %d zero probabilities checked; the point light behind the surface kept its probability %d times\n",
              zeros, behind_surface);
  EXPECT_GT(zeros, 100);
  EXPECT_GT(behind_surface, 10);
}

constexpr double kBvhMaxZ = 5.0;  // as in bdpt_test.cpp
const std::vector<Region> kBvhRegions = {{0, 0, 32, 32}, {0, 0, 16, 16}, {16, 0, 16, 16},
                                      {0, 16, 16, 16}, {16, 16, 16, 16}, {12, 20, 8, 8}};

RegionStats many_light_stats(const Scene& scene, const char* integrator, const char* light_sampler, int spp,
                             int runs) {
  RenderOptions o;
  o.integrator = parse_integrator(integrator);
  o.light_sampler = parse_light_sampler(light_sampler);
  o.spp = spp;
  o.maxdepth = 4;
  return stats_of(render_runs(scene, o, runs, 300), kBvhRegions);
}

// The BVH changes which light is sampled, never the expected image: path
// with bvh, power and uniform selection, bdpt (s = 1 and every MIS weight
// with the BVH's probabilities) and the light tracer agree.
TEST(LightSampler, BvhAgreesWithPowerAndBdpt) {
  auto scene = load_scene_from_string(many_lights_scene(32), "many.pbrt");
  const int runs = 12;
  auto path_bvh = many_light_stats(*scene, "path", "bvh", 16, runs);
  auto path_power = many_light_stats(*scene, "path", "power", 16, runs);
  auto path_uniform = many_light_stats(*scene, "path", "uniform", 16, runs);
  auto bdpt_bvh = many_light_stats(*scene, "bdpt", "bvh", 8, runs);
  auto lt = many_light_stats(*scene, "lt", "bvh", 16, runs);
  EXPECT_LT(max_z(path_power, path_bvh), kBvhMaxZ);
  EXPECT_LT(max_z(path_uniform, path_bvh), kBvhMaxZ);
  EXPECT_LT(max_z(bdpt_bvh, path_bvh), kBvhMaxZ);
  EXPECT_LT(max_z(lt, path_bvh), kBvhMaxZ);
}

// Relative variance of one-sample next-event estimates of the irradiance
// at points of the floor (visibility left out, so that only the choice of
// light differs), averaged over the points.
double irradiance_relative_variance(const Scene& scene, LightSamplerKind kind) {
  LightSampler sampler(scene.lights, scene.shapes, scene.textures, kind);
  RandomStream r = RandomStream::make(8, 9, 10);
  double sum = 0.0;
  const int points = 60, n = 4096;
  for (int k = 0; k < points; ++k) {
    Vec2 a = r.get2d();
    const Vec3 p(-7.f + 14.f * a.x, 0.f, -4.f + 8.f * a.y), nrm(0.f, 1.f, 0.f);
    double s = 0.0, s2 = 0.0;
    for (int i = 0; i < n; ++i) {
      auto ls = sample_light(scene.lights, scene.shapes, scene.textures, sampler, p, nrm, r.get1d(), r.get2d(),
                             SampledWavelengths::rgb());
      const double v = ls ? luminance(film_rgb(ls->L, SampledWavelengths::rgb())) * std::fmax(0.f, glm::dot(nrm, ls->wi)) / ls->pdf : 0.0;
      s += v, s2 += v * v;
    }
    const double mean = s / n;
    sum += (s2 / n - mean * mean) / (mean * mean);
  }
  return sum / points;
}

// The BVH's purpose: in a scene of many small lights, a point's light
// samples go to the lights that light it. Lights at infinity are left out
// here: with them pbrt-v4's rule gives the BVH only 1 / 3 of the samples.
TEST(LightSampler, BvhLowersTheVarianceOfNextEventEstimation) {
  auto scene = load_scene_from_string(many_lights_scene(16, false), "many-finite.pbrt");
  const double bvh = irradiance_relative_variance(*scene, LightSamplerKind::Bvh);
  const double power = irradiance_relative_variance(*scene, LightSamplerKind::Power);
  const double uniform = irradiance_relative_variance(*scene, LightSamplerKind::Uniform);
  std::printf("  relative variance of irradiance estimates: bvh %.3g, power %.3g, uniform %.3g\n", bvh, power, uniform);
  EXPECT_LT(bvh, 0.25 * power);
  EXPECT_LT(bvh, 0.25 * uniform);
}

// Lights spread to the ends of float's range: building the tree bins their
// centroids, and n (c - lo) overflowed before it was divided by the extent
// (a light's vertex at 3e38, found by mutating the Cornell box), giving a
// bucket far outside the array. The tree must hold every light, and what it
// reports must be probabilities: finite, summing to at most one, the one
// sample() gives the one pmf() gives. (Bounds that wide bound nothing: the
// lights near the point get no probability, and the BSDF's samples find
// them. An emitter that reaches so far has no finite area, and the scene
// refuses it: ExtremeGeometry.EmittersOfInfiniteAreaAreRejected.)
TEST(LightBvh, LightsAtTheEndsOfFloatsRangeBuildAndSample) {
  auto light_at = [](Vec3 lo, Vec3 hi) {
    LightBounds b;
    b.lo = lo, b.hi = hi, b.w = Vec3(0.f, -1.f, 0.f), b.phi = 1.f, b.cos_theta_o = 1.f, b.cos_theta_e = 0.f;
    return b;
  };
  for (float far : {3e37f, 3e38f}) {  // 12 x 3e37 overflows; 3e38's centroids do too
    SCOPED_TRACE(far);
    std::vector<LightBounds> bounds;
    for (int i = 0; i < 6; ++i) bounds.push_back(light_at(Vec3(float(i), 5.f, 0.f), Vec3(float(i) + 0.5f, 5.f, 0.5f)));
    bounds.push_back(light_at(Vec3(far, 5.f, 0.f), Vec3(far, 5.f, 1.f)));
    bounds.push_back(light_at(Vec3(-far, 5.f, 0.f), Vec3(-far, 5.f, 1.f)));
    bounds.push_back(light_at(Vec3(0.f, far, 0.f), Vec3(1.f, far, 1.f)));
    std::vector<uint32_t> ids(bounds.size());
    for (uint32_t i = 0; i < ids.size(); ++i) ids[i] = i;
    const LightBvh bvh(bounds, ids, ids.size());
    EXPECT_EQ(bvh.node_count(), 2 * bounds.size() - 1);
    const Vec3 p(2.f, 0.f, 0.2f), n(0.f, 1.f, 0.f);
    double total = 0.0;
    for (uint32_t i = 0; i < ids.size(); ++i) {
      const float pmf = bvh.pmf(p, n, i);
      EXPECT_TRUE(std::isfinite(pmf) && pmf >= 0.f && pmf <= 1.f) << i << ": " << pmf;
      total += pmf;
    }
    EXPECT_LE(total, 1.0 + 1e-5);
    int chosen = 0;
    for (float u : {0.f, 0.3f, 0.7f, 0.999f}) {
      uint32_t light = 0;
      float pmf = 0.f;
      if (bvh.sample(p, n, u, &light, &pmf)) EXPECT_FLOAT_EQ(pmf, bvh.pmf(p, n, light)), ++chosen;
    }
    EXPECT_EQ(chosen > 0, total > 0.0) << "sample() and pmf() disagree on whether any light can be chosen";
  }
}

}  // namespace
}  // namespace lantern
