// pbrt-v3's "heightfield" and "nurbs" shapes, made into the triangle meshes
// pbrt-v3 makes of them (pbrt-v4's upgrade writes the same meshes out).
#include "geometry/nurbs.h"
#include "scene/builder.h"

namespace lantern {

using pbrt::ParamSet;

// "nu" x "nv" heights "Pz" over the unit square, u fastest: the point
// (i / (nu - 1), j / (nv - 1), Pz[j nu + i]) with uv its first two
// coordinates, two triangles a cell, no normals.
void SceneBuilder::add_heightfield(const ParamSet& ps, const GraphicsState& gs) {
  const int nu = ps.get_int("nu", -1), nv = ps.get_int("nv", -1);
  if (nu < 2 || nv < 2) ps.fail("a heightfield needs \"integer nu\" and \"integer nv\" of 2 or more");
  if (size_t(nu) * size_t(nv) > (size_t(1) << 28)) ps.fail("a heightfield of more than 2^28 points is not supported");
  const std::vector<float> z = ps.get_floats("Pz");
  if (z.size() != size_t(nu) * size_t(nv))
    ps.fail("\"float Pz\" has " + std::to_string(z.size()) + " values, expected nu x nv = " +
            std::to_string(size_t(nu) * size_t(nv)));
  TriangleMesh m;
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const float x = float(i) / float(nu - 1), y = float(j) / float(nv - 1);
      m.positions.emplace_back(x, y, z[size_t(j) * size_t(nu) + size_t(i)]);
      m.uvs.emplace_back(x, y);
    }
  add_grid_triangles(m, nu, nv);
  add_mesh(std::move(m), gs, ps, "");
}

// pbrt-v3's parameters: nu, nv, uorder, vorder, uknots, vknots, u0, u1,
// v0, v1 (by default the knots' valid range), and "point3 P" or
// homogeneous "float Pw" control points (geometry/nurbs.h).
void SceneBuilder::add_nurbs(const ParamSet& ps, const GraphicsState& gs) {
  NurbsSurface s;
  s.nu = ps.get_int("nu", -1);
  s.nv = ps.get_int("nv", -1);
  s.uorder = ps.get_int("uorder", -1);
  s.vorder = ps.get_int("vorder", -1);
  for (const char* p : {"nu", "nv", "uorder", "vorder", "uknots", "vknots"})
    if (!ps.has(p)) ps.fail(std::string("a nurbs shape needs \"") + p + "\"");
  s.uknots = ps.get_floats("uknots");
  s.vknots = ps.get_floats("vknots");
  auto knot = [](const std::vector<float>& k, int i) { return i >= 0 && size_t(i) < k.size() ? k[size_t(i)] : 0.f; };
  s.u0 = ps.get_float("u0", knot(s.uknots, s.uorder - 1));
  s.u1 = ps.get_float("u1", knot(s.uknots, s.nu));
  s.v0 = ps.get_float("v0", knot(s.vknots, s.vorder - 1));
  s.v1 = ps.get_float("v1", knot(s.vknots, s.nv));
  if (ps.has("P")) {
    for (const Vec3& p : ps.get_point3s("P")) s.points.emplace_back(p, 1.f);
  } else if (ps.has("Pw")) {
    const std::vector<float> w = ps.get_floats("Pw");
    if (w.size() % 4 != 0) ps.fail(*ps.find("Pw"), "\"Pw\" needs four values (x y z w) a control point");
    for (size_t i = 0; i + 3 < w.size(); i += 4) s.points.emplace_back(w[i], w[i + 1], w[i + 2], w[i + 3]);
  } else {
    ps.fail("a nurbs shape needs its control points, \"point3 P\" or \"float Pw\"");
  }
  if (const std::string problem = nurbs_problem(s); !problem.empty()) ps.fail("nurbs: " + problem);
  add_mesh(tessellate_nurbs(s), gs, ps, "");
}

}  // namespace lantern
