// Sampling a triangle light by the solid angle it subtends
// (math/spherical_triangle.h): the solid angle against an independent
// formula, uniformity over sub-triangles, the projected solid angle against
// Lambert's closed form, and next-event estimation of a triangle light:
// its density where the estimator reads it, its mean against the closed
// form, and its variance against sampling by area.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "geometry/surface.h"
#include "lantern/scene.h"
#include "light/light_sampler.h"
#include "math/rng.h"
#include "math/sampling.h"
#include "math/spherical_triangle.h"
#include "scene/scene.h"

namespace lantern {
namespace {

using glm::dvec3;

// Van Oosterom & Strackee 1983: tan(omega / 2) = |a . (b x c)| /
// (1 + a.b + b.c + c.a), for unit vectors a, b, c.
double solid_angle_vos(const Vec3& p, const Vec3& v0, const Vec3& v1, const Vec3& v2) {
  const dvec3 a = glm::normalize(dvec3(v0) - dvec3(p)), b = glm::normalize(dvec3(v1) - dvec3(p)),
              c = glm::normalize(dvec3(v2) - dvec3(p));
  const double num = std::fabs(glm::dot(a, glm::cross(b, c)));
  return 2.0 * std::atan2(num, 1.0 + glm::dot(a, b) + glm::dot(b, c) + glm::dot(c, a));
}

// Lambert: the integral of n . w over the triangle's directions is half
// the sum over its edges of the edge's angle times n . the edge plane's
// unit normal (up to the sign the triangle's orientation gives).
double projected_solid_angle(const Vec3& p, const Vec3& n, const Vec3 v[3]) {
  double sum = 0.0;
  for (int i = 0; i < 3; ++i) {
    const dvec3 a = glm::normalize(dvec3(v[i]) - dvec3(p)), b = glm::normalize(dvec3(v[(i + 1) % 3]) - dvec3(p));
    const dvec3 g = glm::normalize(glm::cross(a, b));
    sum += std::acos(glm::clamp(glm::dot(a, b), -1.0, 1.0)) * glm::dot(dvec3(n), g);
  }
  return std::fabs(sum) / 2.0;
}

// Whether the ray from p along w crosses triangle v (Moller-Trumbore, with a
// small tolerance: a sample on an edge counts).
bool crosses(const Vec3& p, const Vec3& w, const Vec3& v0, const Vec3& v1, const Vec3& v2) {
  const dvec3 e1 = dvec3(v1 - v0), e2 = dvec3(v2 - v0), d(w), pv = glm::cross(d, e2);
  const double det = glm::dot(e1, pv);
  const dvec3 tv = dvec3(p - v0), qv = glm::cross(tv, e1);
  const double b1 = glm::dot(tv, pv) / det, b2 = glm::dot(d, qv) / det, t = glm::dot(e2, qv) / det;
  return t > 0.0 && b1 >= -1e-5 && b2 >= -1e-5 && b1 + b2 <= 1.0 + 1e-5;
}

TEST(SphericalTriangle, SolidAngleMatchesAnIndependentFormula) {
  const SphericalTriangle octant = spherical_triangle(Vec3(0.f), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1));
  EXPECT_NEAR(octant.solid_angle, kPi / 2.0, 1e-6);
  RandomStream r = RandomStream::make(1, 2, 3);
  for (int k = 0; k < 2000; ++k) {
    // Triangles of every size from p: from 1e-5 sr to almost a hemisphere.
    const float scale = std::pow(10.f, -3.f + 3.5f * r.get1d());
    const Vec3 c(0.f, 0.f, -1.f);
    Vec3 v[3];
    for (Vec3& x : v) x = c + scale * (Vec3(r.get1d(), r.get1d(), r.get1d()) - 0.5f) * Vec3(2.f, 2.f, 0.2f);
    const SphericalTriangle t = spherical_triangle(Vec3(0.f), v[0], v[1], v[2]);
    const double expected = solid_angle_vos(Vec3(0.f), v[0], v[1], v[2]);
    EXPECT_NEAR(t.solid_angle, expected, 1e-6 * expected + 1e-9) << "triangle " << k;
  }
  // Degenerate: p in the triangle's plane, or on a vertex.
  EXPECT_EQ(spherical_triangle(Vec3(0.f), Vec3(1, 0, 0), Vec3(2, 0, 0), Vec3(1, 1, 0)).solid_angle, 0.0);
  EXPECT_EQ(spherical_triangle(Vec3(1, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 1), Vec3(1, 1, 1)).solid_angle, 0.0);
}

// Directions land in the triangle, uniformly: the four sub-triangles of its
// midpoint subdivision receive samples in proportion to their solid angles
// (chi-square, 3 degrees of freedom), and the mean cosine to a normal
// gives Lambert's integral. Small, middling and huge triangles.
TEST(SphericalTriangle, SamplesAreUniformOverTheTriangle) {
  const Vec3 p(0.f), n = glm::normalize(Vec3(0.3f, 0.2f, -1.f));
  for (float size : {0.05f, 0.8f, 3.f, 60.f}) {
    const Vec3 v[3] = {Vec3(-size, -size, -1.f), Vec3(size, -0.5f * size, -1.f), Vec3(0.2f * size, size, -1.f)};
    const SphericalTriangle t = spherical_triangle(p, v[0], v[1], v[2]);
    ASSERT_GT(t.solid_angle, 0.0);
    const Vec3 m01 = 0.5f * (v[0] + v[1]), m12 = 0.5f * (v[1] + v[2]), m20 = 0.5f * (v[2] + v[0]);
    const Vec3 sub[4][3] = {{v[0], m01, m20}, {m01, v[1], m12}, {m20, m12, v[2]}, {m01, m12, m20}};
    const int n_samples = 200000;
    std::vector<int> count(4, 0);
    double cos_sum = 0.0;
    for (int i = 0; i < n_samples; ++i) {
      const Vec2 u((i + 0.5f) / n_samples, float(mix64(uint64_t(i)) >> 40) / float(1 << 24));
      const Vec3 w = sample_spherical_triangle(t, u);
      ASSERT_TRUE(crosses(p, w, v[0], v[1], v[2])) << "size " << size << " sample " << i;
      for (int s = 0; s < 4; ++s)
        if (crosses(p, w, sub[s][0], sub[s][1], sub[s][2])) {
          ++count[size_t(s)];
          break;
        }
      cos_sum += double(glm::dot(n, w));
    }
    double chi2 = 0.0;
    for (int s = 0; s < 4; ++s) {
      const double e = n_samples * solid_angle_vos(p, sub[s][0], sub[s][1], sub[s][2]) / t.solid_angle;
      chi2 += (count[size_t(s)] - e) * (count[size_t(s)] - e) / e;
    }
    EXPECT_LT(chi2, 16.3) << "size " << size;  // p = 0.001 for 3 degrees of freedom
    EXPECT_NEAR(cos_sum / n_samples * t.solid_angle, projected_solid_angle(p, n, v), 2e-3 * t.solid_angle)
        << "size " << size;
  }
}

// The square's point a direction came from is found again (so the cosine
// warp's density can be read from a direction), and the bilinear warp
// draws points with the density bilinear_pdf gives (chi-square over 8 x 8
// cells against the density integrated on a fine grid).
TEST(SphericalTriangle, InverseAndBilinearWarp) {
  RandomStream r = RandomStream::make(7, 8, 9);
  for (float size : {0.05f, 0.8f, 3.f, 60.f}) {
    const Vec3 v[3] = {Vec3(-size, -size, -1.f), Vec3(size, -0.5f * size, -1.f), Vec3(0.2f * size, size, -1.f)};
    const SphericalTriangle t = spherical_triangle(Vec3(0.f), v[0], v[1], v[2]);
    for (int i = 0; i < 2000; ++i) {
      const Vec2 u = r.get2d();
      const Vec2 back = invert_spherical_triangle(t, sample_spherical_triangle(t, u));
      EXPECT_NEAR(back.x, u.x, 2e-4f) << "size " << size;
      EXPECT_NEAR(back.y, u.y, 2e-4f) << "size " << size;
    }
  }
  const float w[4] = {0.05f, 1.f, 0.6f, 0.3f};
  const int cells = 8, n = 400000;
  std::vector<double> count(cells * cells, 0.0);
  for (int i = 0; i < n; ++i) {
    const Vec2 p = sample_bilinear(r.get2d(), w);
    ASSERT_TRUE(p.x >= 0.f && p.x < 1.f && p.y >= 0.f && p.y < 1.f);
    ++count[size_t(int(p.y * cells) * cells + int(p.x * cells))];
  }
  double chi2 = 0.0;
  for (int cy = 0; cy < cells; ++cy)
    for (int cx = 0; cx < cells; ++cx) {
      double mass = 0.0;
      for (int j = 0; j < 16; ++j)
        for (int k = 0; k < 16; ++k)
          mass += bilinear_pdf(Vec2((cx + (k + 0.5f) / 16.f) / cells, (cy + (j + 0.5f) / 16.f) / cells), w);
      const double e = n * mass / (16.0 * 16.0 * cells * cells);
      chi2 += (count[size_t(cy * cells + cx)] - e) * (count[size_t(cy * cells + cx)] - e) / e;
    }
  EXPECT_LT(chi2, 110.0);  // p = 0.001 for 63 degrees of freedom: 103.4
}

// One triangle light of radiance 2 (its emitting side facing -z).
const char* kTriangleLight = R"(
Option "string renderingcoordinatesystem" "world"
LookAt 0 0 5  0 0 0  0 1 0
Camera "perspective"
WorldBegin
AttributeBegin
  AreaLightSource "diffuse" "rgb L" [2 2 2]
  Shape "trianglemesh" "point3 P" [-1 -1 0  1 -1 0  0 1.2 0] "integer indices" [0 2 1]
AttributeEnd
)";

