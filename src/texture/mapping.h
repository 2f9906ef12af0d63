// Texture mappings: where on a texture a surface point lands, as pbrt-v4
// computes it. 2D mappings give (s, t); the 3D mapping gives a point in the
// texture's own space (the inverse of the transform current when the
// texture was defined).
#pragma once

#include "math/frame.h"

namespace lantern {

// Where a texture is evaluated: the surface point (world space), its
// geometric normal (as pbrt-v4's texture context has it) and its (u, v).
struct TextureContext {
  Vec3 p{0.f};
  Vec3 n{0.f, 0.f, 1.f};
  Vec2 uv{0.f};
};

struct TextureMapping {
  enum Kind : uint8_t { UV, Spherical, Cylindrical, Planar } kind = UV;
  float su = 1.f, sv = 1.f, du = 0.f, dv = 0.f;  // uv: scale and offset; planar: du, dv
  Vec3 v1{1.f, 0.f, 0.f}, v2{0.f, 1.f, 0.f};    // planar axes
  Mat4 texture_from_world{1.f};

  Vec3 point(const TextureContext& c) const { return Vec3(texture_from_world * Vec4(c.p, 1.f)); }

  Vec2 map(const TextureContext& c) const {
    switch (kind) {
      case UV: return Vec2(su * c.uv.x + du, sv * c.uv.y + dv);
      case Spherical: {
        Vec3 q = point(c);
        float len = glm::length(q);
        Vec3 d = len > 0.f ? q / len : Vec3(0, 0, 1);
        float phi = std::atan2(d.y, d.x);
        if (phi < 0.f) phi += 2.f * kPi;
        return Vec2(std::acos(glm::clamp(d.z, -1.f, 1.f)) * kInvPi, phi * kInv2Pi);
      }
      case Cylindrical: {
        Vec3 q = point(c);
        return Vec2((kPi + std::atan2(q.y, q.x)) * kInv2Pi, q.z);
      }
      case Planar: {
        Vec3 q = point(c);
        return Vec2(du + glm::dot(q, v1), dv + glm::dot(q, v2));
      }
    }
    return Vec2(0.f);
  }
};

}  // namespace lantern
