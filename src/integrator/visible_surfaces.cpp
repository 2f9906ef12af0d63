// The gbuffer channels of pbrt-v4's GBufferFilm, from a pass of camera rays
// of their own after the render: the first surface each camera sample
// sees (alpha-cut and interface shapes passed through, mixes resolved,
// bump and normal maps applied), whatever integrator made the image. The
// samples are the path tracer's (the same film, lens and time dimensions);
// each pixel's are summed by one task in sample order, so the channels do
// not depend on the thread count.
#include <tbb/parallel_for.h>

#include "integrator/hit.h"
#include "integrator/hit_material.h"
#include "integrator/path_tracer.h"
#include "integrator/shutter.h"
#include "material/bsdf_kernel.h"
#include "math/frame.h"
#include "sampler/dimensions.h"

namespace lantern {

namespace {

// pbrt-v4's albedo of a visible surface: the BSDF's directional albedo
// (rho) estimated from 16 fixed samples, here the centres of a 4 x 4 grid
// with the component choice stratified across them.
template <class BSDF>
RGB directional_albedo(const BSDF& bsdf, const Vec3& wo_local) {
  Spectrum sum(0.f);
  for (int k = 0; k < 16; ++k) {
    const Vec2 u((float(k % 4) + 0.5f) / 4.f, (float(k / 4) + 0.5f) / 4.f);
    const float uc = (float((k * 7) % 16) + 0.5f) / 16.f;
    if (auto bs = bsdf.sample_f(wo_local, uc, u, TransportMode::Radiance); bs && bs->pdf > 0.f)
      sum += bs->f * (std::fabs(bs->wi.z) / bs->pdf);
  }
  const Spectrum a = sum / 16.f;
  return RGB(a[0], a[1], a[2]);
}

}  // namespace

VisibleSurfaces PathTracer::visible_surfaces(uint32_t samples, bool world_space, RayBackend backend) const {
  VisibleSurfaces out;
  out.width = settings_.width, out.height = settings_.height;
  constexpr int C = VisibleSurfaces::kChannels;
  out.values.assign(size_t(out.width) * size_t(out.height) * C, 0.f);
  const Mat4 camera_from_world = glm::inverse(scene_.camera.world_from_camera);
  // Points by the matrix, normals by its inverse transpose, dp/dx by its
  // linear part (pbrt's transformations of each kind); the slopes are
  // camera space's in either case, as pbrt-v4's.
  // The hits are in the space the scene is held in (render space): out of
  // it into the file's world, or into the camera's space.
  const Mat4 out_from_render = world_space ? scene_.camera.file_world_from_render : camera_from_world;
  const glm::mat3 normal_to_out = glm::transpose(glm::inverse(glm::mat3(out_from_render)));
  const glm::mat3 dp_to_camera = glm::mat3(camera_from_world);
  const FootprintModel dp(camera_, settings_.footprint_spp);
  const SampledWavelengths rgb = SampledWavelengths::rgb();

  tbb::parallel_for(0, out.height, [&](int y) {
    RayStream stream(scene_.accel->handle(), backend, nullptr);
    stream.set_scene(scene_.accel->instance_base(), &scene_.shapes);  // hits as shading reads them
    RayBatch rays;
    rays.reserve(size_t(out.width) * samples);
    // Each sample weighs its sign under a filter with negative lobes
    // (pixel_filter.h), as pbrt-v4's GBufferFilm weighs each by the
    // filter's weight: the albedo over all samples' weights, the rest over
    // those of the samples that hit.
    std::vector<double> weight;
    weight.reserve(size_t(out.width) * samples);
    for (int x = 0; x < out.width; ++x) {
      const uint32_t pixel = uint32_t(y) * uint32_t(out.width) + uint32_t(x);
      for (uint32_t j = 0; j < samples; ++j) {
        const PathSampler s = PathSampler::make(sampler_, pixel, j);
        const Vec2 u_film = s.get2d(dims::kFilm);
        weight.push_back(pixel_filter_negative(scene_.filter, u_film) ? -1.0 : 1.0);
        const Vec2 p_raster =
            sample_raster_position(scene_.filter, pixel, uint32_t(out.width), u_film) + settings_.raster_offset;
        const float time = sample_time(scene_, s, settings_.maxdepth);
        std::optional<Camera> moved;
        const CameraRay r =
            camera_at(camera_, time, moved).generate_ray(p_raster, lens_numbers(camera_, s, dims::kLens));
        rays.push(r.o, r.d, 0.f, r.weight > 0.f ? kInfinity : 0.f, time);
      }
    }
    stream.intersect(rays, RayKind::Camera);
    for (int x = 0; x < out.width; ++x) {
      double sum[C] = {}, weight_all = 0.0, weight_hits = 0.0;
      for (uint32_t j = 0; j < samples; ++j) {
        const uint32_t i = uint32_t(x) * samples + j;
        const double w = weight[i];
        weight_all += w;
        if (!rays.hit(i)) continue;
        const Vec3 d = glm::normalize(rays.direction(i));
        SurfacePoint sp = hit_point(scene_.shapes, rays, i);
        Footprint fp;
        const MaterialHandle m = hit_material(scene_, footprints_, rays, i, d, &sp, &fp);
        const Frame frame = Frame::from_z(sp.ns);
        const TextureContext tc{sp.p, sp.ng, sp.uv, footprints_.enabled() ? &fp : nullptr, sp.dpdu};
        const RGB albedo = with_bsdf(m, scene_.materials, scene_.textures, tc, rgb,
                                     [&](const auto& bsdf) { return directional_albedo(bsdf, frame.to_local(-d)); });
        Vec3 dpdx, dpdy;
        dp.dp_dxy(sp.p, sp.ng, &dpdx, &dpdy);
        const Vec3 p = Vec3(out_from_render * Vec4(sp.p, 1.f));
        // Turned to face the camera, as pbrt-v4 turns them (to the side of
        // the direction back along the ray), whatever the mesh's winding.
        auto facing = [&](const Vec3& v) { return glm::dot(v, d) > 0.f ? -v : v; };
        const Vec3 n = normal_to_out * facing(sp.ng), ns = normal_to_out * facing(sp.ns);
        const float v[C] = {albedo[0],
                            albedo[1],
                            albedo[2],
                            p.x,
                            p.y,
                            p.z,
                            (dp_to_camera * dpdx).z,
                            (dp_to_camera * dpdy).z,
                            n.x,
                            n.y,
                            n.z,
                            ns.x,
                            ns.y,
                            ns.z,
                            sp.uv.x,
                            sp.uv.y};
        for (int c = 0; c < C; ++c) sum[c] += w * double(v[c]);
        weight_hits += w;
      }
      float* o = &out.values[(size_t(y) * size_t(out.width) + size_t(x)) * C];
      if (weight_all != 0.0)
        for (int c = VisibleSurfaces::AlbedoR; c <= VisibleSurfaces::AlbedoB; ++c) o[c] = float(sum[c] / weight_all);
      if (weight_hits == 0.0) continue;  // (no hit, or signs that cancel: nothing to average, as in pbrt-v4)
      for (int c : {int(VisibleSurfaces::PX), int(VisibleSurfaces::PY), int(VisibleSurfaces::PZ),
                    int(VisibleSurfaces::U), int(VisibleSurfaces::V)})
        o[c] = float(sum[c] / weight_hits);
      // pbrt-v4 writes the slopes' magnitudes.
      o[VisibleSurfaces::DzDx] = float(std::fabs(sum[VisibleSurfaces::DzDx] / weight_hits));
      o[VisibleSurfaces::DzDy] = float(std::fabs(sum[VisibleSurfaces::DzDy] / weight_hits));
      for (int first : {int(VisibleSurfaces::NX), int(VisibleSurfaces::NsX)}) {
        const glm::dvec3 n(sum[first], sum[first + 1], sum[first + 2]);
        const double len = glm::length(n);
        for (int k = 0; k < 3; ++k) o[first + k] = len > 0.0 ? float(n[k] / len) : 0.f;
      }
    }
  });
  return out;
}

void add_gbuffer_channels(const VisibleSurfaces& v, const Film& film, Image* image) {
  static const char* kNames[] = {"Albedo.R",
                                 "Albedo.G",
                                 "Albedo.B",
                                 "P.X",
                                 "P.Y",
                                 "P.Z",
                                 "dzdx",
                                 "dzdy",
                                 "N.X",
                                 "N.Y",
                                 "N.Z",
                                 "Ns.X",
                                 "Ns.Y",
                                 "Ns.Z",
                                 "u",
                                 "v",
                                 "Variance.R",
                                 "Variance.G",
                                 "Variance.B",
                                 "RelativeVariance.R",
                                 "RelativeVariance.G",
                                 "RelativeVariance.B"};
  constexpr int C = VisibleSurfaces::kChannels, kAll = C + 6;
  image->channel_names.assign(kNames, kNames + kAll);
  const size_t pixels = size_t(v.width) * size_t(v.height);
  image->channels.assign(pixels * kAll, 0.f);
  for (size_t i = 0; i < pixels; ++i) {
    float* o = &image->channels[i * kAll];
    std::copy(&v.values[i * C], &v.values[i * C] + C, o);
    for (int c = 0; c < 3; ++c) {
      // pbrt-v4's VarianceEstimator: the samples' unbiased variance, and
      // that over their mean.
      const double var = film.sample_variance(i, c);
      const double n = double(film.sample_count(i));
      const double mean = n > 0.0 ? double(image->rgb[3 * i + size_t(c)]) : 0.0;
      o[C + c] = float(var);
      o[C + 3 + c] = mean != 0.0 ? float(var / mean) : 0.f;
    }
  }
}

}  // namespace lantern
