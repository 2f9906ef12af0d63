// Quadrics (disk, cylinder, partial and transformed spheres): intersections
// against an independent root search on the implicit surface, areas and
// irradiance against closed forms or a fine tessellation, light sampling
// densities checked through the estimators they feed, and path, bdpt and lt
// agreeing on scenes lit only by quadric lights.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "light/light_sampler.h"
#include "light/lights.h"
#include "math/rng.h"
#include "geometry/surface.h"
#include "expect_error.h"
#include "sanitizer.h"
#include "stat_compare.h"

namespace lantern {
namespace {

Quadric make(QuadricKind kind, float r, float z0, float z1, float phimax_deg, float inner = 0.f) {
  Quadric q;
  q.kind = kind;
  q.radius = r;
  q.z_min = z0;
  q.z_max = z1;
  q.inner_radius = inner;
  q.phi_max = glm::radians(phimax_deg);
  q.theta_z_min = std::acos(glm::clamp(z0 / r, -1.f, 1.f));
  q.theta_z_max = std::acos(glm::clamp(z1 / r, -1.f, 1.f));
  return q;
}

glm::dmat4 placement(bool non_uniform) {
  glm::dmat4 M = glm::translate(glm::dmat4(1.0), glm::dvec3(0.3, -0.2, 0.5));
  M = glm::rotate(M, 0.7, glm::normalize(glm::dvec3(1, 2, 0.5)));
  return non_uniform ? glm::scale(M, glm::dvec3(1.5, 0.7, 1.2)) : glm::scale(M, glm::dvec3(1.3));
}

// The implicit function of the full quadric in object space, and whether a
// point on it lies within the partial shape.
double implicit(const Quadric& q, const glm::dvec3& p) {
  switch (q.kind) {
    case QuadricKind::Sphere: return glm::dot(p, p) - double(q.radius) * q.radius;
    case QuadricKind::Cylinder: return p.x * p.x + p.y * p.y - double(q.radius) * q.radius;
    case QuadricKind::Disk: return p.z - q.z_min;
  }
  return 0.0;
}
bool within(const Quadric& q, const glm::dvec3& p) {
  double phi = std::atan2(p.y, p.x);
  if (phi < 0.0) phi += 2.0 * 3.141592653589793;
  if (phi > q.phi_max) return false;
  if (q.kind == QuadricKind::Disk) {
    double r2 = p.x * p.x + p.y * p.y;
    return r2 <= double(q.radius) * q.radius && r2 >= double(q.inner_radius) * q.inner_radius;
  }
  return p.z >= q.z_min && p.z <= q.z_max;
}

// The first t in (0, t_max) where the ray crosses the implicit surface
// within the partial shape: sign changes on a fine grid, refined by
// bisection. Independent of the closed-form solver under test.
std::optional<double> reference_hit(const Quadric& q, const glm::dvec3& ow, const glm::dvec3& dw, double t_max) {
  const glm::dvec3 o(q.object_from_world * glm::dvec4(ow, 1.0));
  const glm::dvec3 d = glm::dmat3(q.object_from_world) * dw;
  const int n = 40000;
  double t0 = 0.0, f0 = implicit(q, o);
  for (int i = 1; i <= n; ++i) {
    double t1 = t_max * i / n, f1 = implicit(q, o + t1 * d);
    if ((f0 < 0.0) != (f1 < 0.0)) {
      double a = t0, b = t1;
      for (int k = 0; k < 80; ++k) {
        double m = 0.5 * (a + b);
        ((implicit(q, o + a * d) < 0.0) == (implicit(q, o + m * d) < 0.0) ? a : b) = m;
      }
      if (within(q, o + a * d)) return a;
    }
    t0 = t1, f0 = f1;
  }
  return std::nullopt;
}

struct Case {
  const char* name;
  Quadric q;
  bool non_uniform;
};

std::vector<Case> cases() {
  return {{"sphere", make(QuadricKind::Sphere, 1.f, -1.f, 1.f, 360.f), true},
          {"partial sphere", make(QuadricKind::Sphere, 1.f, -0.4f, 0.7f, 250.f), false},
          {"cylinder", make(QuadricKind::Cylinder, 0.8f, -0.5f, 1.f, 300.f), true},
          {"disk", make(QuadricKind::Disk, 1.f, 0.2f, 0.2f, 290.f, 0.3f), true}};
}

TEST(Quadric, IntersectionsMatchAnIndependentRootSearch) {
  RandomStream rng = RandomStream::make(7, 0, 0);
  for (Case c : cases()) {
    ASSERT_EQ(QuadricCheck::Ok, finish_quadric(c.q, placement(c.non_uniform))) << c.name;
    const Quadric& q = c.q;
    Vec3 lo, hi;
    quadric_bounds(q, &lo, &hi);
    const Vec3 centre = 0.5f * (lo + hi);
    int hits = 0, checked = 0;
    for (int i = 0; i < 300; ++i) {
      // Origins outside (towards points in the box) and inside the box,
      // some aimed to graze: targets on the surface, slightly pushed out.
      glm::dvec3 o, target(lo + (hi - lo) * Vec3(rng.get1d(), rng.get1d(), rng.get1d()));
      if (i % 3 == 0) {
        o = glm::dvec3(centre + 0.3f * (hi - lo) * (Vec3(rng.get1d(), rng.get1d(), rng.get1d()) - 0.5f));
      } else {
        Vec3 w = glm::normalize(Vec3(rng.get1d(), rng.get1d(), rng.get1d()) - 0.5f);
        o = glm::dvec3(centre + 4.f * glm::length(hi - lo) * w);
      }
      if (i % 5 == 4) {
        SurfacePoint s = quadric_point(q, Vec2(rng.get1d(), rng.get1d()));
        target = glm::dvec3(s.p + 1e-3f * glm::length(hi - lo) * s.ng);
      }
      glm::dvec3 d = glm::normalize(target - o);
      const double t_max = 20.0 * glm::length(hi - lo);
      auto ref = reference_hit(q, o, d, t_max);
      QuadricHit h;
      bool got = intersect_quadric(q, o, d, 0.0, t_max, &h);
      // A grazing ray may touch within the reference's step: skip the
      // rare disagreement only if the reference's crossing is that close.
      ASSERT_EQ(got, ref.has_value()) << c.name << " ray " << i;
      ++checked;
      if (!got) continue;
      ++hits;
      EXPECT_NEAR(h.t, *ref, 1e-6 * t_max) << c.name << " ray " << i;
      SurfacePoint sp = quadric_point(q, h.uv);
      glm::dvec3 p = o + h.t * d;
      EXPECT_LT(glm::length(glm::dvec3(sp.p) - p), 1e-5 * glm::length(hi - lo)) << c.name << " ray " << i;
      // The normal is the implicit function's gradient carried to the world.
      const glm::dvec3 po(q.object_from_world * glm::dvec4(p, 1.0));
      glm::dvec3 grad = q.kind == QuadricKind::Sphere     ? po
                        : q.kind == QuadricKind::Cylinder ? glm::dvec3(po.x, po.y, 0.0)
                                                          : glm::dvec3(0, 0, 1);
      Vec3 n = glm::normalize(Vec3(glm::transpose(glm::dmat3(q.object_from_world)) * grad));
      EXPECT_GT(std::fabs(glm::dot(n, sp.ng)), 1.f - 1e-5f) << c.name << " ray " << i;
    }
    EXPECT_GT(hits, 60) << c.name;
    EXPECT_EQ(checked, 300);
  }
}

TEST(Quadric, AreasMatchClosedForms) {
  const double pi = 3.141592653589793;
  Quadric zone = make(QuadricKind::Sphere, 2.f, -1.f, 1.5f, 200.f);
  ASSERT_EQ(QuadricCheck::Ok, finish_quadric(zone, glm::scale(glm::dmat4(1.0), glm::dvec3(1.5))));
  EXPECT_NEAR(zone.world_area, 1.5 * 1.5 * glm::radians(200.0) * 2.0 * 2.5, 1e-4 * zone.world_area);
  // A prolate spheroid, semi-axes 1, 1, 2: 2 pi a^2 (1 + c / (a e) asin e).
  Quadric spheroid = make(QuadricKind::Sphere, 1.f, -1.f, 1.f, 360.f);
  ASSERT_EQ(QuadricCheck::Ok, finish_quadric(spheroid, glm::scale(glm::dmat4(1.0), glm::dvec3(1, 1, 2))));
  const double e = std::sqrt(0.75);
  EXPECT_NEAR(spheroid.world_area, 2.0 * pi * (1.0 + 2.0 / e * std::asin(e)), 2e-3 * spheroid.world_area);
  // A disk stretched into an ellipse of semi-axes 2 and 1.
  Quadric disk = make(QuadricKind::Disk, 1.f, 0.f, 0.f, 360.f);
  ASSERT_EQ(QuadricCheck::Ok, finish_quadric(disk, glm::scale(glm::dmat4(1.0), glm::dvec3(2, 1, 1))));
  EXPECT_NEAR(disk.world_area, 2.0 * pi, 1e-4 * disk.world_area);
  // An elliptic cylinder: perimeter 4 a E(e) = 9.6884482205 for a = 2, b = 1.
  Quadric cyl = make(QuadricKind::Cylinder, 1.f, 0.f, 2.f, 360.f);
  ASSERT_EQ(QuadricCheck::Ok, finish_quadric(cyl, glm::scale(glm::dmat4(1.0), glm::dvec3(2, 1, 1))));
  EXPECT_NEAR(cyl.world_area, 2.0 * 9.6884482205, 1e-4 * cyl.world_area);
  // An annulus sector.
  Quadric ring = make(QuadricKind::Disk, 1.f, 0.f, 0.f, 90.f, 0.5f);
  ASSERT_EQ(QuadricCheck::Ok, finish_quadric(ring, glm::dmat4(1.0)));
  EXPECT_NEAR(ring.world_area, 0.25 * pi * 0.75, 1e-5);
}

// Irradiance at p from one emitter, estimated by next-event estimation
// (the light's own sampling density), against a reference: the estimate's
// z statistic.
double nee_irradiance_z(const Scene& s, const Vec3& p, const Vec3& n, int count, double reference) {
  RandomStream rng = RandomStream::make(3, 0, 0);
  double sum = 0.0, sum2 = 0.0;
  for (int i = 0; i < count; ++i) {
    auto ls = sample_light_from(s.lights, s.shapes, s.textures, 0, p, Vec2(rng.get1d(), rng.get1d()), SampledWavelengths::rgb());
    double v = 0.0;
    if (ls && ls->pdf > 0.f) v = double(ls->L[0]) * std::fmax(0.f, glm::dot(n, ls->wi)) / ls->pdf;
    sum += v;
    sum2 += v * v;
  }
  double mean = sum / count, se = std::sqrt((sum2 / count - mean * mean) / (count - 1));
  std::printf("  irradiance %.5f +- %.5f, reference %.5f\n", mean, se, reference);
  return std::fabs(mean - reference) / se;
}

// The same integral over a fine tessellation of the surface, by world-space
// triangle areas: independent of the sampling densities. One-sided
// emitters facing away from p (the far side of a closed shape) add nothing.
double tessellated_irradiance(const Quadric& q, float L, const Vec3& p, const Vec3& n) {
  const int N = 400;
  double sum = 0.0;
  auto at = [&](int i, int j) { return quadric_point(q, Vec2(float(i) / N, float(j) / N)).p; };
  for (int i = 0; i < N; ++i)
    for (int j = 0; j < N; ++j) {
      const Vec3 a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
      for (auto [x, y, z] : {std::array<Vec3, 3>{a, b, c}, std::array<Vec3, 3>{a, c, d}}) {
        Vec3 cr = glm::cross(y - x, z - x);
        double area = 0.5 * glm::length(cr);
        if (area == 0.0) continue;
        Vec3 centre = (x + y + z) / 3.f;
        Vec3 nl = quadric_point(q, Vec2((i + 0.5f) / N, (j + 0.5f) / N)).ng;
        Vec3 w = centre - p;
        float dist2 = glm::dot(w, w);
        w /= std::sqrt(dist2);
        float cos_l = -glm::dot(nl, w), cos_r = glm::dot(n, w);
        if (cos_l > 0.f && cos_r > 0.f) sum += L * cos_l * cos_r * area / dist2;
      }
    }
  return sum;
}

std::shared_ptr<Scene> light_scene(const std::string& shape) {
  return load_scene_from_string("WorldBegin\nAttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [ 2 2 2 ]\n" + shape +
                                    "\nAttributeEnd\n",
                                "quadric-light.pbrt");
}

TEST(Quadric, LightIrradianceMatchesClosedFormsAndQuadrature) {
  // An annulus sector facing down (ReverseOrientation) at height 1 above
  // the point, which lies on its axis: E = L phimax / 2 (R^2 / (h^2 + R^2)
  // - r^2 / (h^2 + r^2)).
  auto ring = light_scene(R"(Translate 0 0 1 ReverseOrientation
    Shape "disk" "float radius" [ 1.2 ] "float innerradius" [ 0.4 ] "float phimax" [ 270 ])");
  const double h = 1.0, R = 1.2, r = 0.4;
  double ring_closed = 2.0 * 0.5 * glm::radians(270.0) * (R * R / (h * h + R * R) - r * r / (h * h + r * r));
  const int n = LANTERN_ASAN ? 50000 : 400000;  // the sanitizers check the code, not the last digit
  EXPECT_LT(nee_irradiance_z(*ring, Vec3(0.f), Vec3(0, 0, 1), n, ring_closed), 4.0);
  struct Check {
    const char* shape;
    Vec3 p, n;
  };
  for (const Check& c : {Check{R"(Translate 2 0 0 Rotate 30 0 1 0
      Shape "cylinder" "float radius" [ 0.5 ] "float zmin" [ -0.5 ] "float zmax" [ 1 ] "float phimax" [ 360 ])",
                               Vec3(0.f), glm::normalize(Vec3(1, 0, 0.3f))},
                         Check{R"(Translate 0 0 2.5 Rotate 40 1 1 0 Scale 1.4 0.6 0.9
      Shape "sphere" "float radius" [ 1 ] "float zmin" [ -0.8 ] "float zmax" [ 0.9 ] "float phimax" [ 300 ])",
                               Vec3(0.f), Vec3(0, 0, 1)}}) {
    auto s = light_scene(c.shape);
    ASSERT_EQ(s->shapes.quadrics.size(), 1u);
    double ref = tessellated_irradiance(s->shapes.quadrics[0], 2.f, c.p, c.n);
    EXPECT_LT(nee_irradiance_z(*s, c.p, c.n, n, ref), 4.0) << c.shape;
  }
}

