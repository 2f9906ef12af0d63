// A triangle hit's point stays on its triangle (integrator/hit.h,
// triangle_barycentrics): Embree's barycentrics of a hit on an edge can
// fall a rounding outside the triangle, and the point then lay past the
// edge; at the top of a wall 2e5 high, a float's step above the ceiling
// that meets it, where bdpt's rays to a light outside the room went
// through (tests/extremes_test.cpp, ScaleInvariance, on a machine whose
// Embree runs its AVX-512 kernels).
#include <gtest/gtest.h>

#include <cmath>

#include "geometry/surface.h"
#include "integrator/hit.h"
#include "math/rng.h"

namespace lantern {
namespace {

// The back wall of the scale-invariance box at scale 1e5: its first vertex
// at the floor, the other two on the ceiling's plane y = 2e5.
TriangleMesh wall() {
  TriangleMesh m;
  m.positions = {Vec3(-1e5f, 0.f, 1e5f), Vec3(-1e5f, 2e5f, 1e5f), Vec3(1e5f, 2e5f, 1e5f), Vec3(0.f)};
  m.triangles = {glm::uvec3(0, 1, 2)};
  m.vertex_count = 3;
  return m;
}

TEST(TriangleHit, BarycentricsAreClampedOntoTheTriangle) {
  EXPECT_EQ(triangle_barycentrics(-1e-8f, 0.5f), Vec2(0.f, 0.5f));
  EXPECT_EQ(triangle_barycentrics(0.3f, 1.2f), Vec2(0.3f, 0.7f));
  EXPECT_EQ(triangle_barycentrics(0.25f, 0.5f), Vec2(0.25f, 0.5f)) << "inside: unchanged";
  for (float u : {0.3f, 0.6f, 0.123456f}) {
    const Vec2 b = triangle_barycentrics(u, std::nextafter(1.f - u, 2.f));
    EXPECT_EQ(1.f - b.x - b.y, 0.f) << "the third barycentric, as triangle_point forms it";
  }
}

// Hits on the wall's top edge whose first barycentric came out a few
// floats' steps below 0: their points never rise above the ceiling's
// plane. (Unclamped, most of them did: checked below, so that this test
// can tell.)
TEST(TriangleHit, PointsOnAnEdgeDoNotPassTheCoordinateItsVerticesShare) {
  const TriangleMesh m = wall();
  RandomStream rng = RandomStream::make(11, 0, 0);
  int above_unclamped = 0;
  for (int i = 0; i < 10000; ++i) {
    const float u = rng.get1d();
    float v = 1.f - u;
    for (int k = 1 + i % 4; k > 0; --k) v = std::nextafter(v, 2.f);  // the sum a few steps past 1
    above_unclamped += triangle_point(m, 0, u, v).p.y > 2e5f;
    const Vec2 b = triangle_barycentrics(u, v);
    ASSERT_LE(triangle_point(m, 0, b.x, b.y).p.y, 2e5f) << "barycentrics " << u << ", " << v;
  }
  EXPECT_GT(above_unclamped, 1000) << "(the rounding this guards against)";
}

}  // namespace
}  // namespace lantern
