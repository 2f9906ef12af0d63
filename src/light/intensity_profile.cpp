#include "light/intensity_profile.h"

#include "math/equal_area.h"

namespace lantern {

namespace {

float grey(const RGB& c) { return (c[0] + c[1] + c[2]) / 3.f; }

// pbrt-v4 reads light images at the nearest texel.
RGB texel(const TextureImage& img, Vec2 uv) { return img.lookup_rgb(uv, ImageFilter::Point, WrapMode::Clamp); }

// Where light-space direction w meets the projection's screen window, as
// (u, v) in [0, 1]^2 (v = 0 at the image's top row); false outside it.
bool screen_uv(const IntensityProfile& p, const Vec3& w, Vec2* uv) {
  if (w.z < p.hither) return false;
  const Vec2 s(w.x / (w.z * p.tan_half), w.y / (w.z * p.tan_half));
  if (s.x < p.screen_lo.x || s.y < p.screen_lo.y || s.x > p.screen_hi.x || s.y > p.screen_hi.y) return false;
  *uv = (s - p.screen_lo) / (p.screen_hi - p.screen_lo);
  return true;
}

// The light-space direction through screen point (u, v), not normalised.
Vec3 screen_dir(const IntensityProfile& p, Vec2 uv) {
  const Vec2 s = p.screen_lo + uv * (p.screen_hi - p.screen_lo);
  return Vec3(s * p.tan_half, 1.f);
}

// Solid angle per unit (u, v) of the screen at light-space direction w:
// the window covers area(window) tan^2 on the plane z = 1, and a patch
// there subtends cos^3 theta of its area.
float screen_jacobian(const IntensityProfile& p, const Vec3& w_unit) {
  const Vec2 extent = p.screen_hi - p.screen_lo;
  return extent.x * extent.y * p.tan_half * p.tan_half * w_unit.z * w_unit.z * w_unit.z;
}

}  // namespace

RGB profile_value(const IntensityProfile& p, const TexturePools& tex, const Vec3& w) {
  const TextureImage& img = tex.images[size_t(p.image)];
  const Vec3 wl = glm::normalize(p.light_from_world * w);
  if (p.kind == ProfileKind::Goniometric) return RGB(grey(texel(img, equal_area_sphere_to_square(wl))));
  Vec2 uv;
  return screen_uv(p, wl, &uv) ? texel(img, uv) : RGB(0.f);
}

bool sample_profile(const IntensityProfile& p, Vec2 u, Vec3* w, float* pdf) {
  float pdf_uv;
  const Vec2 uv = p.distribution.sample_continuous(u, &pdf_uv);
  if (!(pdf_uv > 0.f)) return false;
  Vec3 wl;
  if (p.kind == ProfileKind::Goniometric) {
    wl = equal_area_square_to_sphere(uv);
    *pdf = pdf_uv / (4.f * kPi);
  } else {
    wl = glm::normalize(screen_dir(p, uv));
    *pdf = pdf_uv / screen_jacobian(p, wl);
  }
  *w = glm::normalize(p.world_from_light * wl);
  return *pdf > 0.f && std::isfinite(*pdf);
}

float profile_pdf(const IntensityProfile& p, const Vec3& w) {
  const Vec3 wl = glm::normalize(p.light_from_world * w);
  if (p.kind == ProfileKind::Goniometric) return p.distribution.pdf(equal_area_sphere_to_square(wl)) / (4.f * kPi);
  Vec2 uv;
  if (!screen_uv(p, wl, &uv)) return 0.f;
  return p.distribution.pdf(uv) / screen_jacobian(p, wl);
}

// The profile's integral over the sphere of a per-texel value, and (if
// asked) each texel's share of it.
template <class Value>
double integrate(const IntensityProfile& p, const TextureImage& img, Value&& value, std::vector<float>* weights) {
  double sum = 0.0;
  if (weights) weights->resize(img.texels.size());
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const size_t i = size_t(y) * size_t(img.width) + size_t(x);
      float dw = 4.f * kPi / float(img.texels.size());  // equal area: every texel the same solid angle
      if (p.kind == ProfileKind::Projection) {
        const Vec2 uv((float(x) + 0.5f) / float(img.width), (float(y) + 0.5f) / float(img.height));
        dw = screen_jacobian(p, glm::normalize(screen_dir(p, uv))) / float(img.texels.size());
      }
      const float wi = value(img.texels[i]) * dw;
      if (weights) (*weights)[i] = wi;
      sum += double(wi);
    }
  return sum;
}

void finalize_profile(IntensityProfile& p, const TexturePools& tex) {
  const TextureImage& img = tex.images[size_t(p.image)];
  std::vector<float> w;
  p.mean_intensity = float(integrate(p, img, grey, &w) / (4.0 * kPi));
  p.distribution = Distribution2D(w, img.width, img.height);
}

float profile_power(const IntensityProfile& p, const TexturePools& tex) {
  const TextureImage& img = tex.images[size_t(p.image)];
  if (p.kind == ProfileKind::Goniometric) return float(integrate(p, img, grey, nullptr));
  return float(integrate(
      p, img, [](const RGB& c) { return luminance(c); }, nullptr));
}

}  // namespace lantern