// Path, bdpt and light tracing agree on scenes lit only by quadric lights:
// the emission densities of light subpaths and the MIS weights that
// compare them with next-event estimation are consistent.
TEST(Quadric, IntegratorsAgreeUnderQuadricLights) {
  if (LANTERN_ASAN) GTEST_SKIP() << "the Release suite runs it; the sanitizers cover this code in the other quadric tests";
  auto scene = load_scene_from_string(R"(
LookAt 0 3 -3  0 0.3 0  0 1 0
Camera "perspective" "float fov" [ 35 ]
Film "rgb" "integer xresolution" [ 24 ] "integer yresolution" [ 24 ]
WorldBegin
AttributeBegin
  AreaLightSource "diffuse" "rgb L" [ 3 2.5 2 ]
  Translate 0 2 0 Rotate 90 1 0 0 Scale 1.5 1 1
  Shape "disk" "float radius" [ 0.8 ] "float innerradius" [ 0.3 ] "float phimax" [ 270 ]
AttributeEnd
AttributeBegin
  AreaLightSource "diffuse" "rgb L" [ 1 1.5 2 ] "bool twosided" true
  Translate 1.2 0.2 0.8 Rotate -90 1 0 0
  Shape "cylinder" "float radius" [ 0.15 ] "float zmin" [ 0 ] "float zmax" [ 0.8 ] "float phimax" [ 200 ]
AttributeEnd
AttributeBegin
  AreaLightSource "diffuse" "rgb L" [ 2 1 0.5 ]
  Translate -1.2 0.5 0.6 Scale 0.3 0.6 0.2
  Shape "sphere" "float radius" [ 1 ] "float zmax" [ 0.5 ]
AttributeEnd
Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.5 ]
Shape "trianglemesh" "point3 P" [ -20 0 -20 20 0 -20 20 0 20 -20 0 20 ] "integer indices" [ 0 1 2 0 2 3 ]
AttributeBegin
  Material "coateddiffuse" "rgb reflectance" [ 0.6 0.2 0.1 ] "float roughness" [ 0.1 ]
  Translate 0.2 0.4 0 Rotate -90 1 0 0
  Shape "cylinder" "float radius" [ 0.35 ] "float zmin" [ -0.4 ] "float zmax" [ 0.4 ] "float phimax" [ 280 ]
AttributeEnd
)",
                                      "quadric-lights.pbrt");
  const std::vector<Region> regions = {{0, 0, 24, 24}, {0, 0, 8, 8}, {8, 8, 8, 8}, {16, 8, 8, 8}, {0, 16, 8, 8}};
  auto path = render_stats(*scene, "path", 24, 24, 64, 16, regions);
  auto bdpt = render_stats(*scene, "bdpt", 24, 24, 16, 16, regions);
  auto lt = render_stats(*scene, "lt", 24, 24, 32, 16, regions);
  EXPECT_LT(max_z(bdpt, path), 5.0);
  EXPECT_LT(max_z(lt, path), 5.0);
}

