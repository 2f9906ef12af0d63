#include "medium/nanovdb_grid.h"

#include <iostream>  // before GridValidator.h, which needs it
#include <nanovdb/NanoVDB.h>
#include <nanovdb/util/GridValidator.h>
#include <nanovdb/util/IO.h>

#include <cstring>
#include <fstream>
#include <stdexcept>

namespace lantern {

struct VdbGrid::Data {
  nanovdb::GridHandle<nanovdb::HostBuffer> handle;
  const nanovdb::FloatGrid* grid = nullptr;
  LatticeFrame frame;   // index space
  LatticeFrame blocks;  // blocks of `block` cells: index space / block
  int block = 8;
  int first[3] = {0, 0, 0}, count[3] = {1, 1, 1};  // the blocks the box covers
  std::vector<float> block_max;                    // per block, its largest sample (x fastest)

  float block_value(const int b[3]) const {
    const int x = b[0] - first[0], y = b[1] - first[1], z = b[2] - first[2];
    if (x < 0 || y < 0 || z < 0 || x >= count[0] || y >= count[1] || z >= count[2]) return 0.f;
    return block_max[(size_t(z) * size_t(count[1]) + size_t(y)) * size_t(count[0]) + size_t(x)];
  }
};

namespace {

// A floor division for negative coordinates too.
int floor_div(int a, int b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

// Checks the file's layout before NanoVDB reads it, so that a malformed
// file is an error, not an allocation its header asks for or a read past
// a name: per segment, a 16-byte header, then each grid's 176 bytes of
// metadata and its name, then the grids (nanovdb/util/IO.h).
std::vector<std::string> check_layout(const std::string& path) {
  std::vector<std::string> names;
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) throw std::runtime_error("cannot open \"" + path + "\"");
  const uint64_t size = uint64_t(in.tellg());
  in.seekg(0);
  uint64_t at = 0;
  while (at < size) {
    nanovdb::io::Header header;
    static_assert(sizeof header == 16);
    if (size - at < sizeof header || !in.read(reinterpret_cast<char*>(&header), sizeof header))
      throw std::runtime_error("is cut short (a segment header)");
    if (header.magic != NANOVDB_MAGIC_NUMBER) throw std::runtime_error("is not a NanoVDB file (no magic number)");
    if (header.codec != nanovdb::io::Codec::NONE)
      throw std::runtime_error("is compressed; only uncompressed NanoVDB files are read (nanovdb_convert without -z/-b)");
    if (header.gridCount == 0) throw std::runtime_error("has a segment with no grids");
    at += sizeof header;
    uint64_t data = 0;
    for (int g = 0; g < header.gridCount; ++g) {
      nanovdb::io::MetaData meta;
      if (size - at < sizeof meta || !in.read(reinterpret_cast<char*>(&meta), sizeof meta))
        throw std::runtime_error("is cut short (grid metadata)");
      at += sizeof meta;
      if (meta.nameSize == 0 || meta.nameSize > 4096 || size - at < meta.nameSize)
        throw std::runtime_error("has a grid name of a bad length");
      std::string name(meta.nameSize, '\0');
      in.read(name.data(), meta.nameSize);
      if (name.back() != '\0') throw std::runtime_error("has a grid name that does not end");
      names.push_back(name.c_str());
      at += meta.nameSize;
      if (meta.fileSize != meta.gridSize || meta.gridSize > size)
        throw std::runtime_error("is cut short or malformed (a grid larger than the file)");
      data += meta.fileSize;
    }
    if (size - at < data) throw std::runtime_error("is cut short (grid data)");
    at += data;
    in.seekg(std::streamoff(at));
  }
  return names;
}

// NanoVDB's validator checks the nodes against the size the grid states;
// that size, and the arrays of nodes of each level that the block maxima
// read, must lie in the buffer actually read.
bool within_buffer(const nanovdb::FloatGrid& grid, uint64_t size) {
  const auto* begin = reinterpret_cast<const uint8_t*>(&grid);
  const uint8_t* end = begin + size;
  if (size < sizeof(nanovdb::FloatGrid) + sizeof(nanovdb::FloatTree) || grid.gridSize() > size) return false;
  const auto& tree = grid.tree();
  auto fits = [&](const auto* first, uint32_t count) {
    const auto* p = reinterpret_cast<const uint8_t*>(first);
    return count == 0 || (p >= begin && p <= end && uint64_t(end - p) / sizeof(*first) >= count);
  };
  return fits(tree.getFirstLeaf(), tree.nodeCount(0)) && fits(tree.getFirstLower(), tree.nodeCount(1)) &&
         fits(tree.getFirstUpper(), tree.nodeCount(2));
}

// Blocks [floor((lo - 1) / B), floor(hi / B)] hold the cells next to
// samples [lo, hi] on each axis.
template <class Mark>
void blocks_near(const nanovdb::Coord& lo, const nanovdb::Coord& hi, int B, Mark&& mark) {
  int a[3], b[3];
  for (int k = 0; k < 3; ++k) a[k] = floor_div(lo[k] - 1, B), b[k] = floor_div(hi[k], B);
  for (int z = a[2]; z <= b[2]; ++z)
    for (int y = a[1]; y <= b[1]; ++y)
      for (int x = a[0]; x <= b[0]; ++x) mark(x, y, z);
}

// The blocks' largest samples, from the leaves and from the tiles of
// the internal nodes; any tile of the root that holds a value, or a
// background that is not zero, leaves every block occupied.
void find_block_maxima(VdbGrid::Data& d) {
  const auto& tree = d.grid->tree();
  const size_t n = size_t(d.count[0]) * d.count[1] * d.count[2];
  bool everywhere = tree.background() != 0.f;
  const auto& root = tree.root();
  for (uint32_t i = 0; i < root.tileCount(); ++i) {
    const auto* tile = root.data()->tile(i);
    if (!tile->isChild() && tile->value != 0.f) everywhere = true;
  }
  if (everywhere) {
    d.block_max.assign(n, std::numeric_limits<float>::infinity());
    return;
  }
  d.block_max.assign(n, 0.f);
  auto raise = [&](const nanovdb::Coord& lo, const nanovdb::Coord& hi, float v) {
    blocks_near(lo, hi, d.block, [&](int x, int y, int z) {
      const int b[3] = {x - d.first[0], y - d.first[1], z - d.first[2]};
      if (b[0] < 0 || b[1] < 0 || b[2] < 0 || b[0] >= d.count[0] || b[1] >= d.count[1] || b[2] >= d.count[2]) return;
      float& m = d.block_max[(size_t(b[2]) * d.count[1] + b[1]) * d.count[0] + b[0]];
      m = std::max(m, v);
    });
  };
  const auto* leaf = tree.getFirstLeaf();
  for (uint32_t i = 0; i < tree.nodeCount(0); ++i, ++leaf) {
    float v = 0.f;
    for (uint32_t j = 0; j < 512; ++j) v = std::max(v, std::fabs(leaf->getValue(j)));
    if (v > 0.f) raise(leaf->origin(), leaf->origin() + nanovdb::Coord(7), v);
  }
  auto tiles = [&](const auto* node, uint32_t nodes, uint32_t entries, int dim) {
    for (uint32_t i = 0; i < nodes; ++i, ++node)
      for (uint32_t e = 0; e < entries; ++e) {
        if (node->data()->isChild(e)) continue;
        const float v = std::fabs(node->data()->getValue(e));
        if (v > 0.f) {
          const nanovdb::Coord lo = node->offsetToGlobalCoord(e);
          raise(lo, lo + nanovdb::Coord(dim - 1), v);
        }
      }
  };
  tiles(tree.getFirstLower(), tree.nodeCount(1), 16 * 16 * 16, 8);
  tiles(tree.getFirstUpper(), tree.nodeCount(2), 32 * 32 * 32, 128);
}

}  // namespace

VdbGrid VdbGrid::load(const std::string& path, const std::string& name, const Mat4& medium_from_render) {
  check_layout(path);
  auto d = std::make_shared<Data>();
  d->handle = nanovdb::io::readGrid<nanovdb::HostBuffer>(path, name);
  if (!d->handle) throw std::runtime_error("has no grid named \"" + name + "\"");
  // The handle holds this one grid. (GridHandle::grid looks for it by the
  // index the grid states, walking past the buffer when that is wrong.)
  if (d->handle.size() < sizeof(nanovdb::GridData)) throw std::runtime_error("grid \"" + name + "\" is malformed");
  d->grid = reinterpret_cast<const nanovdb::FloatGrid*>(d->handle.data());
  if (d->grid->gridType() != nanovdb::GridType::Float) throw std::runtime_error("grid \"" + name + "\" does not hold floats");
  if (!within_buffer(*d->grid, d->handle.size()) || !nanovdb::isValid(*d->grid, true, false))
    throw std::runtime_error("grid \"" + name + "\" is malformed");
  const nanovdb::CoordBBox box = d->grid->indexBBox();
  if (box.empty()) throw std::runtime_error("grid \"" + name + "\" has no active voxels");
  for (int k = 0; k < 3; ++k)  // hostile extents would overflow the block counts
    if (int64_t(box.max()[k]) - int64_t(box.min()[k]) >= (int64_t(1) << 26) || std::abs(box.min()[k]) >= (1 << 29) ||
        std::abs(box.max()[k]) >= (1 << 29))
      throw std::runtime_error("grid \"" + name + "\" has an index box of hostile size");
  // index coordinates from the medium's space: the grid's map, inverted
  const nanovdb::Map& map = d->grid->map();
  double det = 0.0;
  for (int j = 0; j < 3; ++j)  // the inverse matrix's determinant, by its first row
    det += map.mInvMatD[j] * (map.mInvMatD[3 + (j + 1) % 3] * map.mInvMatD[6 + (j + 2) % 3] -
                              map.mInvMatD[3 + (j + 2) % 3] * map.mInvMatD[6 + (j + 1) % 3]);
  bool finite = std::isfinite(det) && det != 0.0;
  for (int j = 0; j < 9; ++j) finite = finite && std::isfinite(map.mInvMatD[j]);
  for (int j = 0; j < 3; ++j) finite = finite && std::isfinite(map.mVecD[j]);
  if (!finite) throw std::runtime_error("grid \"" + name + "\" has a singular or non-finite transform");
  double a[3][4], lo[3], hi[3];
  for (int k = 0; k < 3; ++k) {
    for (int j = 0; j < 3; ++j) a[k][j] = map.mInvMatD[3 * k + j];
    a[k][3] = 0.0;
    for (int j = 0; j < 3; ++j) a[k][3] -= map.mInvMatD[3 * k + j] * map.mVecD[j];
    lo[k] = box.min()[k], hi[k] = double(box.max()[k]) + 1.0;
  }
  d->frame = LatticeFrame::compose(a, medium_from_render, lo, hi);
  // blocks of 8 cells, coarser where the box is huge (at most 2^24 blocks)
  auto blocks_for = [&](int B) {
    uint64_t total = 1;
    for (int k = 0; k < 3; ++k) total *= uint64_t(floor_div(box.max()[k], B) - floor_div(box.min()[k], B) + 1);
    return total;
  };
  while (blocks_for(d->block) > (uint64_t(1) << 24) && d->block < (1 << 24)) d->block *= 2;
  double ab[3][4], blo[3], bhi[3];
  for (int k = 0; k < 3; ++k) {
    for (int j = 0; j < 4; ++j) ab[k][j] = a[k][j] / d->block;
    blo[k] = lo[k] / d->block, bhi[k] = hi[k] / d->block;
    d->first[k] = floor_div(box.min()[k], d->block);
    d->count[k] = floor_div(box.max()[k], d->block) - d->first[k] + 1;
  }
  d->blocks = LatticeFrame::compose(ab, medium_from_render, blo, bhi);
  find_block_maxima(*d);
  VdbGrid g;
  g.data = std::move(d);
  return g;
}

float VdbGrid::density(const Vec3& p) const {
  const Data& d = *data;
  double g[3];
  int c[3];
  for (int k = 0; k < 3; ++k) {
    const double* m = d.frame.m[k];
    g[k] = m[0] * p.x + m[1] * p.y + m[2] * p.z + m[3];
    if (!(g[k] >= d.frame.lo[k] && g[k] <= d.frame.hi[k])) return 0.f;
    c[k] = int(std::floor(g[k]));
    g[k] -= c[k];
  }
  auto acc = d.grid->getAccessor();
  double v = 0.0;
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b)
      for (int e = 0; e < 2; ++e)
        v += acc.getValue(nanovdb::Coord(c[0] + a, c[1] + b, c[2] + e)) * (a ? g[0] : 1.0 - g[0]) *
             (b ? g[1] : 1.0 - g[1]) * (e ? g[2] : 1.0 - g[2]);
  return float(v);
}

