#include "film/strategy_film.h"

#include <algorithm>

namespace lantern {

StrategyFilm::Sums& StrategyFilm::sums(int s, int t, bool merge) {
  for (Sums& x : strategies_)
    if (x.s == s && x.t == t && x.merge == merge) return x;
  Sums& x = strategies_.emplace_back();
  x.s = s;
  x.t = t;
  x.merge = merge;
  x.weighted.assign(3 * size_t(width_) * size_t(height_), 0.0);
  x.unweighted.assign(x.weighted.size(), 0.0);
  return x;
}

void StrategyFilm::merge(const std::vector<StrategyRecord>& records, const Film& film) {
  for (const StrategyRecord& r : records) {
    const RGB weighted = film.sensed(r.weighted), unweighted = film.sensed(r.unweighted);
    if (!is_finite(weighted) || !is_finite(unweighted)) continue;
    Sums& x = sums(r.s, r.t, r.merge);
    auto add = [&](size_t pixel, float w) {
      for (size_t c = 0; c < 3; ++c) {
        x.weighted[3 * pixel + c] += double(w * weighted[int(c)]);
        x.unweighted[3 * pixel + c] += double(w * unweighted[int(c)]);
      }
    };
    if (r.t == 1)
      for_each_splat_pixel(filter_, width_, height_, r.p_raster - film.raster_offset(), add);
    else
      add(r.pixel, 1.f);
  }
}

std::vector<StrategyImage> StrategyFilm::resolve(const Film& film) const {
  std::vector<StrategyImage> out;
  const size_t n = size_t(width_) * size_t(height_);
  const double splat_scale = film.splat_scale();
  for (const Sums& x : strategies_) {
    StrategyImage img{x.s, x.t, {}, {}, x.merge};
    for (Image* im : {&img.weighted, &img.unweighted}) {
      im->width = width_;
      im->height = height_;
      im->rgb.assign(3 * n, 0.f);
    }
    for (size_t i = 0; i < n; ++i) {
      uint32_t count = film.sample_count(i);
      double scale = x.t == 1 ? splat_scale : (count ? 1.0 / double(count) : 0.0);
      for (size_t c = 0; c < 3; ++c) {
        img.weighted.rgb[3 * i + c] = float(x.weighted[3 * i + c] * scale);
        img.unweighted.rgb[3 * i + c] = float(x.unweighted[3 * i + c] * scale);
      }
    }
    out.push_back(std::move(img));
  }
  // By path length (segments), connections before merges, then by s.
  auto segments = [](const StrategyImage& x) { return x.s + x.t - (x.merge ? 2 : 1); };
  std::sort(out.begin(), out.end(), [&](const StrategyImage& a, const StrategyImage& b) {
    if (segments(a) != segments(b)) return segments(a) < segments(b);
    return a.merge != b.merge ? b.merge : a.s < b.s;
  });
  return out;
}

}  // namespace lantern
