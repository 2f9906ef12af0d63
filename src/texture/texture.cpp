// Evaluation of texture nodes by kind. Children are evaluated only when
// their weight is not zero, as pbrt-v4 does.
#include "texture/texture.h"

#include "texture/noise.h"
#include "texture/pattern.h"

namespace lantern {

namespace {

RGB image_value(const TexturePools& pools, const TextureNode& n, const TextureContext& c) {
  Vec2 st = n.mapping.map(c);
  st.y = 1.f - st.y;  // pbrt-v4: t = 0 is the bottom row of the image
  const TextureImage& img = pools.images[size_t(n.image)];
  RGB v = n.is_float ? RGB(img.lookup_float(st, n.filter, n.wrap)) : img.lookup_rgb(st, n.filter, n.wrap);
  v *= n.scale;
  return n.invert ? glm::max(RGB(0.f), RGB(1.f) - v) : v;
}

// (1 - w) a + w b, skipping a side whose weight is zero.
RGB blend(const TexturePools& pools, float w, const TextureRef& a, const TextureRef& b, const TextureContext& c) {
  RGB r(0.f);
  if (w != 1.f) r += (1.f - w) * pools.evaluate(a, c);
  if (w != 0.f) r += w * pools.evaluate(b, c);
  return r;
}

}  // namespace

RGB TexturePools::evaluate_node(const TextureNode& n, const TextureContext& c) const {
  switch (n.kind) {
    case TextureKind::Image: return image_value(*this, n, c);
    case TextureKind::Checkerboard: {
      float w = n.dimension == 3 ? checkerboard_3d(n.mapping.point(c)) : checkerboard_2d(n.mapping.map(c));
      return blend(*this, w, n.tex1, n.tex2, c);
    }
    case TextureKind::Dots: return evaluate(inside_polka_dot(n.mapping.map(c)) ? n.tex1 : n.tex2, c);
    case TextureKind::Scale: {
      float s = evaluate_float(n.tex2, c);
      return s == 0.f ? RGB(0.f) : s * evaluate(n.tex1, c);
    }
    case TextureKind::Mix: return blend(*this, evaluate_float(n.amount, c), n.tex1, n.tex2, c);
    case TextureKind::DirectionMix:
      // amt |n . dir| weighs tex1.
      return blend(*this, 1.f - std::fabs(glm::dot(c.n, n.dir)), n.tex1, n.tex2, c);
    case TextureKind::Bilerp: {
      Vec2 st = n.mapping.map(c);
      return (1 - st.x) * (1 - st.y) * n.v00 + (1 - st.x) * st.y * n.v01 + st.x * (1 - st.y) * n.v10 +
             st.x * st.y * n.v11;
    }
    case TextureKind::FBm: return RGB(fbm(n.mapping.point(c), n.roughness, n.octaves));
    case TextureKind::Wrinkled: return RGB(turbulence(n.mapping.point(c), n.roughness, n.octaves));
    case TextureKind::Windy: return RGB(windy(n.mapping.point(c)));
    case TextureKind::Marble:
      return glm::clamp(marble(n.mapping.point(c), n.roughness, n.octaves, n.scale, n.variation), RGB(0.f), RGB(1.f));
  }
  return RGB(0.f);
}

}  // namespace lantern
