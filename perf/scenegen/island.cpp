// lantern-scenegen --island SCALE: a scene of the shape of a production
// island (Disney's Moana Island, published for research: about 90M unique
// quads, 5M curves and 28M instances of a few thousand objects placed
// through included files), scaled by SCALE (1 = that size). Unique quads
// are PLY files of at most 250k quads: two thirds curved terrain (bilinear
// patches), one third flat panels (parallelograms); curves are grass
// blades, instances plants of 50 to 1,400 triangles (about 550 on average,
// so 28M instances trace about 15 billion triangles). Deterministic for a
// seed; everything is written once, so loading is what a run measures.
#include "island.h"

#include <algorithm>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include "mesh_io.h"

namespace scenegen {

namespace fs = std::filesystem;

namespace {

constexpr double kFullQuads = 90e6, kFullCurves = 5e6, kFullInstances = 28e6;
constexpr size_t kQuadsPerFile = 250000, kCurvesPerFile = 250000, kPlacementsPerFile = 500000;
constexpr float kHalf = 1000.f;  // the island spans [-kHalf, kHalf] in x and z

float island_height(float x, float z) {
  const float r2 = (x * x + z * z) / (420.f * 420.f);
  return 260.f * std::exp(-r2) - 8.f + 6.f * std::sin(0.013f * x + 0.4f) * std::cos(0.011f * z) +
         1.5f * std::sin(0.09f * x - 0.05f * z);
}

// An r x r grid of curved quads over a square of the terrain.
Mesh terrain_quads(float x0, float z0, float size, int r) {
  Mesh m;
  m.arity = 4;
  for (int j = 0; j < r; ++j)
    for (int i = 0; i < r; ++i) {
      const float x = x0 + size * float(i) / float(r - 1), z = z0 + size * float(j) / float(r - 1);
      m.p.push_back({x, island_height(x, z), z});
    }
  for (int j = 0; j + 1 < r; ++j)
    for (int i = 0; i + 1 < r; ++i) {
      const uint32_t a = uint32_t(j * r + i);
      m.idx.insert(m.idx.end(), {a, a + 1, a + 1 + uint32_t(r), a + uint32_t(r)});
    }
  return m;
}

// A flat n x n panel (every quad a parallelogram), tilted, standing on the
// terrain at (x, z): boardwalks, walls, rock faces.
void add_panel(Mesh& m, float x, float z, float size, int n, float angle) {
  const uint32_t base = uint32_t(m.p.size());
  const float y = island_height(x, z), c = std::cos(angle), s = std::sin(angle);
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const float u = size * (float(i) / float(n) - 0.5f), v = size * float(j) / float(n);
      m.p.push_back({x + c * u, y + 0.9f * v, z + s * u + 0.3f * v});
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const uint32_t a = base + uint32_t(j * (n + 1) + i);
      m.idx.insert(m.idx.end(), {a, a + 1, a + 2 + uint32_t(n), a + 1 + uint32_t(n)});
    }
}

// A plant: a bumpy ellipsoid of rings x segments (two triangles each).
Mesh plant(int rings, int segments, float h, uint32_t seed) {
  Mesh m;
  for (int j = 0; j <= rings; ++j) {
    const float th = 3.14159265f * float(j) / float(rings);
    for (int i = 0; i < segments; ++i) {
      const float ph = 6.2831853f * float(i) / float(segments);
      const float n = 1.f + 0.25f * std::sin(5.f * th + float(seed)) * std::sin(4.f * ph + 0.7f * float(seed));
      m.p.push_back({0.6f * n * std::sin(th) * std::cos(ph), h * (0.5f + 0.5f * std::cos(3.14159265f - th)) * n,
                     0.6f * n * std::sin(th) * std::sin(ph)});
    }
  }
  for (int j = 0; j < rings; ++j)
    for (int i = 0; i < segments; ++i) {
      const uint32_t a = uint32_t(j * segments + i), b = uint32_t(j * segments + (i + 1) % segments);
      m.idx.insert(m.idx.end(), {a, b, a + uint32_t(segments), b, b + uint32_t(segments), a + uint32_t(segments)});
    }
  return m;
}

std::string file_name(const char* stem, size_t k, const char* ext) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%s_%05zu.%s", stem, k, ext);
  return buf;
}

