#include "material/fourier_bsdf.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>

#include "color/spectrum_conversion.h"
#include "math/catmull_rom.h"
#include "math/fourier_series.h"

namespace lantern {

namespace {

const char kScatfunMagic[8] = {'S', 'C', 'A', 'T', 'F', 'U', 'N', '\x01'};

// The coefficients at (mu_i, mu_o), summed over the 4 x 4 spline nodes
// around them: per channel, `m` of them (the largest order among the
// nodes). They live in the caller's frame: inline up to an order the
// published tables stay below, on the heap beyond it. (A per-thread
// scratch would outlive the pool's threads, which leak checkers report.)
struct Coefficients {
  static constexpr size_t kInline = 3 * 128;
  std::array<float, kInline> inline_storage;
  std::vector<float> heap;
  const float* channel[3] = {nullptr, nullptr, nullptr};
  int m = 0;
  Coefficients() = default;
  Coefficients(const Coefficients&) = delete;  // channel points into itself
  Coefficients& operator=(const Coefficients&) = delete;
};
bool coefficients(const FourierTable& t, float mu_i, float mu_o, int channels, Coefficients* out) {
  SplineWeights wi, wo;
  if (!catmull_rom_weights(t.mu, mu_i, &wi) || !catmull_rom_weights(t.mu, mu_o, &wo)) return false;
  const size_t size = size_t(t.m_max) * size_t(channels);
  float* scratch = out->inline_storage.data();
  if (size > Coefficients::kInline) {
    out->heap.resize(size);
    scratch = out->heap.data();
  }
  std::fill(scratch, scratch + size, 0.f);
  const size_t n = t.mu.size();
  int m = 0;
  for (int b = 0; b < 4; ++b)
    for (int a = 0; a < 4; ++a) {
      const float w = wi.weight[a] * wo.weight[b];
      if (w == 0.f) continue;
      const size_t cell = size_t(wo.offset + b) * n + size_t(wi.offset + a);
      const int order = t.order[cell];
      const float* ak = &t.a[size_t(t.offset[cell])];
      m = std::max(m, order);
      for (int c = 0; c < channels; ++c)
        for (int k = 0; k < order; ++k) scratch[size_t(c * t.m_max + k)] += w * ak[c * order + k];
    }
  for (int c = 0; c < channels; ++c) out->channel[c] = scratch + size_t(c * t.m_max);
  out->m = m;
  return true;
}

// cos(phi) between the azimuths of a and b (1 where either has none).
float cos_delta_phi(const Vec3& a, const Vec3& b) {
  const float axy = a.x * a.x + a.y * a.y, bxy = b.x * b.x + b.y * b.y;
  if (axy == 0.f || bxy == 0.f) return 1.f;
  return std::clamp((a.x * b.x + a.y * b.y) / std::sqrt(axy * bxy), -1.f, 1.f);
}

// The tabulated series' value as colour, divided by |mu_i| and, for
// radiance crossing the boundary, by the relative index squared.
RGB colour(const FourierTable& t, const Coefficients& c, float cos_phi, float mu_i, float mu_o, TransportMode mode) {
  const float y = max_num(fourier(c.channel[0], c.m, cos_phi), 0.f);
  float scale = mu_i != 0.f ? 1.f / std::fabs(mu_i) : 0.f;
  if (mode == TransportMode::Radiance && mu_i * mu_o > 0.f) scale /= sqr(mu_i > 0.f ? t.eta : 1.f / t.eta);
  if (t.channels == 1) return RGB(y * scale);
  const float r = fourier(c.channel[1], c.m, cos_phi), b = fourier(c.channel[2], c.m, cos_phi);
  // Green from the luminance: Y = 0.212671 R + 0.715160 G + 0.072169 B.
  const float g = 1.39829f * y - 0.100913f * b - 0.297375f * r;
  return max(RGB(r, g, b) * scale, RGB(0.f));
}

std::runtime_error error(const std::string& path, const std::string& what) {
  return std::runtime_error(path + ": " + what);
}

}  // namespace

std::shared_ptr<const FourierTable> FourierTable::load(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw error(path, "cannot open the Fourier BSDF file");
  const std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (bytes.size() < 8 || std::memcmp(bytes.data(), kScatfunMagic, 8) != 0)
    throw error(path, "not a Fourier BSDF file (expected it to begin with \"SCATFUN\" and version 1)");
  size_t at = 8;
  auto read = [&](void* out, size_t count, const char* what) {
    if ((bytes.size() - at) / 4 < count) throw error(path, std::string("the file ends inside its ") + what);
    std::memcpy(out, &bytes[at], count * 4);
    at += count * 4;
  };
  int32_t header[6], unused[7];
  float eta;
  read(header, 6, "header");
  read(unused, 3, "header");
  read(&eta, 1, "header");
  read(unused, 4, "header");
  const int32_t flags = header[0], n_mu = header[1], n_coeffs = header[2], m_max = header[3], channels = header[4],
                bases = header[5];
  if (flags != 1 || bases != 1)
    throw error(path, "a Fourier BSDF with flags " + std::to_string(flags) + " and " + std::to_string(bases) +
                          " bases (expected 1 and 1: a BSDF without textured parameters, as pbrt-v3 reads)");
  if (channels != 1 && channels != 3) throw error(path, std::to_string(channels) + " channels (expected 1 or 3)");
  if (n_mu < 2 || n_mu > 100000 || m_max < 1 || m_max > 100000 || n_coeffs < 0)
    throw error(path, "implausible sizes (" + std::to_string(n_mu) + " cosines, order " + std::to_string(m_max) + ")");
  if (!(eta > 0.f)) throw error(path, "an index of refraction of " + std::to_string(eta) + " (expected above 0)");
  auto t = std::make_shared<FourierTable>();
  t->path = path, t->eta = eta, t->m_max = m_max, t->channels = channels;
  const size_t cells = size_t(n_mu) * size_t(n_mu);
  t->mu.resize(size_t(n_mu)), t->cdf.resize(cells), t->a.resize(size_t(n_coeffs));
  std::vector<int32_t> offset_and_length(2 * cells);
  read(t->mu.data(), t->mu.size(), "zenith cosines");
  read(t->cdf.data(), cells, "CDF table");
  read(offset_and_length.data(), 2 * cells, "coefficient offsets");
  read(t->a.data(), t->a.size(), "coefficients");
  for (size_t i = 1; i < t->mu.size(); ++i)
    if (!(t->mu[i] > t->mu[i - 1])) throw error(path, "its zenith cosines are not increasing");
  t->offset.resize(cells), t->order.resize(cells), t->a0.resize(cells);
  for (size_t c = 0; c < cells; ++c) {
    const int32_t off = offset_and_length[2 * c], len = offset_and_length[2 * c + 1];
    if (off < 0 || len < 0 || len > m_max || int64_t(off) + int64_t(len) * channels > n_coeffs)
      throw error(path, "coefficient block " + std::to_string(c) + " (offset " + std::to_string(off) + ", order " +
                            std::to_string(len) + ") lies outside the " + std::to_string(n_coeffs) + " coefficients");
    t->offset[c] = off, t->order[c] = len;
    t->a0[c] = len > 0 ? t->a[size_t(off)] : 0.f;
  }
  return t;
}

size_t FourierTable::memory_bytes() const {
  return sizeof(*this) + (mu.capacity() + a0.capacity() + cdf.capacity() + a.capacity()) * sizeof(float) +
         (offset.capacity() + order.capacity()) * sizeof(int32_t);
}

Spectrum FourierBSDF::f(const Vec3& wo, const Vec3& wi, TransportMode mode) const {
  const float mu_i = -wi.z, mu_o = wo.z;
  Coefficients c;
  if (!coefficients(*table, mu_i, mu_o, table->channels, &c)) return Spectrum(0.f);
  return unbounded_spectrum(colour(*table, c, cos_delta_phi(-wi, wo), mu_i, mu_o, mode), lambda);
}

std::optional<BSDFSample> FourierBSDF::sample_f(const Vec3& wo, float, Vec2 u, TransportMode mode, Lobes lobes) const {
  const float mu_o = wo.z;
  const float sin2_o = 1.f - mu_o * mu_o;
  // The zenith cosine from the luminance's a_0 along mu_i, then the azimuth
  // from the series there.
  const SplineSample z = sample_catmull_rom_2d(table->mu, table->mu, table->a0.data(), table->cdf.data(), mu_o, u.y);
  Coefficients c;
  if (!(z.pdf > 0.f) || !coefficients(*table, z.x, mu_o, table->channels, &c) || c.m == 0 || !(c.channel[0][0] > 0.f))
    return std::nullopt;
  const FourierSample a = sample_fourier(c.channel[0], c.m, u.x);
  const float mu_i = z.x;
  // -wi: wo's azimuth turned by phi, at zenith cosine mu_i. Seen from the
  // pole wo has no azimuth; x stands in for it (the limit's series does
  // not depend on phi).
  const float sin_o = std::sqrt(max_num(sin2_o, 0.f));
  const Vec2 e1 = sin_o > 1e-6f ? Vec2(wo.x, wo.y) / sin_o : Vec2(1.f, 0.f);
  const float sin_i = std::sqrt(max_num(0.f, 1.f - mu_i * mu_i));
  const float sp = std::sin(a.phi), cp = std::cos(a.phi);
  BSDFSample s;
  s.wi = -glm::normalize(Vec3(sin_i * (cp * e1.x - sp * e1.y), sin_i * (sp * e1.x + cp * e1.y), mu_i));
  s.pdf = a.pdf * z.pdf;
  s.transmission = mu_i * mu_o > 0.f;
  if (!(s.pdf > 0.f) || !std::isfinite(s.pdf) || !is_finite(s.wi)) return std::nullopt;
  if (!has(lobes, s.transmission ? Lobes::Transmission : Lobes::Reflection)) return std::nullopt;
  s.etap = s.transmission ? (mu_o > 0.f ? table->eta : 1.f / table->eta) : 1.f;
  s.f = unbounded_spectrum(colour(*table, c, cp, mu_i, mu_o, mode), lambda);
  return s;
}

float FourierBSDF::pdf(const Vec3& wo, const Vec3& wi, TransportMode, Lobes lobes) const {
  const float mu_i = -wi.z, mu_o = wo.z;
  if (!has(lobes, mu_i * mu_o > 0.f ? Lobes::Transmission : Lobes::Reflection)) return 0.f;
  Coefficients c;
  if (!coefficients(*table, mu_i, mu_o, 1, &c)) return 0.f;
  // The luminance's albedo at mu_o: 2 pi times the integral of a_0 over mu_i.
  SplineWeights wo_w;
  catmull_rom_weights(table->mu, mu_o, &wo_w);
  const size_t n = table->mu.size();
  float rho = 0.f;
  for (int b = 0; b < 4; ++b)
    if (wo_w.weight[b] != 0.f) rho += wo_w.weight[b] * table->cdf[size_t(wo_w.offset + b) * n + n - 1];
  rho *= 2.f * kPi;
  const float y = fourier(c.channel[0], c.m, cos_delta_phi(-wi, wo));
  return rho > 0.f && y > 0.f ? y / rho : 0.f;
}

}  // namespace lantern
