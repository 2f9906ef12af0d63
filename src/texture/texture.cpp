// Evaluation of texture nodes by kind. Children are evaluated only when
// their weight is not zero, as pbrt-v4 does.
#include "texture/texture.h"

#include "texture/noise.h"
#include "texture/pattern.h"

namespace lantern {

namespace {

RGB image_value(const TexturePools& pools, const TextureNode& n, const TextureContext& c) {
  RGB v;
  if (n.cached >= 0) {
    TexCoord2D tc = n.mapping.map_filtered(c);
    // pbrt-v4: t = 0 is the bottom row of the image.
    TextureLookup q{Vec2(tc.st.x, 1.f - tc.st.y), Vec2(tc.dst_dx.x, -tc.dst_dx.y), Vec2(tc.dst_dy.x, -tc.dst_dy.y)};
    v = n.is_float ? RGB(pools.cache->lookup_float(n.cached, q)) : pools.cache->lookup_rgb(n.cached, q);
  } else {
    Vec2 st = n.mapping.map(c);
    st.y = 1.f - st.y;
    const TextureImage& img = pools.images[size_t(n.image)];
    v = n.is_float ? RGB(img.lookup_float(st, n.filter, n.wrap)) : img.lookup_rgb(st, n.filter, n.wrap);
  }
  v *= n.scale;
  return n.invert ? max(RGB(0.f), RGB(1.f) - v) : v;
}

// (1 - w) a + w b, skipping a side whose weight is zero; as a + w (b - a),
// which is exactly a where the two agree.
RGB blend(const TexturePools& pools, float w, const RGBTextureRef& a, const RGBTextureRef& b, const TextureContext& c) {
  if (w == 0.f) return pools.evaluate(a, c);
  if (w == 1.f) return pools.evaluate(b, c);
  RGB va = pools.evaluate(a, c);
  return va + w * (pools.evaluate(b, c) - va);
}

}  // namespace

RGB TexturePools::evaluate_node(const TextureNode& n, const TextureContext& c) const {
  switch (n.kind) {
    case TextureKind::Image: return image_value(*this, n, c);
    case TextureKind::Checkerboard: {
      float w = n.dimension == 3 ? checkerboard_3d(n.mapping.map3d(c)) : checkerboard_2d(n.mapping.map_filtered(c));
      return blend(*this, w, n.tex1, n.tex2, c);
    }
    case TextureKind::Dots: return evaluate(inside_polka_dot(n.mapping.map(c)) ? n.tex1 : n.tex2, c);
    case TextureKind::Scale: {
      const float s = evaluate(n.tex2, c)[0];  // a float texture, held broadcast
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
    case TextureKind::FBm: {
      TexCoord3D q = n.mapping.map3d(c);
      return RGB(fbm(q.p, q.dpdx, q.dpdy, n.roughness, n.octaves));
    }
    case TextureKind::Wrinkled: {
      TexCoord3D q = n.mapping.map3d(c);
      return RGB(turbulence(q.p, q.dpdx, q.dpdy, n.roughness, n.octaves));
    }
    case TextureKind::Windy: {
      TexCoord3D q = n.mapping.map3d(c);
      return RGB(windy(q.p, q.dpdx, q.dpdy));
    }
    case TextureKind::Marble: {
      TexCoord3D q = n.mapping.map3d(c);
      return clamp(marble(q.p, q.dpdx, q.dpdy, n.roughness, n.octaves, n.scale, n.variation), RGB(0.f), RGB(1.f));
    }
  }
  return RGB(0.f);
}

Spectrum TexturePools::evaluate_albedo(const RGBTextureRef& t, const TextureContext& c,
                                       const SampledWavelengths& l) const {
  if (t.node < 0 && t.spectrum >= 0) {
    const DenselySampledSpectrum& d = spectra[size_t(t.spectrum)];
    Spectrum v;
    for (int i = 0; i < kSpectrumSamples; ++i) v[i] = d(l.nm[size_t(i)]);
    return clamp(v, 0.f, 1.f);
  }
  const TextureNode* n = t.node < 0 ? nullptr : &nodes[size_t(t.node)];
  if (!n || !n->spectral) return albedo_spectrum(evaluate_reflectance(t, c), l);
  switch (n->kind) {
    case TextureKind::Checkerboard: {
      const float w = n->dimension == 3 ? checkerboard_3d(n->mapping.map3d(c)) : checkerboard_2d(n->mapping.map_filtered(c));
      return blend_albedo(w, n->tex1, n->tex2, c, l);
    }
    case TextureKind::Dots:
      return evaluate_albedo(inside_polka_dot(n->mapping.map(c)) ? n->tex1 : n->tex2, c, l);
    case TextureKind::Scale: {
      const float s = evaluate(n->tex2, c)[0];
      return s == 0.f ? Spectrum(0.f) : s * evaluate_albedo(n->tex1, c, l);
    }
    case TextureKind::Mix: return blend_albedo(evaluate_float(n->amount, c), n->tex1, n->tex2, c, l);
    case TextureKind::DirectionMix:
      return blend_albedo(1.f - std::fabs(glm::dot(c.n, n->dir)), n->tex1, n->tex2, c, l);
    default:  // (no other kind has children: never spectral)
      return albedo_spectrum(clamp(evaluate_node(*n, c), RGB(0.f), RGB(1.f)), l);
  }
}

Spectrum TexturePools::blend_albedo(float w, const RGBTextureRef& a, const RGBTextureRef& b, const TextureContext& c,
                                    const SampledWavelengths& l) const {
  if (w == 0.f) return evaluate_albedo(a, c, l);
  if (w == 1.f) return evaluate_albedo(b, c, l);
  return (1.f - w) * evaluate_albedo(a, c, l) + w * evaluate_albedo(b, c, l);
}

}  // namespace lantern