struct Estimate {
  double mean = 0.0, variance = 0.0;
};

// Next-event estimates of the irradiance at p (normal n), visibility left
// out: by the renderer's light sampling, or by area with the point's own
// density converted to solid angle (the estimator before solid-angle
// sampling, kept here as the reference to beat).
Estimate irradiance(const Scene& scene, const Vec3& p, const Vec3& n, bool by_area) {
  const LightSampler sampler(scene.lights, scene.shapes, scene.textures, LightSamplerKind::Power);
  RandomStream r = RandomStream::make(4, 5, 6);
  const int count = 100000;
  double s = 0.0, s2 = 0.0;
  for (int i = 0; i < count; ++i) {
    double v = 0.0;
    if (by_area) {
      const AreaLight& a = scene.lights.area[0];
      const SurfacePoint sp = sample_area_point(scene.shapes, a, r.get2d());
      const Vec3 d = sp.p - p;
      const float dist2 = glm::dot(d, d), cos_l = std::fabs(glm::dot(sp.ng, d)) / std::sqrt(dist2);
      const Vec3 wi = d / std::sqrt(dist2);
      const float pdf = dist2 * area_point_density(scene.shapes, a, sp.p, sp.ng) / cos_l;
      if (glm::dot(sp.ng, -wi) > 0.f) v = 2.0 * std::max(0.f, glm::dot(n, wi)) / pdf;
    } else {
      auto ls = sample_light(scene.lights, scene.shapes, scene.textures, sampler, p, n, r.get1d(), r.get2d(),
                             SampledWavelengths::rgb());
      if (ls) {
        // The density the estimator reads when a BSDF sample finds the same point.
        const float pdf = area_light_pdf(scene.lights, scene.shapes, sampler, 0, p, n, ls->p_light, ls->n_light);
        EXPECT_NEAR(pdf, ls->pdf, 1e-4f * ls->pdf);
        v = double(ls->L[0]) * std::max(0.f, glm::dot(n, ls->wi)) / ls->pdf;
      }
    }
    s += v;
    s2 += v * v;
  }
  Estimate e;
  e.mean = s / count;
  e.variance = s2 / count - e.mean * e.mean;
  return e;
}