struct Writer {
  fs::path out;
  std::mt19937 rng;
  std::FILE* scene;
  float U() { return std::uniform_real_distribution<float>(0.f, 1.f)(rng); }
  float in_island() { return (U() - 0.5f) * 2.f * kHalf * 0.97f; }
};

std::FILE* open_text(const fs::path& p) {
  std::FILE* f = std::fopen(p.c_str(), "w");
  if (!f) throw std::runtime_error("cannot write " + p.string());
  return f;
}

// Terrain tiles over the island, then panels, in files of kQuadsPerFile.
IslandCounts write_quads(Writer& w, double quads) {
  IslandCounts c;
  const size_t terrain = size_t(quads * 2.0 / 3.0), panels = size_t(quads) - terrain;
  const size_t tiles_per_side = std::max<size_t>(1, size_t(std::ceil(std::sqrt(double(terrain) / kQuadsPerFile))));
  const int r = std::max(2, int(std::lround(std::sqrt(double(terrain) / double(tiles_per_side * tiles_per_side)))) + 1);
  const float tile = 2.f * kHalf / float(tiles_per_side);
  std::fprintf(w.scene, "AttributeBegin\nMaterial \"diffuse\" \"rgb reflectance\" [ 0.3 0.26 0.16 ]\n");
  for (size_t ty = 0; ty < tiles_per_side; ++ty)
    for (size_t tx = 0; tx < tiles_per_side; ++tx) {
      Mesh m = terrain_quads(-kHalf + tile * float(tx), -kHalf + tile * float(ty), tile, r);
      const std::string name = file_name("terrain", c.files, "ply");
      write_ply(w.out / "meshes" / name, m);
      c.quads += m.faces(), ++c.files;
      std::fprintf(w.scene, "Shape \"plymesh\" \"string filename\" \"meshes/%s\"\n", name.c_str());
    }
  std::fprintf(w.scene, "Material \"coateddiffuse\" \"rgb reflectance\" [ 0.4 0.35 0.3 ] \"float roughness\" 0.2\n");
  const int n = 16;  // 256 quads a panel
  for (size_t done = 0; done < panels;) {
    Mesh m;
    m.arity = 4;
    while (m.faces() + size_t(n) * n <= kQuadsPerFile && done + m.faces() < panels)
      add_panel(m, w.in_island(), w.in_island(), 2.f + 6.f * w.U(), n, 6.2831853f * w.U());
    const std::string name = file_name("panels", c.files, "ply");
    write_ply(w.out / "meshes" / name, m);
    done += m.faces(), c.quads += m.faces(), ++c.files;
    std::fprintf(w.scene, "Shape \"plymesh\" \"string filename\" \"meshes/%s\"\n", name.c_str());
  }
  std::fprintf(w.scene, "AttributeEnd\n");
  return c;
}

// Grass blades: cubic Bezier curves, kCurvesPerFile to an included file.
size_t write_curves(Writer& w, double curves) {
  size_t written = 0;
  for (size_t k = 0; written < size_t(curves); ++k) {
    const std::string name = file_name("grass", k, "pbrt");
    std::FILE* f = open_text(w.out / "curves" / name);
    std::fprintf(f, "AttributeBegin\nMaterial \"diffuse\" \"rgb reflectance\" [ 0.12 0.3 0.05 ]\n");
    for (size_t i = 0; i < kCurvesPerFile && written < size_t(curves); ++i, ++written) {
      const float x = w.in_island(), z = w.in_island(), y = island_height(x, z), h = 0.3f + 0.5f * w.U();
      const float bx = 0.3f * (w.U() - 0.5f), bz = 0.3f * (w.U() - 0.5f);
      std::fprintf(f, "Shape \"curve\" \"point3 P\" [ %.6g %.6g %.6g %.6g %.6g %.6g %.6g %.6g %.6g %.6g %.6g %.6g ] "
                   "\"float width0\" 0.02 \"float width1\" 0.002\n",
                   x, y, z, x, y + h / 3, z, x + bx / 2, y + 2 * h / 3, z + bz / 2, x + bx, y + h, z + bz);
    }
    std::fprintf(f, "AttributeEnd\n");
    if (std::fclose(f) != 0) throw std::runtime_error("cannot write " + name);
    std::fprintf(w.scene, "Import \"curves/%s\"\n", name.c_str());
  }
  return written;
}

