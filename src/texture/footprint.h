// Texture filter footprints: how far a pixel step moves the surface point
// seen, by pbrt-v4's approximation from the camera (Pharr, Jakob &
// Humphreys, PBR 4th ed., sec. 10.1.1): the camera's smallest ray
// differentials, turned to point at p, meet the tangent plane at p; the
// offsets are scaled by max(1/8, 1/sqrt(spp)) because a pixel's samples
// each cover part of it. Lantern uses it at every vertex, camera and light
// subpaths alike, so a texture's value is a function of the surface point
// alone and every bidirectional strategy shades a vertex the same way.
#pragma once

#include "camera/camera.h"
#include "texture/mapping.h"

namespace lantern {

class FootprintModel {
 public:
  FootprintModel() = default;  // zero footprints: textures read unfiltered
  FootprintModel(const Camera& camera, int samples_per_pixel);

  bool enabled() const { return enabled_; }
  // dp/dx and dp/dy at p on a surface with normal n (zero where the
  // differential rays miss the tangent plane).
  void dp_dxy(const Vec3& p, const Vec3& n, Vec3* dpdx, Vec3* dpdy) const;
  // The footprint at p, with (u, v) from dp/du and dp/dv by least squares.
  Footprint at(const Vec3& p, const Vec3& n, const Vec3& dpdu, const Vec3& dpdv) const;

 private:
  bool enabled_ = false;
  Vec3 origin_{0.f}, forward_{0.f, 0.f, 1.f};
  Vec3 min_pos_dx_{0.f}, min_pos_dy_{0.f}, min_dir_dx_{0.f}, min_dir_dy_{0.f};  // world space, relative to forward_
  float spp_scale_ = 1.f;
};

}  // namespace lantern
