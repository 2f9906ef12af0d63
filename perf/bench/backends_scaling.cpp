// The ray-query back ends on the same scene, integrator and samples; and
// scaling with threads and wave size. Ratios within one run, medians of
// alternating rounds, because single timings on this machine are noisy.
#include <cstdio>
#include <map>
#include <thread>

#include "bench.h"

namespace bench {

int backends(const Common& c, const std::string& name, const std::string& integrator, int spp, int rounds) {
  auto scene = load(c, name);
  const char* kinds[] = {"stream", "stream-1m", "single", "packet16"};
  std::map<std::string, std::vector<double>> sps, rps;
  for (int r = 0; r < rounds; ++r)
    for (const char* b : kinds) {
      lantern::RenderOptions o = scene_options(c, *scene, integrator);
      o.spp = spp;
      o.ray_backend = lantern::parse_ray_backend(b);
      lantern::RenderStats s = render_stats(*scene, o);
      sps[b].push_back(double(s.samples) / s.seconds);
      rps[b].push_back(double(s.camera_rays + s.extension_rays + s.light_rays + s.shadow_rays) / s.seconds);
    }
  Table t;
  t.header = {"back end", "Msamples/s", "Mrays/s", "vs stream"};
  double base = median(sps["stream"]);
  for (const char* b : kinds)
    t.rows.push_back({b, fmt(median(sps[b]) * 1e-6), fmt(median(rps[b]) * 1e-6), fmt(median(sps[b]) / base)});
  std::printf("Ray back ends: %s, %s, %d spp, median of %d alternating rounds\n\n", name.c_str(), integrator.c_str(),
              spp, rounds);
  t.print();
  t.save_csv(c, "backends_" + name + "_" + integrator);
  return 0;
}

int scaling(const Common& c, const std::string& name, const std::string& integrator, int spp) {
  auto scene = load(c, name);
  auto run = [&](int threads, int wave) {
    lantern::RenderOptions o = scene_options(c, *scene, integrator);
    o.spp = spp;
    o.threads = threads;
    o.wave_size = wave;
    lantern::RenderStats s = render_stats(*scene, o);
    return double(s.samples) / s.seconds;
  };
  const int cores = int(std::max(1u, std::thread::hardware_concurrency()));
  std::vector<int> thread_counts = {1, 2};
  if (cores > 2) thread_counts.push_back(cores);
  Table t;
  t.header = {"threads", "Msamples/s", "vs 1 thread"};
  std::map<int, std::vector<double>> by_threads;
  for (int r = 0; r < 3; ++r)
    for (int n : thread_counts) by_threads[n].push_back(run(n, 4096));
  for (int n : thread_counts)
    t.rows.push_back({std::to_string(n), fmt(median(by_threads[n]) * 1e-6),
                      fmt(median(by_threads[n]) / median(by_threads[1]))});
  std::printf("Thread scaling: %s, %s, %d spp, wave size 4096, median of 3 rounds (%d cores)\n\n", name.c_str(),
              integrator.c_str(), spp, cores);
  t.print();
  t.save_csv(c, "scaling_threads");

  Table w;
  w.header = {"wave size", "Msamples/s", "vs 4096"};
  const int waves[] = {256, 512, 1024, 2048, 4096, 8192};
  std::map<int, std::vector<double>> by_wave;
  for (int r = 0; r < 3; ++r)
    for (int size : waves) by_wave[size].push_back(run(c.threads, size));
  for (int size : waves)
    w.rows.push_back({std::to_string(size), fmt(median(by_wave[size]) * 1e-6),
                      fmt(median(by_wave[size]) / median(by_wave[4096]))});
  std::printf("Wave size: %s, %s, %d spp, all threads, median of 3 rounds\n\n", name.c_str(), integrator.c_str(),
              spp);
  w.print();
  w.save_csv(c, "scaling_waves");
  return 0;
}

}  // namespace bench