// A quadric in an object placed by ObjectInstance renders as the same
// quadric placed directly (its hits come back in the object's space).
TEST(Quadric, InstancedQuadricsRenderAsPlacedOnes) {
  const std::string head = R"(
LookAt 0 -4 2  0 0 0.5  0 0 1
Camera "perspective" "float fov" [ 45 ]
Film "rgb" "integer xresolution" [ 24 ] "integer yresolution" [ 24 ]
WorldBegin
LightSource "distant" "rgb L" [ 2 2 2 ] "point3 from" [ 1 -2 3 ] "point3 to" [ 0 0 0 ]
Shape "trianglemesh" "point3 P" [ -9 -9 0 9 -9 0 9 9 0 -9 9 0 ] "integer indices" [ 0 1 2 0 2 3 ]
)";
  const std::string shapes = R"(
  Shape "cylinder" "float radius" [ 0.4 ] "float zmin" [ 0 ] "float zmax" [ 1 ] "float phimax" [ 250 ]
  Translate 0 0 1.5 Shape "sphere" "float radius" [ 0.5 ] "float zmin" [ -0.2 ]
  Shape "disk" "float radius" [ 0.4 ] "float innerradius" [ 0.1 ]
)";
  const std::string place = "Translate 0.5 0.2 0 Rotate 20 0 0 1 Scale 1 1.3 0.8\n";
  auto direct = load_scene_from_string(head + "AttributeBegin\n" + place + shapes + "AttributeEnd\n", "direct.pbrt");
  auto instanced = load_scene_from_string(head + "ObjectBegin \"o\"" + shapes + "ObjectEnd\nAttributeBegin\n" + place +
                                              "ObjectInstance \"o\"\nAttributeEnd\n",
                                          "instanced.pbrt");
  ASSERT_EQ(instanced->shapes.instances.size(), 1u);
  RenderOptions o;
  o.spp = 16;
  for (const char* integrator : {"path", "bdpt"}) {
    o.integrator = parse_integrator(integrator);
    Image a = render(*direct, o).image, b = render(*instanced, o).image;
    double sa = 0.0, sb = 0.0, diff = 0.0;
    for (size_t i = 0; i < a.rgb.size(); ++i) {
      sa += a.rgb[i], sb += b.rgb[i];
      diff = std::max(diff, double(std::fabs(a.rgb[i] - b.rgb[i])));
    }
    // The same paths up to rounding: pixel values differ by far less than
    // their noise.
    EXPECT_NEAR(sa, sb, 1e-3 * sa) << integrator;
    EXPECT_LT(diff, 0.05) << integrator;
  }
}

