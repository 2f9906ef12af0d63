#include "medium/cloud.h"

#include "texture/noise.h"

namespace lantern {

namespace {

// The noise's gradient by forward differences of step 0.01.
Vec3 noise_gradient(const Vec3& p) {
  const float h = 0.01f, n = perlin_noise(p);
  return Vec3(perlin_noise(p + Vec3(h, 0.f, 0.f)) - n, perlin_noise(p + Vec3(0.f, h, 0.f)) - n,
              perlin_noise(p + Vec3(0.f, 0.f, h)) - n) /
         h;
}

}  // namespace

float CloudMedium::density_in_medium(Vec3 p) const {
  Vec3 q = frequency * p;
  if (wispiness > 0.f) {  // two octaves of displacement
    float amount = 0.05f * wispiness, scale = 10.f;
    for (int i = 0; i < 2; ++i, amount *= 0.5f, scale *= 1.99f) q += amount * noise_gradient(scale * q);
  }
  float sum = 0.f, weight = 0.5f, scale = 1.f;
  for (int i = 0; i < 5; ++i, weight *= 0.5f, scale *= 1.99f) sum += weight * perlin_noise(scale * q);
  float d = std::clamp((1.f - p.y) * 4.5f * density * sum, 0.f, 1.f);
  d += 2.f * std::max(0.f, 0.5f - p.y);
  return std::clamp(d, 0.f, 1.f);
}

float CloudMedium::density_at(const Vec3& p_render) const {
  const Vec3 p = Vec3(medium_from_render * Vec4(p_render, 1.f));
  if (p.x < p0.x || p.y < p0.y || p.z < p0.z || p.x > p1.x || p.y > p1.y || p.z > p1.z) return 0.f;
  return density_in_medium(p);
}

bool CloudMedium::clip(const Vec3& o, const Vec3& d, float t0, float t1, float* ta, float* tb) const {
  const Vec3 om = Vec3(medium_from_render * Vec4(o, 1.f)), dm = glm::mat3(medium_from_render) * d;
  float a = t0, b = t1;
  for (int k = 0; k < 3; ++k) {
    if (dm[k] == 0.f) {
      if (om[k] < p0[k] || om[k] > p1[k]) return false;
      continue;
    }
    float e0 = (p0[k] - om[k]) / dm[k], e1 = (p1[k] - om[k]) / dm[k];
    if (e0 > e1) std::swap(e0, e1);
    a = std::max(a, e0);
    b = std::min(b, e1);
  }
  *ta = a, *tb = b;
  return a < b;
}

void CloudMedium::build_proxy(int n) {
  proxy.nx = proxy.ny = proxy.nz = n;
  proxy.p0 = p0, proxy.p1 = p1;
  proxy.medium_from_render = medium_from_render;
  proxy.values.resize(size_t(n) * n * n);
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        const Vec3 u = (Vec3(float(x), float(y), float(z)) + 0.5f) / float(n);
        proxy.values[proxy.offset(x, y, z)] = density_in_medium(p0 + u * (p1 - p0));
      }
  proxy.find_occupied_cells();
}

}  // namespace lantern
