// Which pixels split their camera samples at the first hit
// (PathTracerSettings::split). A split pixel has fewer camera samples, so
// the variance that where in the pixel a camera sample looks causes grows:
// splitting pays where that variance is small and the paths beyond the
// first hit make the rest. It is large where the pixel sees an emitter
// (the edge of a light: in the Cornell box its 0.8% of the pixels made
// 66% of a split render's squared error, docs/splitting.md), the sky of
// an infinite light, or a surface that may be specular (what it mirrors),
// and there the camera samples stay whole.
//
// Each pixel's first four camera samples look, one ray each: a pure
// function of the pixel and the seed, so the image does not depend on the
// threads, the waves or the parts.
#include <tbb/parallel_for.h>

#include "integrator/hit.h"
#include "integrator/hit_material.h"
#include "integrator/path_tracer.h"
#include "integrator/shutter.h"
#include "material/may_be_specular.h"
#include "sampler/dimensions.h"

namespace lantern {

namespace {
constexpr uint32_t kProbes = 4;
}

// For each of `pixels` (of the film), whether one of its probes sees what
// keeps its camera samples whole.
std::vector<uint8_t> PathTracer::probe_pixels(const std::vector<uint32_t>& pixels, RayBackend backend) const {
  const uint32_t width = uint32_t(settings_.width);
  const bool sky = !scene_.lights.infinite.empty();
  RayStream stream(scene_.accel->handle(), backend, nullptr);
  stream.set_scene(scene_.accel->instance_base(), &scene_.shapes);  // hits as shading reads them
  RayBatch rays;
  rays.reserve(pixels.size() * kProbes);
  for (const uint32_t pixel : pixels)
    for (uint32_t j = 0; j < kProbes; ++j) {
      const PathSampler s = PathSampler::make(camera_sampler_, pixel, j);
      const Vec2 p_raster =
          sample_raster_position(scene_.filter, pixel, width, s.get2d(dims::kFilm)) + settings_.raster_offset;
      const float time = sample_time(scene_, s, settings_.maxdepth);
      std::optional<Camera> moved;
      const CameraRay r = camera_at(camera_, time, moved).generate_ray(p_raster, lens_numbers(camera_, s, dims::kLens));
      rays.push(r.o, r.d, 0.f, r.weight > 0.f ? kInfinity : 0.f, time);
    }
  stream.intersect(rays, RayKind::Camera);
  std::vector<uint8_t> whole(pixels.size(), 0);
  for (size_t k = 0; k < pixels.size(); ++k)
    for (uint32_t j = 0; j < kProbes && !whole[k]; ++j) {
      const uint32_t i = uint32_t(k) * kProbes + j;
      if (!rays.hit(i)) {
        whole[k] = sky;
        continue;
      }
      if (hit_area_light(scene_.shapes, rays, i) >= 0) {
        whole[k] = 1;
        continue;
      }
      const Vec3 d = glm::normalize(rays.direction(i));
      SurfacePoint sp = hit_point(scene_.shapes, rays, i);
      Footprint fp;
      const MaterialHandle m = hit_material(scene_, footprints_, rays, i, d, &sp, &fp);
      whole[k] = may_be_specular(scene_.materials, scene_.textures, m);
    }
  return whole;
}

// A pixel the light only partly covers may have no probe that sees it: its
// neighbours' probes do, and it stays whole with them. Every pixel's probes
// are traced once and the result spread to the eight around it; a pilot's
// pixels, far apart, trace their neighbours' probes themselves.
std::vector<uint8_t> PathTracer::find_split_pixels(RayBackend backend) const {
  const int width = settings_.width, height = settings_.height, stride = int(settings_.probe_stride);
  const uint32_t columns = uint32_t(probe_columns()), rows = uint32_t(probe_rows());
  std::vector<uint8_t> split(size_t(columns) * size_t(rows), 0);
  if (stride == 1) {
    std::vector<uint8_t> whole_here(split.size(), 0);
    tbb::parallel_for(0, height, [&](int y) {
      std::vector<uint32_t> row(static_cast<size_t>(width));
      for (int x = 0; x < width; ++x) row[size_t(x)] = uint32_t(y) * uint32_t(width) + uint32_t(x);
      const std::vector<uint8_t> w = probe_pixels(row, backend);
      std::copy(w.begin(), w.end(), whole_here.begin() + ptrdiff_t(y) * width);
    });
    tbb::parallel_for(0, height, [&](int y) {
      for (int x = 0; x < width; ++x) {
        bool whole = false;
        for (int yy = std::max(y - 1, 0); yy <= std::min(y + 1, height - 1); ++yy)
          for (int xx = std::max(x - 1, 0); xx <= std::min(x + 1, width - 1); ++xx)
            whole = whole || whole_here[size_t(yy) * size_t(width) + size_t(xx)] != 0;
        split[size_t(y) * size_t(width) + size_t(x)] = whole ? 0 : 1;
      }
    });
    return split;
  }
  tbb::parallel_for(0u, rows, [&](uint32_t r) {
    const int y = stride / 2 + int(r) * stride;
    std::vector<uint32_t> around;  // each probed pixel's 3 x 3, in turn
    std::vector<uint32_t> count;
    for (uint32_t c = 0; c < columns; ++c) {
      const int x = stride / 2 + int(c) * stride;
      const size_t before = around.size();
      for (int yy = std::max(y - 1, 0); yy <= std::min(y + 1, height - 1); ++yy)
        for (int xx = std::max(x - 1, 0); xx <= std::min(x + 1, width - 1); ++xx)
          around.push_back(uint32_t(yy) * uint32_t(width) + uint32_t(xx));
      count.push_back(uint32_t(around.size() - before));
    }
    const std::vector<uint8_t> w = probe_pixels(around, backend);
    size_t k = 0;
    for (uint32_t c = 0; c < columns; ++c) {
      bool whole = false;
      for (uint32_t n = 0; n < count[c]; ++n) whole = whole || w[k++] != 0;
      split[size_t(r) * columns + c] = whole ? 0 : 1;
    }
  });
  return split;
}

}  // namespace lantern
