// Bounds on a float texture's values, by interval arithmetic over its tree:
// each kind maps its children's bounds to its own. A kind whose values its
// parameters do not bound (an image read through the cache, bilerp's
// unbounded coordinates, the signed noises) is wide; so is anything that
// would need 0 times infinity or infinity minus infinity.
#include <algorithm>
#include <cmath>
#include <initializer_list>

#include "texture/texture.h"

namespace lantern {

namespace {

constexpr ValueRange kWide{};

bool finite(const ValueRange& r) { return std::isfinite(r.lo) && std::isfinite(r.hi); }

ValueRange hull(const ValueRange& a, const ValueRange& b) { return {std::min(a.lo, b.lo), std::max(a.hi, b.hi)}; }

// The extremes of a function linear in each argument lie at the corners of
// the box of its arguments' bounds.
ValueRange over_corners(std::initializer_list<float> corners) {
  ValueRange r{kInfinity, -kInfinity};
  for (const float c : corners) {
    if (std::isnan(c)) return kWide;
    r.lo = std::min(r.lo, c);
    r.hi = std::max(r.hi, c);
  }
  return r;
}

ValueRange product(const ValueRange& a, const ValueRange& b) {
  // (0 times anything is 0: a corner of 0 and infinity stands for 0)
  const auto mul = [](float x, float y) { return x == 0.f || y == 0.f ? 0.f : x * y; };
  return over_corners({mul(a.lo, b.lo), mul(a.lo, b.hi), mul(a.hi, b.lo), mul(a.hi, b.hi)});
}

// a + w (b - a) for w within `w`, a and b within theirs (texture.cpp's
// blend). The amount may be unbounded (a mix by a noise): at an infinite
// one, the blend of a and b is a where they agree, and infinite otherwise.
ValueRange blend(const ValueRange& w, const ValueRange& a, const ValueRange& b) {
  if (!finite(a) || !finite(b)) return kWide;
  const auto at = [](float w, float a, float b) { return b == a ? a : a + w * (b - a); };
  return over_corners({at(w.lo, a.lo, b.lo), at(w.lo, a.lo, b.hi), at(w.lo, a.hi, b.lo), at(w.lo, a.hi, b.hi),
                       at(w.hi, a.lo, b.lo), at(w.hi, a.lo, b.hi), at(w.hi, a.hi, b.lo), at(w.hi, a.hi, b.hi)});
}

// An image's values (its texels' channels and alpha, which its lookups
// interpolate), scaled and inverted as texture.cpp's image_value does; 0
// too where a "black" wrap reads it outside the image. (A lookup more than
// a billion texels out reads 0 whatever the wrap: a measure of nothing.)
// Resident images found theirs at load; an image read through the cache
// has the bounds its prepared file recorded, and none (wide) if it was
// used as it is.
ValueRange image_range(const TexturePools& pools, const TextureNode& n) {
  ValueRange r;
  if (n.image >= 0) {
    const TextureImage& img = pools.images[size_t(n.image)];
    r = {img.least, img.greatest};
  } else if (n.cached >= 0 && pools.cache) {
    const auto [lo, hi] = pools.cache->bounds(n.cached);
    r = {lo, hi};
  } else {
    return kWide;
  }
  if (!(r.lo <= r.hi)) return kWide;  // (an image made otherwise than by loading one)
  if (n.wrap == WrapMode::Black) r = hull(r, {0.f, 0.f});
  r = product(r, {n.scale, n.scale});
  return n.invert ? ValueRange{std::max(0.f, 1.f - r.hi), std::max(0.f, 1.f - r.lo)} : r;
}

}  // namespace

ValueRange TexturePools::range(const FloatTextureRef& t) const {
  return t.node < 0 ? ValueRange{t.value, t.value} : range_of_node(nodes[size_t(t.node)]);
}

ValueRange TexturePools::range(const RGBTextureRef& t) const {
  if (t.node >= 0) return range_of_node(nodes[size_t(t.node)]);
  return {std::min({t.value[0], t.value[1], t.value[2]}), std::max({t.value[0], t.value[1], t.value[2]})};
}

ValueRange TexturePools::range_of_node(const TextureNode& n) const {
  constexpr ValueRange unit{0.f, 1.f};
  switch (n.kind) {
    case TextureKind::Checkerboard:  // (filtered: a blend by a weight in [0, 1])
    case TextureKind::DirectionMix:
    case TextureKind::Dots:
      return hull(range(n.tex1), range(n.tex2));
    case TextureKind::Scale:
      return product(range(n.tex1), range(n.tex2));
    case TextureKind::Mix:
      return blend(range(n.amount), range(n.tex1), range(n.tex2));
    case TextureKind::Wrinkled:  // a sum of |noise| and 0.2, weighted by powers of the roughness
      return n.roughness >= 0.f ? ValueRange{0.f, kInfinity} : kWide;
    case TextureKind::Marble:
      return unit;  // (clamped)
    case TextureKind::Image:
      return image_range(*this, n);
    case TextureKind::Bilerp:
    case TextureKind::FBm:
    case TextureKind::Windy:
      break;
  }
  return kWide;
}

}  // namespace lantern
