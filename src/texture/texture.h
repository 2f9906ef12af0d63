// Textures: every material parameter pbrt-v4 lets be a texture is a
// FloatTextureRef or an RGBTextureRef, a constant or a node in TexturePools. A constant is read from
// the material's own pool entry with one branch, so a scene without
// textures pays nothing more. Nodes are evaluated by kind (texture.cpp);
// the families live in their own files: image (image.h), checkerboard and
// dots (pattern.h), scale, mix, directionmix and bilerp (combine.h), and
// the Perlin-noise family (noise.h).
#pragma once

#include <memory>
#include <vector>

#include "color/densely_sampled_spectrum.h"
#include "texture/image.h"
#include "texture/mapping.h"
#include "texture/texture_cache.h"

namespace lantern {

// Bounds on the values a float texture can take anywhere (texture_range.cpp);
// infinite where nothing bounds them.
struct ValueRange {
  float lo = -kInfinity, hi = kInfinity;
  bool contains(float v) const { return lo <= v && v <= hi; }
};

// A float parameter and a colour parameter are distinct types, as pbrt-v4's
// FloatTexture and SpectrumTexture are: a float is never turned into a
// spectrum, and a colour is never read as one of its channels.
template <class T>
struct TextureRefOf {
  T value{0.f};       // the constant, when node < 0
  int32_t node = -1;  // index into TexturePools::nodes
  // A constant given as a spectrum (a file, pairs, a named metal): index
  // into TexturePools::spectra, which the spectral renderer reads; value
  // holds its colour for the RGB renderer.
  int32_t spectrum = -1;

  static TextureRefOf constant(T v) { return TextureRefOf{v, -1, -1}; }
  bool is_constant() const { return node < 0; }
};
using FloatTextureRef = TextureRefOf<float>;
using RGBTextureRef = TextureRefOf<RGB>;

// A float texture where a node's children are held: nodes evaluate to
// colour, a float node's in every channel.
inline RGBTextureRef broadcast(const FloatTextureRef& f) { return RGBTextureRef{RGB(f.value), f.node, -1}; }

enum class TextureKind : uint8_t {
  Image, Checkerboard, Dots, Scale, Mix, DirectionMix, Bilerp, FBm, Wrinkled, Windy, Marble
};

// One texture of a scene. Float textures hold their value in every channel.
struct TextureNode {
  TextureKind kind = TextureKind::Image;
  bool is_float = false;
  TextureMapping mapping;
  RGBTextureRef tex1, tex2;  // checkerboard, mix, directionmix; dots: off, on the dots; scale: tex, scale
  FloatTextureRef amount;    // mix
  Vec3 dir{0.f, 1.f, 0.f};  // directionmix, world space
  RGB v00{0.f}, v01{1.f}, v10{0.f}, v11{1.f};  // bilerp
  int dimension = 2;      // checkerboard
  int octaves = 8;        // noise family
  float roughness = 0.5f, variation = 0.2f, scale = 1.f;  // noise family; image: scale
  int32_t image = -1;   // image: resident (TexturePools::images), or
  int32_t cached = -1;  // read through TexturePools::cache
  ImageFilter filter = ImageFilter::Bilinear;
  float max_anisotropy = 8.f;
  WrapMode wrap = WrapMode::Repeat;
  bool invert = false;
  // A leaf below (tex1 or tex2, or deeper) holds a spectrum (given by
  // samples, or a colour of a space other than sRGB): the spectral
  // renderer evaluates the tree by wavelength as a reflectance
  // (evaluate_albedo).
  bool spectral = false;
};

struct TexturePools {
  std::vector<TextureImage> images;
  std::vector<TextureNode> nodes;
  std::vector<DenselySampledSpectrum> spectra;  // constants given as spectra (TextureRefOf::spectrum)
  std::shared_ptr<TextureCache> cache;  // made when the first image texture is
  // Some texture filters over the pixel footprint (texture/footprint.h):
  // only then do the integrators compute one per hit.
  bool uses_footprint = false;

  RGB evaluate(const RGBTextureRef& t, const TextureContext& c) const {
    return t.node < 0 ? t.value : evaluate_node(nodes[size_t(t.node)], c);
  }
  float evaluate_float(const FloatTextureRef& t, const TextureContext& c) const {
    return t.node < 0 ? t.value : evaluate_node(nodes[size_t(t.node)], c)[0];
  }
  // Bounds on what the float texture evaluates to, for the questions a
  // scene asks before it renders (can this roughness reach 0?). Wide where
  // a kind's values are not bounded by its parameters or held: images read
  // through the cache, bilerp, fbm and windy.
  ValueRange range(const FloatTextureRef& t) const;
  float image_mean(int32_t image) const { return images[size_t(image)].mean; }
  // Reflectances are clamped to [0, 1], as pbrt-v4's materials do.
  RGB evaluate_reflectance(const RGBTextureRef& t, const TextureContext& c) const {
    return clamp(evaluate(t, c), RGB(0.f), RGB(1.f));
  }

  // A reflectance whose tree has a spectrum among its leaves, at the
  // wavelengths, as pbrt-v4 evaluates its spectrum textures: each leaf's
  // colour becomes an albedo spectrum (clamped into [0, 1]) and the nodes
  // combine spectra. Other trees are evaluated in colour and the result
  // turned into a spectrum (the materials' kernels,
  // material/bsdf_kernel.h), which keeps their images as they were; so are
  // trees giving unbounded values (eta, k, sigma_a): a leaf of another
  // colour space is fitted as a reflectance when its texture is defined.
  bool spectral_tree(const RGBTextureRef& t) const { return t.node >= 0 && nodes[size_t(t.node)].spectral; }
  Spectrum evaluate_albedo(const RGBTextureRef& t, const TextureContext& c, const SampledWavelengths& l) const;

 private:
  RGB evaluate_node(const TextureNode& n, const TextureContext& c) const;
  ValueRange range(const RGBTextureRef& t) const;  // (over the channels)
  ValueRange range_of_node(const TextureNode& n) const;
  Spectrum blend_albedo(float w, const RGBTextureRef& a, const RGBTextureRef& b, const TextureContext& c,
                        const SampledWavelengths& l) const;
};

}  // namespace lantern
