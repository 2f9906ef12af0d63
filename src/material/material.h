// Material component: a handle (kind, index) into one parameter pool per
// kind. A scene without glass has an empty dielectric pool and its shading
// loop never enters dielectric code.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "math/common.h"
#include "material/fourier_bsdf.h"
#include "material/measured_bsdf.h"
#include "material/microfacet.h"
#include "texture/texture.h"

namespace lantern {

// The kinds with a BSDF, each with its pool and shading loop; then two
// kinds that never reach shading: Mix is resolved to one of its materials
// when a hit is stored (resolve_material), and Interface (a boundary with no
// surface) is cut out of the scene like alpha 0.
enum class MaterialKind : uint8_t {
  Diffuse = 0,
  Conductor,
  Dielectric,
  CoatedDiffuse,
  CoatedConductor,
  DiffuseTransmission,
  ThinDielectric,
  Hair,
  Measured,
  Fourier,
  Mix,
  Interface
};
inline constexpr int kMaterialKindCount = 10;  // the kinds with a BSDF

struct MaterialHandle {
  uint32_t bits = 0;
  static MaterialHandle make(MaterialKind k, uint32_t index) { return {uint32_t(k) << 24 | index}; }
  MaterialKind kind() const { return MaterialKind(bits >> 24); }
  uint32_t index() const { return bits & 0xFFFFFFu; }
};

// pbrt's roughness parameters: uroughness / vroughness (textures), mapped
// to GGX alphas by sqrt when remaproughness is true.
struct RoughnessParams {
  FloatTextureRef u = FloatTextureRef::constant(0.f), v = FloatTextureRef::constant(0.f);
  bool remap = true;

  TrowbridgeReitz distribution(const TexturePools& tex, const TextureContext& c) const {
    float ru = max_num(tex.evaluate_float(u, c), 0.f), rv = max_num(tex.evaluate_float(v, c), 0.f);
    return remap ? TrowbridgeReitz{std::sqrt(ru), std::sqrt(rv)} : TrowbridgeReitz{ru, rv};
  }
};

struct DiffuseMaterial {
  RGBTextureRef reflectance;
  int32_t bump = -1;  // index into MaterialPools::bumps
};

struct ConductorMaterial {
  RGBTextureRef eta = RGBTextureRef::constant(RGB(1.f)), k = RGBTextureRef::constant(RGB(0.f));
  // pbrt-v4's conductor given by its reflectance at normal incidence, when
  // that is a texture (a constant one is turned into eta and k at load).
  RGBTextureRef reflectance;
  bool by_reflectance = false;
  RGBTextureRef mirror_reflectance = RGBTextureRef::constant(RGB(1.f));  // pbrt's "mirror" (Kr)
  bool mirror = false;
  RoughnessParams roughness;
  int32_t bump = -1;
};

struct DielectricMaterial {
  FloatTextureRef eta = FloatTextureRef::constant(1.5f);
  // An index that varies with wavelength (TexturePools::spectra), or -1:
  // the spectral renderer reads it at a sample's first wavelength and
  // keeps that one alone (integrator/dispersion.h).
  int32_t dispersion = -1;
  RoughnessParams roughness;
  int32_t bump = -1;  // index into MaterialPools::bumps
};

// The layer between the coat and the base of pbrt-v4's coated materials,
// with its defaults.
struct CoatLayer {
  RGBTextureRef albedo = RGBTextureRef::constant(RGB(0.f));  // of the medium between coat and base
  FloatTextureRef thickness = FloatTextureRef::constant(0.01f);
  FloatTextureRef g = FloatTextureRef::constant(0.f);
  int max_depth = 10;
  int n_samples = 1;
};

struct CoatedDiffuseMaterial {
  RGBTextureRef reflectance = RGBTextureRef::constant(RGB(0.5f));
  float eta = 1.5f;
  int32_t dispersion = -1;  // the coat's index varies with wavelength: as DielectricMaterial's
  RoughnessParams roughness;
  CoatLayer layer;
  int32_t bump = -1;
};

// pbrt-v4's coatedconductor: a dielectric coat ("interface.*") over a
// conductor ("conductor.*", or "reflectance") that sits in the coat.
struct CoatedConductorMaterial {
  float interface_eta = 1.5f;
  int32_t dispersion = -1;  // the coat's index varies with wavelength: as DielectricMaterial's
  RoughnessParams interface_roughness;
  RGBTextureRef conductor_eta, conductor_k;
  RGBTextureRef reflectance;
  bool by_reflectance = false;
  RoughnessParams conductor_roughness;
  CoatLayer layer;
  int32_t bump = -1;
};

// pbrt-v4's diffusetransmission: reflectance and transmittance (default
// 0.25 each), both scaled by "scale" and clamped to [0, 1].
struct DiffuseTransmissionMaterial {
  RGBTextureRef reflectance = RGBTextureRef::constant(RGB(0.25f)), transmittance = RGBTextureRef::constant(RGB(0.25f));
  float scale = 1.f;
  int32_t bump = -1;
};

struct ThinDielectricMaterial {
  FloatTextureRef eta = FloatTextureRef::constant(1.5f);
  int32_t dispersion = -1;  // as DielectricMaterial's
  int32_t bump = -1;
};

// pbrt-v4's hair: the fibre's absorption given directly (sigma_a, per unit
// of diameter), by the colour it gives multiply scattering hair
// (reflectance; pbrt-v3's "color"), or by melanin concentrations (the
// default: eumelanin 1.3, brown hair).
struct HairMaterial {
  enum class Absorption : uint8_t { SigmaA, Reflectance, Melanin };
  Absorption by = Absorption::Melanin;
  RGBTextureRef sigma_a, reflectance;
  FloatTextureRef eumelanin = FloatTextureRef::constant(1.3f), pheomelanin = FloatTextureRef::constant(0.f);
  FloatTextureRef eta = FloatTextureRef::constant(1.55f);
  FloatTextureRef beta_m = FloatTextureRef::constant(0.3f), beta_n = FloatTextureRef::constant(0.3f);
  FloatTextureRef alpha = FloatTextureRef::constant(2.f);  // degrees
};

// pbrt-v4's measured: a tabulated BRDF file (material/measured_bsdf.h),
// loaded once per file however many materials name it.
struct MeasuredMaterial {
  const MeasuredBRDF* brdf = nullptr;  // owned by MaterialPools::measured_brdfs
  int32_t bump = -1;
};

// pbrt-v3's fourier: a BSDF tabulated as Fourier series
// (material/fourier_bsdf.h), loaded once per file.
struct FourierMaterial {
  const FourierTable* table = nullptr;  // owned by MaterialPools::fourier_tables
  int32_t bump = -1;
};

// A material's bump or normal map (applied by material/bump.h).
struct BumpParams {
  FloatTextureRef displacement = FloatTextureRef::constant(0.f);
  int32_t normal_map = -1;  // id in TexturePools::cache
};

// pbrt-v4's mix: materials[1] with probability amount, materials[0]
// otherwise, chosen per hit by a hash of the point and direction.
struct MixMaterial {
  MaterialHandle materials[2];
  FloatTextureRef amount = FloatTextureRef::constant(0.5f);
};

struct MaterialPools {
  std::vector<DiffuseMaterial> diffuse;
  std::vector<ConductorMaterial> conductor;
  std::vector<DielectricMaterial> dielectric;
  std::vector<CoatedDiffuseMaterial> coated_diffuse;
  std::vector<CoatedConductorMaterial> coated_conductor;
  std::vector<DiffuseTransmissionMaterial> diffuse_transmission;
  std::vector<ThinDielectricMaterial> thin_dielectric;
  std::vector<HairMaterial> hair;
  std::vector<MeasuredMaterial> measured;
  std::vector<std::shared_ptr<const MeasuredBRDF>> measured_brdfs;
  std::vector<FourierMaterial> fourier;
  std::vector<std::shared_ptr<const FourierTable>> fourier_tables;
  std::vector<MixMaterial> mix;
  std::vector<BumpParams> bumps;  // only for materials with a displacement or normal map