TEST(SphericalTriangle, NextEventEstimationOfATriangleLight) {
  auto scene = load_scene_from_string(kTriangleLight, "triangle.pbrt");
  const Vec3 v[3] = {Vec3(-1, -1, 0), Vec3(1, -1, 0), Vec3(0, 1.2f, 0)};
  // Close (2.1 and 2.8 sr: sampled by solid angle, variance 24x and 66x
  // below sampling by area's), and far (0.015 sr: by area).
  struct Case {
    Vec3 p, n;
    bool spherical;
  };
  const Case cases[] = {{Vec3(0.3f, 0.f, -0.6f), glm::normalize(Vec3(0.5f, 0.f, 1.f)), true},
                        {Vec3(-0.4f, 0.2f, -0.25f), Vec3(0, 0, 1), true},
                        {Vec3(1.f, 0.f, -12.f), Vec3(0, 0, 1), false}};
  for (const Case& c : cases) {
    const SphericalTriangle t = spherical_triangle(c.p, v[0], v[1], v[2]);
    const double expected = 2.0 * projected_solid_angle(c.p, c.n, v);
    const Estimate ours = irradiance(*scene, c.p, c.n, false), area = irradiance(*scene, c.p, c.n, true);
    EXPECT_NEAR(ours.mean, expected, 5.0 * std::sqrt(ours.variance / 100000.0)) << "solid angle " << t.solid_angle;
    EXPECT_NEAR(area.mean, expected, 5.0 * std::sqrt(area.variance / 100000.0)) << "solid angle " << t.solid_angle;
    if (c.spherical) EXPECT_LT(ours.variance, 0.5 * area.variance) << "solid angle " << t.solid_angle;
    else EXPECT_NEAR(ours.variance, area.variance, 0.05 * area.variance) << "solid angle " << t.solid_angle;
  }
}

