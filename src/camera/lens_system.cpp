#include "camera/lens_system.h"

#include <tbb/parallel_for.h>

#include <cctype>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace lantern {

namespace {

// Lens space is camera space with z negated (the film at z = 0 in both).
LensRay flip_z(const LensRay& r) { return {Vec3(r.o.x, r.o.y, -r.o.z), Vec3(r.d.x, r.d.y, -r.d.z)}; }

// The sphere of radius |radius| centred on the axis at z_center: the
// crossing on the element's side (the nearer root when the ray runs
// towards the centre's side of the vertex, else the farther), with the
// normal turned against the ray.
bool intersect_element(float radius, float z_center, const LensRay& r, float* t, Vec3* n) {
  const Vec3 o = r.o - Vec3(0.f, 0.f, z_center);
  const float a = glm::dot(r.d, r.d), b = 2.f * glm::dot(r.d, o), c = glm::dot(o, o) - radius * radius;
  const float disc = b * b - 4.f * a * c;
  if (disc < 0.f) return false;
  const float q = -0.5f * (b + std::copysign(std::sqrt(disc), b));
  float t0 = q / a, t1 = q != 0.f ? c / q : t0;
  if (t0 > t1) std::swap(t0, t1);
  const bool closer = (r.d.z > 0.f) != (radius < 0.f);
  *t = closer ? t0 : t1;
  if (!(*t > 0.f)) return false;
  *n = glm::normalize(o + *t * r.d);
  if (glm::dot(*n, -r.d) < 0.f) *n = -*n;
  return true;
}

// Snell's law for the unit direction d arriving at a surface of normal n
// (against d), eta_ratio = eta_incident / eta_transmitted; false on total
// internal reflection.
bool refract(const Vec3& d, const Vec3& n, float eta_ratio, Vec3* out) {
  const Vec3 wi = -glm::normalize(d);
  const float cos_i = glm::dot(n, wi);
  const float sin2_t = eta_ratio * eta_ratio * std::max(0.f, 1.f - cos_i * cos_i);
  if (sin2_t >= 1.f) return false;
  const float cos_t = std::sqrt(1.f - sin2_t);
  *out = eta_ratio * -wi + (eta_ratio * cos_i - cos_t) * n;
  return true;
}

}  // namespace

