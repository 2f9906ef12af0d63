// lantern-scenegen: writes a scalable test scene in pbrt-v4 format, a forest
// of instanced trees and rocks on unique terrain tiles, lit by a dim sky and
// a few small lanterns (where bidirectional path tracing pays off); or, with
// --island, a scene of a production island's shape (island.cpp).
//
//   lantern-scenegen OUT_DIR --instanced-triangles N --unique-triangles M [--seed S]
//   lantern-scenegen OUT_DIR --island SCALE [--prototypes P] [--seed S]
//
// Unique geometry: terrain tiles, displaced grids written as binary PLY,
// together M triangles. Instanced geometry: three prototypes (a tree of
// ~9k, a bush of ~2k, a rock of ~1k triangles), placed until the traced
// total reaches N. The scene is deterministic for a given seed.
#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "island.h"
#include "mesh_io.h"

namespace {

using scenegen::Mesh;
using scenegen::V3;
using scenegen::write_ply;

// Smooth pseudo-random height field: a few octaves of sines, cheap and
// deterministic.
float terrain_height(float x, float z) {
  return 0.6f * std::sin(0.11f * x + 0.3f) * std::cos(0.07f * z) + 0.25f * std::sin(0.37f * x - 0.21f * z) +
         0.08f * std::sin(1.3f * x + 0.9f * z);
}

// An r x r vertex grid over [x0, x0 + size] x [z0, z0 + size] on the terrain.
Mesh terrain_tile(float x0, float z0, float size, int r) {
  Mesh m;
  m.p.reserve(size_t(r) * size_t(r));
  for (int j = 0; j < r; ++j)
    for (int i = 0; i < r; ++i) {
      float x = x0 + size * float(i) / float(r - 1), z = z0 + size * float(j) / float(r - 1);
      m.p.push_back({x, terrain_height(x, z), z});
    }
  m.idx.reserve(size_t(r - 1) * size_t(r - 1) * 6);
  for (int j = 0; j + 1 < r; ++j)
    for (int i = 0; i + 1 < r; ++i) {
      uint32_t a = uint32_t(j * r + i), b = a + 1, c = a + uint32_t(r), d = c + 1;
      m.idx.insert(m.idx.end(), {a, c, b, b, c, d});
    }
  return m;
}

// A bumpy ellipsoid from a latitude-longitude grid: canopies, bushes, rocks.
void add_blob(Mesh& m, V3 c, V3 radius, int rings, int segments, float bump, uint32_t seed) {
  const uint32_t base = uint32_t(m.p.size());
  for (int j = 0; j <= rings; ++j) {
    float th = 3.14159265f * float(j) / float(rings);
    for (int i = 0; i < segments; ++i) {
      float ph = 6.2831853f * float(i) / float(segments);
      float n = 1.f + bump * std::sin(7.f * th + float(seed)) * std::sin(5.f * ph + 0.5f * float(seed));
      m.p.push_back({c.x + radius.x * n * std::sin(th) * std::cos(ph), c.y + radius.y * n * std::cos(th),
                     c.z + radius.z * n * std::sin(th) * std::sin(ph)});
    }
  }
  for (int j = 0; j < rings; ++j)
    for (int i = 0; i < segments; ++i) {
      uint32_t a = base + uint32_t(j * segments + i), b = base + uint32_t(j * segments + (i + 1) % segments);
      uint32_t c = a + uint32_t(segments), d = b + uint32_t(segments);
      m.idx.insert(m.idx.end(), {a, b, c, b, d, c});
    }
}

// An open cylinder along y: trunks.
void add_cylinder(Mesh& m, V3 base_c, float r, float h, int segments) {
  const uint32_t base = uint32_t(m.p.size());
  for (int k = 0; k < 2; ++k)
    for (int i = 0; i < segments; ++i) {
      float ph = 6.2831853f * float(i) / float(segments);
      m.p.push_back({base_c.x + r * std::cos(ph), base_c.y + h * float(k), base_c.z + r * std::sin(ph)});
    }
  for (int i = 0; i < segments; ++i) {
    uint32_t a = base + uint32_t(i), b = base + uint32_t((i + 1) % segments);
    m.idx.insert(m.idx.end(), {a, a + uint32_t(segments), b, b, a + uint32_t(segments), b + uint32_t(segments)});
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Writes a scalable pbrt-v4 test scene: instanced forest on unique terrain"};
  std::string out;
  double instanced = 1e6, unique = 1e6;
  uint32_t seed = 1;
  int variants = 1;
  app.add_option("out", out, "Output folder (scene.pbrt and meshes/)")->required();
  app.add_option("--instanced-triangles", instanced, "Triangles traced through instances (e.g. 1e9)");
  app.add_option("--unique-triangles", unique, "Triangles stored once, in terrain tiles (e.g. 2e7)");
  app.add_option("--seed", seed, "Placement seed");
  app.add_option("--tree-variants", variants, "Distinct tree objects (each its own prototype and BVH)")
      ->check(CLI::Range(1, 100000));
  double island = 0;
  int prototypes = 0;
  app.add_option("--island", island, "A production island's shape at this scale (1: 90M quads, 5M curves, 28M instances)")
      ->check(CLI::Range(1e-6, 4.0));
  app.add_option("--prototypes", prototypes, "With --island: distinct instanced objects (default from the scale)");
  CLI11_PARSE(app, argc, argv);
  namespace fs = std::filesystem;
  if (island > 0) {
    const scenegen::IslandCounts c = scenegen::write_island(out, island, prototypes, seed);
    std::printf("%s: %zu unique quads in %zu files, %zu curves, %zu instances of %zu objects tracing %zu triangles\n",
                (fs::path(out) / "scene.pbrt").c_str(), c.quads, c.files, c.curves, c.instances, c.prototypes,
                c.instanced_triangles);
    return 0;
  }
  fs::create_directories(fs::path(out) / "meshes");

  // Terrain: a square of side L in tiles of at most ~1M triangles each.
  const float L = 400.f;
  const size_t tiles_per_side = std::max<size_t>(1, size_t(std::ceil(std::sqrt(unique / 1e6))));
  const int r = std::max(2, int(std::lround(std::sqrt(unique / double(tiles_per_side * tiles_per_side) / 2.0))) + 1);
  size_t unique_written = 0;
  std::ofstream s(fs::path(out) / "scene.pbrt");
  s << "# lantern-scenegen --instanced-triangles " << instanced << " --unique-triangles " << unique << " --seed " << seed
    << "\nLookAt -150 9 -150  -120 5 -120  0 1 0\nCamera \"perspective\" \"float fov\" [ 50 ]\n"
    << "Film \"rgb\" \"integer xresolution\" [ 960 ] \"integer yresolution\" [ 540 ] \"string filename\" \"forest.exr\"\n"
    << "Sampler \"independent\" \"integer pixelsamples\" [ 16 ]\nIntegrator \"bdpt\" \"integer maxdepth\" [ 6 ]\n"
    << "WorldBegin\nLightSource \"infinite\" \"rgb L\" [ 0.02 0.025 0.04 ]\n";
  s << "AttributeBegin\nMaterial \"diffuse\" \"rgb reflectance\" [ 0.25 0.3 0.15 ]\n";
  const float tile = L / float(tiles_per_side);
  for (size_t ty = 0; ty < tiles_per_side; ++ty)
    for (size_t tx = 0; tx < tiles_per_side; ++tx) {
      Mesh m = terrain_tile(-L / 2 + tile * float(tx), -L / 2 + tile * float(ty), tile, r);
      std::string name = "terrain_" + std::to_string(ty) + "_" + std::to_string(tx) + ".ply";
      write_ply(fs::path(out) / "meshes" / name, m);
      unique_written += m.faces();
      s << "Shape \"plymesh\" \"string filename\" \"meshes/" << name << "\"\n";
    }
  s << "AttributeEnd\n";

  // Prototypes: `variants` distinct trees, a bush and a rock.
  std::vector<Mesh> trees(static_cast<size_t>(variants));
  for (int v = 0; v < variants; ++v) {
    add_cylinder(trees[size_t(v)], {0, -0.2f, 0}, 0.25f, 4.f, 24);
    add_blob(trees[size_t(v)], {0, 5.f, 0}, {2.f, 2.6f, 2.f}, 64, 70, 0.12f, uint32_t(3 + v));
    std::string name = variants == 1 ? "tree" : "tree" + std::to_string(v);
    write_ply(fs::path(out) / "meshes" / (name + ".ply"), trees[size_t(v)]);
    s << "ObjectBegin \"" << name << "\"\nMaterial \"diffuse\" \"rgb reflectance\" [ 0.1 0.3 0.08 ]\n"
      << "Shape \"plymesh\" \"string filename\" \"meshes/" << name << ".ply\"\nObjectEnd\n";
  }
  Mesh bush, rock;
  add_blob(bush, {0, 0.5f, 0}, {1.2f, 0.8f, 1.2f}, 30, 34, 0.2f, 5);
  add_blob(rock, {0, 0.2f, 0}, {0.8f, 0.5f, 0.6f}, 20, 26, 0.3f, 7);
  write_ply(fs::path(out) / "meshes" / "bush.ply", bush);
  write_ply(fs::path(out) / "meshes" / "rock.ply", rock);
  s << "ObjectBegin \"bush\"\nMaterial \"coateddiffuse\" \"rgb reflectance\" [ 0.15 0.35 0.1 ] \"float roughness\" [ 0.3 ]\n"
       "Shape \"plymesh\" \"string filename\" \"meshes/bush.ply\"\nObjectEnd\n"
       "ObjectBegin \"rock\"\nMaterial \"conductor\" \"rgb reflectance\" [ 0.4 0.4 0.4 ] \"float roughness\" [ 0.4 ]\n"
       "Shape \"plymesh\" \"string filename\" \"meshes/rock.ply\"\nObjectEnd\n";

  // Placements: trees, bushes and rocks in the ratio 6 : 3 : 1 by count;
  // each tree is a variant drawn uniformly.
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> U(0.f, 1.f);
  size_t traced = 0, count[3] = {0, 0, 0};
  while (traced < size_t(instanced)) {
    float pick = U(rng);
    int k = pick < 0.6f ? 0 : pick < 0.9f ? 1 : 2;
    float x = (U(rng) - 0.5f) * L * 0.98f, z = (U(rng) - 0.5f) * L * 0.98f;
    int v = std::min(variants - 1, int(U(rng) * float(variants)));
    std::string name = k == 1 ? "bush" : k == 2 ? "rock" : variants == 1 ? "tree" : "tree" + std::to_string(v);
    s << "AttributeBegin Translate " << x << " " << terrain_height(x, z) << " " << z << " Rotate " << 360.f * U(rng)
      << " 0 1 0 Scale " << 0.7f + 0.6f * U(rng) << " " << 0.7f + 0.6f * U(rng) << " " << 0.7f + 0.6f * U(rng)
      << " ObjectInstance \"" << name << "\" AttributeEnd\n";
    traced += k == 0 ? trees[size_t(v)].faces() : k == 1 ? bush.faces() : rock.faces();
    ++count[k];
  }
  // Lanterns: small warm sphere lights near the camera's path.
  for (int i = 0; i < 6; ++i) {
    float x = -140.f + 8.f * float(i) + 3.f * U(rng), z = -140.f + 7.f * float(i) + 3.f * U(rng);
    s << "AttributeBegin\n  AreaLightSource \"diffuse\" \"rgb L\" [ 400 260 120 ]\n  Translate " << x << " "
      << terrain_height(x, z) + 1.2f << " " << z << "\n  Shape \"sphere\" \"float radius\" [ 0.05 ]\nAttributeEnd\n";
  }
  std::printf("%s: %zu unique triangles in %zu tiles; %zu instances (%zu trees, %zu bushes, %zu rocks) tracing %zu triangles\n",
              (fs::path(out) / "scene.pbrt").c_str(), unique_written, tiles_per_side * tiles_per_side,
              count[0] + count[1] + count[2], count[0], count[1], count[2], traced);
  return 0;
}