// At the extremes: points from 1e-5 to 1e5 light sizes away, in the
// light's plane, on its edges and vertices, with normals in every
// direction. A sample is either refused or finite, on the triangle, with
// the density area_light_pdf gives its point (to float precision).
TEST(SphericalTriangle, NextEventEstimationAtTheExtremes) {
  auto scene = load_scene_from_string(kTriangleLight, "triangle.pbrt");
  const LightSampler sampler(scene->lights, scene->shapes, scene->textures, LightSamplerKind::Power);
  const Vec3 v[3] = {Vec3(-1, -1, 0), Vec3(1, -1, 0), Vec3(0, 1.2f, 0)};
  RandomStream r = RandomStream::make(11, 12, 13);
  int sampled = 0, spherical = 0;
  for (int k = 0; k < 4000; ++k) {
    const Vec2 b = r.get2d();
    Vec3 on = v[0] + b.x * (v[1] - v[0]) + b.y * (1.f - b.x) * (v[2] - v[0]);  // a point of the triangle
    if (k % 10 == 0) on = v[k / 10 % 3];                                       // a vertex
    const float dist = std::pow(10.f, -5.f + 10.f * r.get1d());
    Vec3 off = glm::normalize(Vec3(r.get1d() - 0.5f, r.get1d() - 0.5f, -r.get1d()));
    if (k % 7 == 0) off.z = 0.f;  // in the light's plane
    const Vec3 p = on + dist * off;
    const Vec3 n = glm::normalize(Vec3(r.get1d() - 0.5f, r.get1d() - 0.5f, r.get1d() - 0.5f) + Vec3(1e-4f));
    // (the renderer's gate: area x cosine / distance^2 at the centroid)
    const Vec3 d = (v[0] + v[1] + v[2]) / 3.f - p;
    const float approx = 0.5f * std::fabs(glm::dot(glm::cross(v[1] - v[0], v[2] - v[0]), d)) /
                         std::pow(glm::dot(d, d), 1.5f);
    if (approx >= kSphericalSamplingFrom && samples_spherical(spherical_triangle(p, v[0], v[1], v[2]))) ++spherical;
    for (int i = 0; i < 4; ++i) {
      auto ls = sample_light(scene->lights, scene->shapes, scene->textures, sampler, p, n, r.get1d(), r.get2d(),
                             SampledWavelengths::rgb());
      if (!ls) continue;
      ++sampled;
      ASSERT_TRUE(std::isfinite(ls->pdf) && ls->pdf > 0.f) << "p " << p.x << " " << p.y << " " << p.z;
      ASSERT_TRUE(std::isfinite(ls->L[0]) && std::isfinite(ls->wi.x) && std::isfinite(ls->p_light.x));
      EXPECT_NEAR(ls->p_light.z, 0.f, 1e-5f);
      const float pdf = area_light_pdf(scene->lights, scene->shapes, sampler, 0, p, n, ls->p_light, ls->n_light);
      EXPECT_NEAR(pdf, ls->pdf, 2e-3f * ls->pdf) << "at distance " << dist;
    }
  }
  EXPECT_GT(spherical, 400);  // both ways of sampling were exercised (689 of 4000 points by solid angle)
  EXPECT_GT(sampled, 8000);
}

}  // namespace
}  // namespace lantern
