// Material component: a handle (kind, index) into one parameter pool per
// kind. A scene without glass has an empty dielectric pool and its shading
// loop never enters dielectric code.
#pragma once

#include <cstdint>
#include <vector>

#include "math/common.h"
#include "scene/texture.h"

namespace lantern {

enum class MaterialKind : uint8_t { Diffuse = 0, Conductor, Dielectric, CoatedDiffuse };
inline constexpr int kMaterialKindCount = 4;

struct MaterialHandle {
  uint32_t bits = 0;
  static MaterialHandle make(MaterialKind k, uint32_t index) { return {uint32_t(k) << 24 | index}; }
  MaterialKind kind() const { return MaterialKind(bits >> 24); }
  uint32_t index() const { return bits & 0xFFFFFFu; }
};

struct DiffuseMaterial {
  RGBTexture reflectance;
};

struct ConductorMaterial {
  RGB eta{1.f}, k{0.f};
  RGB mirror_reflectance{1.f};  // used when `mirror` (pbrt's "mirror": constant reflectance)
  bool mirror = false;
  float alpha_x = 0.f, alpha_y = 0.f;
};

struct DielectricMaterial {
  float eta = 1.5f;
  float alpha_x = 0.f, alpha_y = 0.f;
};

// pbrt-v4's parameters and defaults.
struct CoatedDiffuseMaterial {
  RGBTexture reflectance;
  RGBTexture albedo;  // of the medium between coat and base
  float eta = 1.5f;
  float alpha_x = 0.f, alpha_y = 0.f;
  float thickness = 0.01f;
  float g = 0.f;
  int max_depth = 10;
  int n_samples = 1;
};

struct MaterialPools {
  std::vector<DiffuseMaterial> diffuse;
  std::vector<ConductorMaterial> conductor;
  std::vector<DielectricMaterial> dielectric;
  std::vector<CoatedDiffuseMaterial> coated_diffuse;

  bool has(MaterialKind k) const {
    switch (k) {
      case MaterialKind::Diffuse: return !diffuse.empty();
      case MaterialKind::Conductor: return !conductor.empty();
      case MaterialKind::Dielectric: return !dielectric.empty();
      case MaterialKind::CoatedDiffuse: return !coated_diffuse.empty();
    }
    return false;
  }
};

// pbrt's roughness remapping: alpha = sqrt(roughness) when remaproughness.
inline float roughness_to_alpha(float r) { return std::sqrt(std::fmax(r, 0.f)); }

}  // namespace lantern