// Prototypes, then placements (a few prototypes common, most rare).
size_t write_instances(Writer& w, double instances, int prototypes, size_t* traced) {
  std::vector<size_t> triangles(static_cast<size_t>(prototypes));
  for (int k = 0; k < prototypes; ++k) {
    const int rings = 4 + int(w.rng() % 23), segments = 6 + int(w.rng() % 25);
    Mesh m = plant(rings, segments, 0.5f + 3.f * w.U(), uint32_t(k));
    write_ply(w.out / "meshes" / file_name("plant", size_t(k), "ply"), m);
    triangles[size_t(k)] = m.faces();
    std::fprintf(w.scene, "ObjectBegin \"p%d\"\nMaterial \"diffuse\" \"rgb reflectance\" [ %.3g %.3g %.3g ]\n"
                 "Shape \"plymesh\" \"string filename\" \"meshes/%s\"\nObjectEnd\n",
                 k, 0.05 + 0.2 * w.U(), 0.2 + 0.3 * w.U(), 0.05 + 0.1 * w.U(), file_name("plant", size_t(k), "ply").c_str());
  }
  size_t placed = 0;
  *traced = 0;
  for (size_t k = 0; placed < size_t(instances); ++k) {
    const std::string name = file_name("place", k, "pbrt");
    std::FILE* f = open_text(w.out / "instances" / name);
    for (size_t i = 0; i < kPlacementsPerFile && placed < size_t(instances); ++i, ++placed) {
      const float x = w.in_island(), z = w.in_island(), s = 0.6f + 0.8f * w.U();
      const int p = std::min(prototypes - 1, int(float(prototypes) * std::pow(w.U(), 3.f)));
      std::fprintf(f, "AttributeBegin Translate %.6g %.6g %.6g Rotate %.4g 0 1 0 Scale %.4g %.4g %.4g ObjectInstance \"p%d\" AttributeEnd\n",
                   x, island_height(x, z), z, 360.f * w.U(), s, s * (0.8f + 0.4f * w.U()), s, p);
      *traced += triangles[size_t(p)];
    }
    if (std::fclose(f) != 0) throw std::runtime_error("cannot write " + name);
    std::fprintf(w.scene, "Import \"instances/%s\"\n", name.c_str());
  }
  return placed;
}

}  // namespace

IslandCounts write_island(const fs::path& out, double scale, int prototypes, uint32_t seed) {
  for (const char* d : {"meshes", "curves", "instances"}) fs::create_directories(out / d);
  Writer w{out, std::mt19937(seed), open_text(out / "scene.pbrt")};
  if (prototypes <= 0) prototypes = std::clamp(int(std::lround(3000.0 * std::sqrt(scale))), 8, 3000);
  std::fprintf(w.scene,
               "# lantern-scenegen --island %g --prototypes %d --seed %" PRIu32 "\n"
               "LookAt -900 40 -900  0 120 0  0 1 0\nCamera \"perspective\" \"float fov\" [ 35 ]\n"
               "Film \"rgb\" \"integer xresolution\" [ 1920 ] \"integer yresolution\" [ 804 ] \"string filename\" \"island.exr\"\n"
               "Sampler \"zsobol\" \"integer pixelsamples\" [ 16 ]\nIntegrator \"path\" \"integer maxdepth\" [ 5 ]\n"
               "WorldBegin\nLightSource \"infinite\" \"rgb L\" [ 0.3 0.45 0.8 ]\n"
               "LightSource \"distant\" \"point3 to\" [ 0.8 -1.1 0.9 ] \"blackbody L\" [ 5500 ] \"float scale\" 3\n",
               scale, prototypes, seed);
  IslandCounts c = write_quads(w, kFullQuads * scale);
  c.curves = write_curves(w, kFullCurves * scale);
  c.prototypes = size_t(prototypes);
  c.instances = write_instances(w, kFullInstances * scale, prototypes, &c.instanced_triangles);
  if (std::fclose(w.scene) != 0) throw std::runtime_error("cannot write scene.pbrt");
  return c;
}

}  // namespace scenegen
