// Texture mappings: where on a texture a surface point lands, as pbrt-v4
// computes it. 2D mappings give (s, t); the 3D mapping gives a point in the
// texture's own space (the inverse of the transform current when the
// texture was defined).
#pragma once

#include "math/frame.h"

namespace lantern {

// How far a pixel step in x and y moves a surface point: in space and in
// (u, v). Zero where nothing is filtered (texture/footprint.h makes them).
struct Footprint {
  Vec3 dpdx{0.f}, dpdy{0.f};
  Vec2 duvdx{0.f}, duvdy{0.f};  // (du/dx, dv/dx), (du/dy, dv/dy)
};

inline const Footprint kNoFootprint{};

// Where a texture is evaluated: the surface point (world space), its
// geometric normal (as pbrt-v4's texture context has it), its (u, v) and
// the pixel's footprint there (by pointer: most scenes have none, and a
// context is made for every BSDF).
struct TextureContext {
  Vec3 p{0.f};
  Vec3 n{0.f, 0.f, 1.f};
  Vec2 uv{0.f};
  const Footprint* fp = nullptr;  // null: zero
  Vec3 dpdu{0.f};  // a curve's unit tangent (read by the hair BSDF); zero elsewhere
  const Footprint& footprint() const { return fp ? *fp : kNoFootprint; }
};

// (s, t) and their derivatives over a pixel step.
struct TexCoord2D {
  Vec2 st{0.f};
  Vec2 dst_dx{0.f}, dst_dy{0.f};
};

// A texture-space point and its derivatives over a pixel step.
struct TexCoord3D {
  Vec3 p{0.f};
  Vec3 dpdx{0.f}, dpdy{0.f};
};

struct TextureMapping {
  enum Kind : uint8_t { UV, Spherical, Cylindrical, Planar } kind = UV;
  float su = 1.f, sv = 1.f, du = 0.f, dv = 0.f;  // uv: scale and offset; planar: du, dv
  Vec3 v1{1.f, 0.f, 0.f}, v2{0.f, 1.f, 0.f};    // planar axes
  Mat4 texture_from_world{1.f};

  Vec3 point(const TextureContext& c) const { return Vec3(texture_from_world * Vec4(c.p, 1.f)); }
  TexCoord3D map3d(const TextureContext& c) const {
    const glm::mat3 M(texture_from_world);
    return TexCoord3D{point(c), M * c.footprint().dpdx, M * c.footprint().dpdy};
  }

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

  // map() with the derivatives of (s, t): by the chain rule through (u, v)
  // for the uv mapping, through the texture-space point for the others.
  TexCoord2D map_filtered(const TextureContext& c) const {
    TexCoord2D r{map(c)};
    if (kind == UV) {
      const Vec2 scale(su, sv);
      r.dst_dx = scale * c.footprint().duvdx;
      r.dst_dy = scale * c.footprint().duvdy;
      return r;
    }
    const TexCoord3D q = map3d(c);
    Vec3 ds(0.f), dt(0.f);  // gradients of s and t in texture space
    const float rho2 = q.p.x * q.p.x + q.p.y * q.p.y;
    if (kind == Planar) {
      ds = v1;
      dt = v2;
    } else if (rho2 > 0.f) {
      const Vec3 dphi = Vec3(-q.p.y, q.p.x, 0.f) / rho2;  // of atan2(y, x)
      if (kind == Cylindrical) {
        ds = dphi * kInv2Pi;
        dt = Vec3(0.f, 0.f, 1.f);
      } else {  // spherical: s = theta / pi, t = phi / (2 pi)
        const float r2 = rho2 + q.p.z * q.p.z, rho = std::sqrt(rho2);
        ds = Vec3(q.p.x * q.p.z / rho, q.p.y * q.p.z / rho, -rho) / (r2 * kPi);
        dt = dphi * kInv2Pi;
      }
    }
    r.dst_dx = Vec2(glm::dot(ds, q.dpdx), glm::dot(dt, q.dpdx));
    r.dst_dy = Vec2(glm::dot(ds, q.dpdy), glm::dot(dt, q.dpdy));
    return r;
  }
};

}  // namespace lantern
