// Samples/s, rays/s by kind and where the thread time goes, per scene and
// integrator, at a fixed sample count.
#include <cstdio>

#include "bench.h"

namespace bench {

namespace {
double stage(const lantern::RenderStats& s, const std::string& name) {
  for (const auto& [n, sec] : s.stage_seconds)
    if (n == name) return sec;
  return 0.0;
}
}  // namespace

int throughput(const Common& c, const std::vector<std::string>& scenes, int spp, int width, int height) {
  Table t;
  t.header = {"scene", "integrator", "Msamples/s", "Mrays/s", "camera", "eye ext.", "light ext.", "shadow/conn.",
              "% rays", "% generate", "% surface", "% shade", "% accumulate",
              "eye verts", "light verts"};
  for (const std::string& name : scenes) {
    auto scene = load(c, name);
    for (const char* integrator : {"path", "bdpt", "lt"}) {
      lantern::RenderOptions o = scene_options(c, *scene, integrator);
      o.spp = spp;
      o.width = width;
      o.height = height;
      o.collect_stats = true;
      lantern::RenderStats s = render_stats(*scene, o);
      double rays_t = s.camera_ray_seconds + s.extension_ray_seconds + s.light_ray_seconds + s.shadow_ray_seconds;
      double total_t = rays_t;
      for (const auto& st : s.stage_seconds) total_t += st.second;
      auto pct = [&](double x) { return fmt(100.0 * x / total_t, 2); };
      auto mps = [&](uint64_t n) { return fmt(double(n) / s.seconds * 1e-6, 3); };
      uint64_t rays = s.camera_rays + s.extension_rays + s.light_rays + s.shadow_rays;
      t.rows.push_back({name, integrator, mps(s.samples), mps(rays), mps(s.camera_rays), mps(s.extension_rays),
                        mps(s.light_rays), mps(s.shadow_rays), pct(rays_t), pct(stage(s, "generate")),
                        pct(stage(s, "surface")), pct(stage(s, "shade")), pct(stage(s, "accumulate")),
                        fmt(s.samples ? double(s.eye_vertices) / double(s.samples) : 0.0),
                        fmt(s.light_paths ? double(s.light_vertices) / double(s.light_paths) : 0.0)});
      std::fprintf(stderr, "throughput: %s %s done\n", name.c_str(), integrator);
    }
  }
  std::printf("Throughput at %d spp, %dx%d (rays columns: Mrays/s of that kind; %% of thread time)\n\n", spp, width,
              height);
  t.print();
  t.save_csv(c, "throughput");
  return 0;
}

}  // namespace bench
