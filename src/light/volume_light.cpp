#include "light/volume_light.h"

#include <algorithm>

namespace lantern {

namespace {

// Blocks per axis: the grid's samples, at most 64 (a bound per block costs
// a look at every sample that weighs on it, once, at load).
constexpr int kMaxBlocksPerAxis = 64;

// The box of a grid medium: unit coordinates to p0..p1 of the medium's space.
Mat4 render_from_grid_box(const GridLayout& g) {
  Mat4 box(1.f);
  box[0][0] = g.p1.x - g.p0.x, box[1][1] = g.p1.y - g.p0.y, box[2][2] = g.p1.z - g.p0.z;
  box[3] = Vec4(g.p0, 1.f);
  return glm::inverse(g.medium_from_render) * box;
}

}  // namespace

bool make_volume_light(const MediumPools& media, MediumHandle h, const Vec3& lo, const Vec3& hi, VolumeLight* out) {
  VolumeLight v;
  v.medium = h;
  // bound(u0, u1): the block's weight, following the largest sigma_a Le in it
  std::vector<float> weights;
  auto fill = [&](auto&& bound) {
    const size_t count = size_t(v.res[0]) * size_t(v.res[1]) * size_t(v.res[2]);
    weights.resize(count);
    for (int z = 0; z < v.res[2]; ++z)
      for (int y = 0; y < v.res[1]; ++y)
        for (int x = 0; x < v.res[0]; ++x) {
          const Vec3 u0 = Vec3(float(x), float(y), float(z)) / Vec3(v.res[0], v.res[1], v.res[2]);
          const Vec3 u1 = Vec3(float(x + 1), float(y + 1), float(z + 1)) / Vec3(v.res[0], v.res[1], v.res[2]);
          weights[(size_t(z) * size_t(v.res[1]) + size_t(y)) * size_t(v.res[0]) + size_t(x)] = bound(u0, u1);
        }
  };
  auto grid_res = [&](const GridLayout& g) {
    v.res[0] = std::min(g.nx, kMaxBlocksPerAxis);
    v.res[1] = std::min(g.ny, kMaxBlocksPerAxis);
    v.res[2] = std::min(g.nz, kMaxBlocksPerAxis);
    v.render_from_unit = render_from_grid_box(g);
  };
  switch (h.kind()) {
    case MediumKind::Homogeneous: {
      const HomogeneousMedium& m = media.homogeneous[h.index()];
      v.render_from_unit = Mat4(1.f);
      v.render_from_unit[0][0] = hi.x - lo.x, v.render_from_unit[1][1] = hi.y - lo.y, v.render_from_unit[2][2] = hi.z - lo.z;
      v.render_from_unit[3] = Vec4(lo, 1.f);
      weights = {max_component(m.sigma_a * m.Le)};
      break;
    }
    case MediumKind::Grid: {
      const GridMedium& m = media.grid[h.index()];
      grid_res(m.density);
      const float a = max_component(m.per_density.sigma_a);
      fill([&](const Vec3& u0, const Vec3& u1) {
        const float rho = max_over(m.density, u0, u1, [&](int x, int y, int z) { return m.density.values[m.density.offset(x, y, z)]; });
        return rho > 0.f ? a * rho * m.emission.bound(u0, u1) : 0.f;
      });
      break;
    }
    case MediumKind::RgbGrid: {
      const RgbGridMedium& m = media.rgb_grid[h.index()];
      const RgbGrid& g = m.grid;
      grid_res(g);
      fill([&](const Vec3& u0, const Vec3& u1) {
        const float a = g.sigma_a.empty() ? max_component(g.constant_a)
                                          : max_over(g, u0, u1, [&](int x, int y, int z) { return max_component(g.sigma_a[g.offset(x, y, z)]); });
        const float e = max_over(g, u0, u1, [&](int x, int y, int z) { return max_component(g.Le[g.offset(x, y, z)]); });
        return a * e * m.Le_scale;
      });
      break;
    }
    case MediumKind::Vdb: {  // the temperature grid's blocks
      const VdbMedium& m = media.vdb[h.index()];
      if (!m.emits()) return false;
      v.render_from_unit = m.temperature.block_box(v.res);
      const float a = max_component(m.per_density.sigma_a) * m.Le_scale;
      const std::vector<float>& hottest = m.temperature.block_maxima();  // largest |sample| per block
      const bool uniform = m.heat.scale < 0.f || std::any_of(hottest.begin(), hottest.end(), [](float t) { return std::isinf(t); });
      for (float t : hottest) {
        // positive wherever the block can emit: its hottest sample is
        // then above 100 K (the density is left out: a block where it is
        // zero only wastes its samples). A negative scale makes the
        // coldest sample the hottest, which the blocks do not keep.
        const float kelvin = uniform ? kInfinity : m.heat.kelvin(t);
        weights.push_back(kelvin > 100.f ? a * std::max(max_component(m.heat.blackbody.at(kelvin)), 1e-30f) : 0.f);
      }
      break;
    }
    default: return false;
  }
  v.unit_from_render = glm::inverse(v.render_from_unit);
  v.volume = std::fabs(glm::determinant(glm::mat3(v.render_from_unit)));
  if (!(v.volume > 0.f) || !std::isfinite(v.volume)) return false;
  double total = 0.0;
  for (float w : weights) total += double(w);
  if (!(total > 0.0)) return false;
  v.power = float(4.0 * kPi * total / double(weights.size()) * double(v.volume));
  v.blocks = Distribution1D(std::move(weights));
  v.lo = Vec3(kInfinity), v.hi = Vec3(-kInfinity);
  for (int c = 0; c < 8; ++c) {
    const Vec3 p = Vec3(v.render_from_unit * Vec4(float(c & 1), float((c >> 1) & 1), float(c >> 2), 1.f));
    v.lo = glm::min(v.lo, p), v.hi = glm::max(v.hi, p);
  }
  *out = std::move(v);
  return true;
}

Vec3 sample_volume_point(const VolumeLight& v, const Vec3& u, float* pdf) {
  float pdf_block;
  size_t block;
  const float x = v.blocks.sample_continuous(u.x, &pdf_block, &block);  // pdf_block: per unit of [0, 1)
  const size_t n = v.blocks.size();
  const float in_block = std::clamp(x * float(n) - float(block), 0.f, kOneMinusEpsilon);  // uniform again
  const size_t bx = block % size_t(v.res[0]), by = block / size_t(v.res[0]) % size_t(v.res[1]),
               bz = block / (size_t(v.res[0]) * size_t(v.res[1]));
  const Vec3 unit = (Vec3(float(bx), float(by), float(bz)) + Vec3(in_block, u.y, u.z)) / Vec3(v.res[0], v.res[1], v.res[2]);
  *pdf = v.blocks.discrete_pmf(block) * float(n) / v.volume;
  return Vec3(v.render_from_unit * Vec4(unit, 1.f));
}

float volume_point_density(const VolumeLight& v, const Vec3& p) {
  const Vec3 unit = Vec3(v.unit_from_render * Vec4(p, 1.f));
  if (!(unit.x >= 0.f && unit.y >= 0.f && unit.z >= 0.f && unit.x < 1.f && unit.y < 1.f && unit.z < 1.f)) return 0.f;
  const int bx = std::min(int(unit.x * float(v.res[0])), v.res[0] - 1);
  const int by = std::min(int(unit.y * float(v.res[1])), v.res[1] - 1);
  const int bz = std::min(int(unit.z * float(v.res[2])), v.res[2] - 1);
  const size_t block = (size_t(bz) * size_t(v.res[1]) + size_t(by)) * size_t(v.res[0]) + size_t(bx);
  return v.blocks.discrete_pmf(block) * float(v.blocks.size()) / v.volume;
}

}  // namespace lantern