  // Where a concrete material keeps the index of its bump or normal map
  // (into `bumps`, -1: none), or nullptr for the kinds that take none
  // (hair, as in pbrt-v4; mixes, whose materials keep their own).
  const int32_t* bump_index(MaterialHandle m) const { return bump_index_of(*this, m); }
  int32_t* bump_index(MaterialHandle m) { return bump_index_of(*this, m); }
  // The bump or normal map of a concrete material, or nullptr.
  const BumpParams* bump(MaterialHandle m) const {
    const int32_t* b = bump_index(m);
    return !b || *b < 0 ? nullptr : &bumps[size_t(*b)];
  }

  // Whether the material's index varies with wavelength, so a spectral
  // sample that scatters there keeps only its first wavelength.
  bool dispersive(MaterialHandle m) const {
    switch (m.kind()) {
      case MaterialKind::Dielectric: return dielectric[m.index()].dispersion >= 0;
      case MaterialKind::ThinDielectric: return thin_dielectric[m.index()].dispersion >= 0;
      case MaterialKind::CoatedDiffuse: return coated_diffuse[m.index()].dispersion >= 0;
      case MaterialKind::CoatedConductor: return coated_conductor[m.index()].dispersion >= 0;
      default: return false;
    }
  }

  bool has(MaterialKind k) const {
    switch (k) {
      case MaterialKind::Diffuse: return !diffuse.empty();
      case MaterialKind::Conductor: return !conductor.empty();
      case MaterialKind::Dielectric: return !dielectric.empty();
      case MaterialKind::CoatedDiffuse: return !coated_diffuse.empty();
      case MaterialKind::CoatedConductor: return !coated_conductor.empty();
      case MaterialKind::DiffuseTransmission: return !diffuse_transmission.empty();
      case MaterialKind::ThinDielectric: return !thin_dielectric.empty();
      case MaterialKind::Hair: return !hair.empty();
      case MaterialKind::Measured: return !measured.empty();
      case MaterialKind::Fourier: return !fourier.empty();
      case MaterialKind::Mix: return !mix.empty();
      case MaterialKind::Interface: return false;
    }
    return false;
  }

 private:
  template <class Pools>
  static auto bump_index_of(Pools& p, MaterialHandle m) -> decltype(&p.diffuse[0].bump) {
    switch (m.kind()) {
      case MaterialKind::Diffuse: return &p.diffuse[m.index()].bump;
      case MaterialKind::Conductor: return &p.conductor[m.index()].bump;
      case MaterialKind::Dielectric: return &p.dielectric[m.index()].bump;
      case MaterialKind::CoatedDiffuse: return &p.coated_diffuse[m.index()].bump;
      case MaterialKind::CoatedConductor: return &p.coated_conductor[m.index()].bump;
      case MaterialKind::DiffuseTransmission: return &p.diffuse_transmission[m.index()].bump;
      case MaterialKind::ThinDielectric: return &p.thin_dielectric[m.index()].bump;
      case MaterialKind::Measured: return &p.measured[m.index()].bump;
      case MaterialKind::Fourier: return &p.fourier[m.index()].bump;
      case MaterialKind::Hair:
      case MaterialKind::Mix:
      case MaterialKind::Interface: break;
    }
    return nullptr;
  }
};


}  // namespace lantern