// An alpha-0 quadric leaves the image exactly as without it: the user
// geometry runs the alpha filter on each candidate.
TEST(Quadric, AlphaCutsQuadrics) {
  const std::string head = R"(
LookAt 0 -4 2  0 0 0.5  0 0 1
Camera "perspective" "float fov" [ 45 ]
Film "rgb" "integer xresolution" [ 16 ] "integer yresolution" [ 16 ]
WorldBegin
AttributeBegin
  AreaLightSource "diffuse" "rgb L" [ 2 2 2 ]
  Translate 0 0 3 ReverseOrientation Shape "disk" "float radius" [ 1 ]
AttributeEnd
Shape "trianglemesh" "point3 P" [ -9 -9 0 9 -9 0 9 9 0 -9 9 0 ] "integer indices" [ 0 1 2 0 2 3 ]
)";
  auto open = load_scene_from_string(head, "open.pbrt");
  auto cut = load_scene_from_string(head + R"(Translate 0 0 1
    Shape "sphere" "float radius" [ 0.8 ] "float zmax" [ 0.5 ] "float alpha" [ 0 ]
    Shape "cylinder" "float radius" [ 1.5 ] "float alpha" [ 0 ]
    Shape "disk" "float radius" [ 3 ] "float height" [ 1 ] "float alpha" [ 0 ])",
                                    "cut.pbrt");
  expect_identical_renders(*open, *cut, {"path", "bdpt", "lt"});
}

TEST(Quadric, BadParametersAreClearErrors) {
  expect_load_error("WorldBegin\nShape \"disk\" \"float radius\" [ 1 ] \"float innerradius\" [ 1 ]\n", "d.pbrt",
                    {"d.pbrt:2", "innerradius", "less than"});
  expect_load_error("WorldBegin\nShape \"cylinder\" \"float radius\" [ -1 ]\n", "c.pbrt", {"c.pbrt:2", "radius", "positive"});
  expect_load_error("WorldBegin\nScale 1 0 1\nShape \"sphere\" \"float zmax\" [ 0.5 ]\n", "s.pbrt",
                    {"s.pbrt:3", "singular"});
  expect_load_error("WorldBegin\nShape \"cone\"\n", "x.pbrt", {"x.pbrt:2", "cone", "cylinder", "disk"});
  expect_load_error("WorldBegin\nShape \"disk\" \"float radius\" [ 1e38 ]\n", "h.pbrt", {"h.pbrt:2", "disk", "single precision"});
  expect_load_error("WorldBegin\nTranslate 1e300 0 0\nShape \"cylinder\"\n", "t.pbrt", {"t.pbrt:3", "single precision"});
}

}  // namespace
}  // namespace lantern