std::vector<float> read_lens_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open lens file \"" + path + "\"");
  std::vector<float> numbers;
  std::string line;
  for (int line_number = 1; std::getline(in, line); ++line_number) {
    if (const size_t hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    std::istringstream words(line);
    for (std::string w; words >> w;) {
      size_t used = 0;
      float v = 0.f;
      try {
        v = std::stof(w, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used != w.size() || !std::isfinite(v))
        throw std::runtime_error(path + ":" + std::to_string(line_number) + ": \"" + w.substr(0, 40) +
                                 "\" is not a number (a lens file holds four numbers per element: curvature "
                                 "radius, thickness, index of refraction, aperture diameter)");
      numbers.push_back(v);
    }
  }
  return numbers;
}

LensSystem::LensSystem(const std::vector<float>& n, float aperture_diameter_mm) {
  if (n.empty() || n.size() % 4 != 0)
    throw std::invalid_argument(
        "a lens file holds four numbers per element (curvature radius, thickness, index of "
        "refraction, aperture diameter, in mm); this one has " +
        std::to_string(n.size()));
  bool stop = false;
  for (size_t i = 0; i < n.size(); i += 4) {
    LensInterface e;
    e.curvature_radius = n[i] * 0.001f;
    e.thickness = n[i + 1] * 0.001f;
    e.eta = n[i + 2] == 0.f ? 1.f : n[i + 2];
    float diameter = n[i + 3];
    if (n[i] == 0.f) {
      stop = true;
      diameter = std::min(diameter, aperture_diameter_mm);
    }
    e.aperture_radius = 0.5f * diameter * 0.001f;
    if (!(e.thickness >= 0.f) || !(e.eta > 0.f) || !(e.aperture_radius > 0.f))
      throw std::invalid_argument("lens element " + std::to_string(i / 4 + 1) +
                                  ": thickness must be >= 0, index of refraction > 0 (or 0 for air) and aperture "
                                  "diameter > 0");
    interfaces_.push_back(e);
  }
  if (!stop) throw std::invalid_argument("the lens has no aperture stop (an element of curvature radius 0)");
}

float LensSystem::front_z() const {
  float z = 0.f;
  for (const LensInterface& e : interfaces_) z += e.thickness;
  return z;
}

ApertureMask::ApertureMask(int w, int h, std::vector<float> v) : width(w), height(h), values(std::move(v)) {
  double sum = 0.0;
  for (float& x : values) {
    x = std::isfinite(x) ? max_num(x, 0.f) : 0.f;
    sum += x;
  }
  if (width < 1 || height < 1 || size_t(width) * size_t(height) != values.size() || !(sum > 0.0))
    throw std::invalid_argument("the aperture image is empty or black: it would let no light through");
  const float scale = float(0.25 * double(kPi) * double(values.size()) / sum);
  for (float& x : values) x *= scale;
}

float ApertureMask::at(Vec2 p) const {
  const float x = 0.5f * (p.x + 1.f) * float(width) - 0.5f, y = 0.5f * (p.y + 1.f) * float(height) - 0.5f;
  const int x0 = int(std::floor(x)), y0 = int(std::floor(y));
  const float fx = x - float(x0), fy = y - float(y0);
  auto texel = [&](int i, int j) {
    return i < 0 || j < 0 || i >= width || j >= height ? 0.f : values[size_t(j) * size_t(width) + size_t(i)];
  };
  return (1.f - fy) * ((1.f - fx) * texel(x0, y0) + fx * texel(x0 + 1, y0)) +
         fy * ((1.f - fx) * texel(x0, y0 + 1) + fx * texel(x0 + 1, y0 + 1));
}

namespace {

// 1 inside the polygon (non-zero winding), 0 outside, at texel centres of
// [-1, 1]^2, row 0 at y = -1; then mirrored in y, as pbrt-v4 flips its
// built-in images before use.
std::vector<float> rasterize(const std::vector<Vec2>& poly, int res) {
  std::vector<float> v(size_t(res) * size_t(res), 0.f);
  for (int y = 0; y < res; ++y)
    for (int x = 0; x < res; ++x) {
      const Vec2 p(-1.f + 2.f * (float(x) + 0.5f) / float(res), -1.f + 2.f * (float(y) + 0.5f) / float(res));
      int winding = 0;
      for (size_t i = 0; i < poly.size(); ++i) {
        const Vec2 a = poly[i], b = poly[(i + 1) % poly.size()];
        const float side = (p.x - a.x) * (b.y - a.y) - (p.y - a.y) * (b.x - a.x);
        if (a.y <= p.y && b.y > p.y && side > 0.f)
          ++winding;
        else if (a.y > p.y && b.y <= p.y && side < 0.f)
          --winding;
      }
      v[size_t(res - 1 - y) * size_t(res) + size_t(x)] = winding != 0 ? 1.f : 0.f;
    }
  return v;
}

}  // namespace

std::optional<ApertureMask> builtin_aperture(const std::string& name) {
  constexpr int kRes = 256;
  std::vector<float> v(size_t(kRes) * size_t(kRes), 0.f);
  if (name == "gaussian") {
    // exp(-r^2) - exp(-1), cut at 0 (sigma^2 = 1), symmetric: no flip.
    for (int y = 0; y < kRes; ++y)
      for (int x = 0; x < kRes; ++x) {
        const float u = -1.f + 2.f * (float(x) + 0.5f) / kRes, w = -1.f + 2.f * (float(y) + 0.5f) / kRes;
        v[size_t(y * kRes + x)] = max_num(0.f, std::exp(-(u * u + w * w)) - std::exp(-1.f));
      }
  } else if (name == "square") {
    for (int y = kRes / 4; y < 3 * kRes / 4; ++y)
      for (int x = kRes / 4; x < 3 * kRes / 4; ++x) v[size_t(y * kRes + x)] = 1.f;
  } else if (name == "pentagon") {
    // A regular pentagon of circumradius 0.8, a vertex at +y.
    std::vector<Vec2> poly;
    for (int i = 0; i < 5; ++i) {
      const float a = 0.5f * kPi - 2.f * kPi * float(i) / 5.f;
      poly.push_back(0.8f * Vec2(std::cos(a), std::sin(a)));
    }
    v = rasterize(poly, kRes);
  } else if (name == "star") {
    // Five points on the unit circle, the inner vertices where the
    // pentagram's edges cross (radius cos 72 / cos 36), listed clockwise.
    std::vector<Vec2> poly;
    for (int i = 9; i >= 0; --i) {
      const float r = (i & 1) ? 1.f : std::cos(glm::radians(72.f)) / std::cos(glm::radians(36.f));
      poly.push_back(r * Vec2(std::cos(kPi * float(i) / 5.f), std::sin(kPi * float(i) / 5.f)));
    }
    v = rasterize(poly, kRes);
  } else {
    return std::nullopt;
  }
  return ApertureMask(kRes, kRes, std::move(v));
}

std::optional<LensRay> LensSystem::trace_from_film(LensRay camera_ray, float* transmission) const {
  LensRay r = flip_z(camera_ray);
  float element_z = 0.f;
  for (size_t k = interfaces_.size(); k-- > 0;) {
    const LensInterface& e = interfaces_[k];
    element_z -= e.thickness;
    float t;
    Vec3 n;
    const bool stop = e.curvature_radius == 0.f;
    if (stop) {
      if (r.d.z >= 0.f) return std::nullopt;
      t = (element_z - r.o.z) / r.d.z;
      if (t < 0.f) return std::nullopt;
    } else if (!intersect_element(e.curvature_radius, element_z + e.curvature_radius, r, &t, &n)) {
      return std::nullopt;
    }
    const Vec3 p = r.o + t * r.d;
    if (stop && transmission && aperture_) {
      *transmission = aperture_->at(Vec2(p.x, p.y) / e.aperture_radius);
      if (!(*transmission > 0.f)) return std::nullopt;
    } else if (p.x * p.x + p.y * p.y > e.aperture_radius * e.aperture_radius) {
      return std::nullopt;
    }
    r.o = p;
    if (!stop) {
      const float eta_in = e.eta, eta_out = k > 0 ? interfaces_[k - 1].eta : 1.f;
      Vec3 d;
      if (!refract(r.d, n, eta_in / eta_out, &d)) return std::nullopt;
      r.d = d;
    }
  }
  return flip_z(r);
}

std::optional<LensRay> LensSystem::trace_from_scene(LensRay camera_ray) const {
  LensRay r = flip_z(camera_ray);
  float element_z = -front_z();
  for (size_t k = 0; k < interfaces_.size(); ++k) {
    const LensInterface& e = interfaces_[k];
    float t;
    Vec3 n;
    const bool stop = e.curvature_radius == 0.f;
    if (stop) {
      if (r.d.z <= 0.f) return std::nullopt;
      t = (element_z - r.o.z) / r.d.z;
      if (t < 0.f) return std::nullopt;
    } else if (!intersect_element(e.curvature_radius, element_z + e.curvature_radius, r, &t, &n)) {
      return std::nullopt;
    }
    const Vec3 p = r.o + t * r.d;
    if (p.x * p.x + p.y * p.y > e.aperture_radius * e.aperture_radius) return std::nullopt;
    r.o = p;
    if (!stop) {
      const float eta_in = k > 0 ? interfaces_[k - 1].eta : 1.f, eta_out = e.eta;
      Vec3 d;
      if (!refract(r.d, n, eta_in / eta_out, &d)) return std::nullopt;
      r.d = d;
    }
    element_z += e.thickness;
  }
  return flip_z(r);
}

namespace {

// Where a paraxial ray leaving the system crosses the axis (the focal
// point) and where its extension meets the entering ray's line (the
// principal plane), as lens-space z (Pharr et al., sec. 5.3.3).
void cardinal_points(const LensRay& in, const LensRay& out, float* principal_z, float* focal_z) {
  const float tf = -out.o.x / out.d.x;
  *focal_z = -(out.o.z + tf * out.d.z);
  const float tp = (in.o.x - out.o.x) / out.d.x;
  *principal_z = -(out.o.z + tp * out.d.z);
}

}  // namespace

void LensSystem::focus(float focus_distance, float probe_height) {
  float pz[2], fz[2];
  const LensRay from_scene{Vec3(probe_height, 0.f, front_z() + 1.f), Vec3(0.f, 0.f, -1.f)};
  const std::optional<LensRay> on_film = trace_from_scene(from_scene);
  const LensRay from_film{Vec3(probe_height, 0.f, rear_z() - 1.f), Vec3(0.f, 0.f, 1.f)};
  const std::optional<LensRay> in_scene = trace_from_film(from_film);
  if (!on_film || !in_scene || on_film->d.x == 0.f || in_scene->d.x == 0.f)
    throw std::invalid_argument("rays near the axis do not pass through the lens: it cannot be focused");
  cardinal_points(from_scene, *on_film, &pz[0], &fz[0]);
  cardinal_points(from_film, *in_scene, &pz[1], &fz[1]);
  // The thick lens's imaging equation solved for the film's shift.
  const float f = fz[0] - pz[0];
  const float z = -focus_distance;
  const float c = (pz[1] - z - pz[0]) * (pz[1] - z - 4.f * f - pz[0]);
  if (!(c > 0.f))
    throw std::invalid_argument("the lens cannot focus at " + std::to_string(focus_distance) +
                                " (closer than it reaches); give a larger \"focusdistance\"");
  const float delta = 0.5f * (pz[1] - z + pz[0] - std::sqrt(c));
  interfaces_.back().thickness += delta;
  if (!(interfaces_.back().thickness > 0.f))
    throw std::invalid_argument("focused at " + std::to_string(focus_distance) +
                                ", the film would lie inside the lens");
}

// Per segment [r0, r1] of film radius, the box of rear-plane points that
// some film point of the segment on the +x axis sees through the whole
// system: a Halton grid over a square of 1.5 times the rear element's
// radius, grown by two grid diagonals so that a thin part of the pupil
// between samples stays inside (a box too small would darken the image; one
// too large only wastes rays).
void LensSystem::compute_exit_pupil(float film_radius) {
  constexpr int kSegments = 64, kSamples = 1 << 12;
  film_radius_ = film_radius;
  pupil_.assign(kSegments, Box{});
  const float half = 1.5f * rear_radius();
  tbb::parallel_for(0, kSegments, [&](int s) {
    const float r0 = film_radius * float(s) / kSegments, r1 = film_radius * float(s + 1) / kSegments;
    Vec2 lo(kInfinity), hi(-kInfinity);
    bool any = false;
    for (int i = 0; i < kSamples; ++i) {
      // Halton (bases 2 and 3) over the square, film points along the segment.
      float h2 = 0.f, h3 = 0.f;
      for (float f = 0.5f, k = float(i); k > 0.f; f *= 0.5f, k = std::floor(k / 2.f)) h2 += f * std::fmod(k, 2.f);
      for (float f = 1.f / 3.f, k = float(i); k > 0.f; f /= 3.f, k = std::floor(k / 3.f)) h3 += f * std::fmod(k, 3.f);
      const Vec3 film(r0 + (float(i) + 0.5f) / kSamples * (r1 - r0), 0.f, 0.f);
      const Vec3 rear(-half + 2.f * half * h2, -half + 2.f * half * h3, rear_z());
      const Vec2 q(rear.x, rear.y);
      const bool inside = any && q.x >= lo.x && q.x <= hi.x && q.y >= lo.y && q.y <= hi.y;
      if (inside || trace_from_film({film, rear - film})) {
        lo = glm::min(lo, q);
        hi = glm::max(hi, q);
        any = true;
      }
    }
    if (!any) return;  // nothing gets through: an empty box, every ray vignetted
    const float grow = 2.f * (2.f * half * std::sqrt(2.f)) / std::sqrt(float(kSamples));
    pupil_[size_t(s)] = {lo - Vec2(grow), hi + Vec2(grow)};
  });
}

std::optional<LensSystem::Sample> LensSystem::sample_ray(const Vec3& p_film, Vec2 u) const {
  const float r = std::sqrt(p_film.x * p_film.x + p_film.y * p_film.y);
  const size_t segment = std::min(pupil_.size() - 1, size_t(r / film_radius_ * float(pupil_.size())));
  const Box& b = pupil_[segment];
  const float area = (b.hi.x - b.lo.x) * (b.hi.y - b.lo.y);
  if (!(area > 0.f)) return std::nullopt;
  const Vec2 q = b.lo + u * (b.hi - b.lo);
  // The box is for a film point on +x: turned to this one's angle.
  const float s = r > 0.f ? p_film.y / r : 0.f, c = r > 0.f ? p_film.x / r : 1.f;
  const Vec3 rear(c * q.x - s * q.y, s * q.x + c * q.y, rear_z());
  const LensRay film_ray{p_film, rear - p_film};
  float transmission = 1.f;
  const std::optional<LensRay> out = trace_from_film(film_ray, &transmission);
  if (!out) return std::nullopt;
  const float cos_theta = glm::normalize(film_ray.d).z;
  const float cos4 = sqr(cos_theta) * sqr(cos_theta);
  return Sample{{out->o, glm::normalize(out->d)}, transmission * cos4 * area / sqr(rear_z())};
}

}  // namespace lantern