float VdbGrid::integrate(const Vec3& o, const Vec3& dir, float t0, float t1, float target, float* t_hit) const {
  const Data& d = *data;
  auto acc = d.grid->getAccessor();
  lattice::DepthSum depth(target, t_hit);
  auto cell = [&](const int c[3], double t, double t_exit, const double f0[3], const double dg[3]) {
    return depth.add(c, t, t_exit, f0, dg, [&](int x, int y, int z) { return acc.getValue(nanovdb::Coord(x, y, z)); });
  };
  lattice::walk(d.blocks, o, dir, t0, t1, [&](const int b[3], double t, double t_exit, const double*, const double*) {
    if (d.block_value(b) == 0.f) return false;  // no sample of its cells is stored
    lattice::walk(d.frame, o, dir, float(t), float(t_exit), cell);
    return depth.reached;
  });
  return depth.result();
}

bool VdbGrid::has_grid(const std::string& path, const std::string& name) {
  for (const std::string& n : check_layout(path))
    if (n == name) return true;
  return false;
}

Mat4 VdbGrid::block_box(int res[3]) const {
  const Data& d = *data;
  glm::dmat4 block_from_render(1.0);  // glm: [column][row]
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 4; ++j) block_from_render[j][k] = d.blocks.m[k][j];
  glm::dmat4 block_from_unit(1.0);
  for (int k = 0; k < 3; ++k) {
    res[k] = d.count[k];
    block_from_unit[k][k] = double(d.count[k]);
    block_from_unit[3][k] = double(d.first[k]);
  }
  return Mat4(glm::inverse(block_from_render) * block_from_unit);
}

const std::vector<float>& VdbGrid::block_maxima() const { return data->block_max; }

size_t VdbGrid::occupied_blocks(size_t* total) const {
  *total = data->block_max.size();
  size_t n = 0;
  for (float v : data->block_max) n += v != 0.f;
  return n;
}

}  // namespace lantern
