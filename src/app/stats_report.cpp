#include "app/stats_report.h"

#include "app/huge_pages.h"
#include "app/log.h"

#include "sampler/sampler.h"

#include <sys/resource.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>

namespace lantern {

size_t peak_rss_bytes() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return size_t(u.ru_maxrss) * 1024;  // Linux reports kilobytes
}

size_t rss_bytes() {
  unsigned long long pages = 0, resident = 0;
  std::FILE* f = std::fopen("/proc/self/statm", "r");
  if (!f) return 0;
  const int n = std::fscanf(f, "%llu %llu", &pages, &resident);
  std::fclose(f);
  return n == 2 ? size_t(resident) * size_t(sysconf(_SC_PAGESIZE)) : 0;
}

namespace {

double per_second(double count, double seconds) { return seconds > 0.0 ? count / seconds : 0.0; }

nlohmann::json ray_entry(uint64_t count, double render_seconds, double query_seconds, bool timed) {
  nlohmann::json j = {{"count", count}, {"per_second", per_second(double(count), render_seconds)}};
  if (timed) {
    j["query_thread_seconds"] = query_seconds;
    j["per_query_thread_second"] = per_second(double(count), query_seconds);
  }
  return j;
}

nlohmann::json subpath_entry(uint64_t vertices, uint64_t paths, const std::vector<std::pair<std::string, uint64_t>>& ends) {
  nlohmann::json ended = nlohmann::json::object();
  for (const auto& [name, n] : ends) ended[name] = n;
  return {{"vertices", vertices}, {"mean_vertices", paths ? double(vertices) / double(paths) : 0.0}, {"ended", ended}};
}

}  // namespace

nlohmann::json stats_json(const RunInfo& run, const RenderStats& s) {
  nlohmann::json j;
  j["scene"] = run.scene;
  j["output"] = run.output;
  j["integrator"] = run.integrator;
  j["ray_backend"] = run.ray_backend;
  j["resolution"] = {run.width, run.height};
  j["wave_size"] = run.wave_size;
  j["threads"] = s.threads;
  j["samples"] = s.samples;
  j["min_spp"] = s.min_spp;
  j["max_spp"] = s.max_spp;
  if (s.estimated_relmse >= 0) j["estimated_relmse"] = s.estimated_relmse;
  if (s.guiding_leaves > 0 || s.guiding_light_leaves > 0)
    j["guiding"] = {{"iterations", s.guiding_iterations},
                    {"spatial_leaves", s.guiding_leaves},
                    {"directional_nodes", s.guiding_nodes},
                    {"medium_leaves", s.guiding_medium_leaves},
                    {"distance_leaves", s.guiding_distance_leaves},
                    {"distance_lit_leaves", s.guiding_distance_lit_leaves},
                    {"light_leaves", s.guiding_light_leaves},
                    {"bytes", s.guiding_bytes},
                    {"records", s.guiding_records},
                    {"records_aimed", s.guiding_records_aimed},
                    {"light_records", s.guiding_light_records},
                    {"stopped_after", s.guiding_stopped_after},
                    {"share", s.guiding_share},
                    {"light_stopped_after", s.guiding_light_stopped_after},
                    {"light_share", s.guiding_light_share}};
  j["light_paths"] = s.light_paths;
  j["seconds"] = {{"load", run.load_seconds}, {"bvh_build", run.scene_info.bvh_build_seconds}, {"render", s.seconds}};
  j["load_phases"] = nlohmann::json::array();
  for (const LoadPhase& p : run.load_phases)
    j["load_phases"].push_back(
        {{"stage", p.stage}, {"end_seconds", p.end_seconds}, {"rss_bytes", p.rss_bytes}, {"peak_rss_bytes", p.peak_rss_bytes}});
  j["samples_per_second"] = per_second(double(s.samples), s.seconds);
  const uint64_t total = s.camera_rays + s.extension_rays + s.light_rays + s.shadow_rays;
  j["rays"] = {{"camera", ray_entry(s.camera_rays, s.seconds, s.camera_ray_seconds, s.timed)},
               {"eye_extension", ray_entry(s.extension_rays, s.seconds, s.extension_ray_seconds, s.timed)},
               {"light_extension", ray_entry(s.light_rays, s.seconds, s.light_ray_seconds, s.timed)},
               {"shadow_connection", ray_entry(s.shadow_rays, s.seconds, s.shadow_ray_seconds, s.timed)},
               {"total", {{"count", total}, {"per_second", per_second(double(total), s.seconds)}}}};
  if (s.timed) {
    nlohmann::json stages = nlohmann::json::object();
    for (const auto& [name, sec] : s.stage_seconds) stages[name] = sec;
    double rays = s.camera_ray_seconds + s.extension_ray_seconds + s.light_ray_seconds + s.shadow_ray_seconds;
    stages["ray_queries"] = rays;
    j["stage_thread_seconds"] = stages;
    j["film_merge_seconds"] = s.film_seconds;
  }
  j["subpaths"] = {{"eye", subpath_entry(s.eye_vertices, s.samples, s.eye_ends)},
                   {"light", subpath_entry(s.light_vertices, s.light_paths, s.light_ends)}};
  j["nonfinite_samples"] = s.nonfinite_samples;
  auto describe = [](const SamplerSettings& s) {
    nlohmann::json d = {{"type", name(s.type)}, {"seed", s.seed}};
    const SamplerKind kind = s.type;
    d["randomization"] = s.randomization.empty() ? randomization_name(default_randomization(kind)) : s.randomization;
    if (kind == SamplerKind::Stratified) d["strata"] = {s.xsamples, s.ysamples}, d["jitter"] = s.jitter;
    return d;
  };
  j["sampler"] = {{"used", describe(run.sampler)}, {"scene", describe(run.scene_sampler)}};
  j["light_sampler"] = {{"used", s.light_sampler}, {"scene", run.scene_light_sampler}};
  if (s.light_sampler == "bvh")
    j["light_sampler"]["bvh"] = {{"nodes", s.light_bvh_nodes},
                                 {"depth", s.light_bvh_depth},
                                 {"memory_bytes", s.light_sampler_bytes},
                                 {"build_seconds", s.light_sampler_seconds}};
  // How often a chosen light was worth its shadow ray: a direct view of
  // light-selection quality.
  j["next_event"] = {{"light_samples", s.light_samples},
                     {"unoccluded_nonzero", s.light_samples_unoccluded},
                     {"fraction", s.light_samples ? double(s.light_samples_unoccluded) / double(s.light_samples) : 0.0}};
  if (s.vcm_radius > 0.f)
    j["vcm"] = {{"merges", s.merges},
                {"merges_per_eye_vertex", s.eye_vertices ? double(s.merges) / double(s.eye_vertices) : 0.0},
                {"light_subpaths_per_wave", s.vcm_wave_paths},
                {"first_radius", s.vcm_radius},
                {"last_radius", s.vcm_last_radius},
                {"grid_build_seconds", s.vcm_grid_seconds}};
  if (s.merging_pilot >= 0) {
    j["merging"] = {{"merges", s.merging_pilot == 1}, {"from_checkpoint", s.merging_from_checkpoint}};
    if (!s.merging_from_checkpoint)
      j["merging"]["pilot"] = {{"candidates", {"vcm", "bdpt"}},
                               {"relmse_per_sample", s.merging_error},
                               {"rays_per_sample", s.merging_cost},
                               {"bdpt_missed_light", s.merging_missed},
                               {"seconds", s.merging_seconds}};
  }
  if (s.split > 0) {
    j["split"] = {{"paths_per_camera_sample", s.split}};
    if (!s.split_error.empty())
      j["split"]["pilot"] = {{"candidates", s.split_candidates},
                             {"error_at_equal_time", s.split_error},
                             {"camera_sample_share_of_work", s.split_camera_share}};
  }
  if (s.light_subpath_rate >= 0.f) {
    j["light_subpaths"] = {{"rate", s.light_subpath_rate}};
    if (!s.light_subpath_error.empty())
      j["light_subpaths"]["pilot"] = {{"rates", s.light_subpath_candidates},
                                      {"relmse_per_sample", s.light_subpath_error},
                                      {"rays_per_sample", s.light_subpath_cost}};
    if (!s.light_choice.empty())
      j["light_subpaths"]["light_choice"] = {{"chosen", s.light_choice},
                                             {"probabilities", s.light_choice_probability},
                                             {"pilot",
                                              {{"candidates", s.light_choice_candidates},
                                               {"relmse_per_sample", s.light_choice_error},
                                               {"mse_per_sample", s.light_choice_mse},
                                               {"rays_per_sample", s.light_choice_cost}}}};
  }
  if (s.mlt_chains > 0)
    j["mlt"] = {{"chains", s.mlt_chains},
                {"proposals", s.mlt_proposals},
                {"accepted", s.mlt_accepted},
                {"b", s.mlt_b}};
  j["memory"] = {{"peak_rss_bytes", peak_rss_bytes()},
                 {"wave_pools_bytes", s.wave_pool_bytes},
                 {"bvh_bytes", run.scene_info.bvh_bytes},
                 {"bvh_peak_bytes", run.scene_info.bvh_peak_bytes},
                 {"geometry_bytes", run.scene_info.geometry_bytes},
                 {"compact_instances", run.scene_info.compact_instances},
                 {"compact_bvh", run.scene_info.compact_bvh},
                 {"huge_pages", heap_in_huge_pages()},
                 {"anon_huge_pages_bytes", anon_huge_page_bytes()}};
  if (s.texture_cache) {
    j["texture_cache"] = {{"lookups", s.texture_lookups},
                          {"bytes_read", s.texture_bytes_read},
                          {"tiles_read", s.texture_tiles_read},
                          {"peak_tiles", s.texture_peak_tiles},
                          {"memory_bytes", s.texture_cache_bytes},
                          {"failed_lookups", s.texture_failed_lookups}};
    // Part of the shading stages' thread-seconds, not added to them.
    if (s.timed) j["texture_cache"]["lookup_thread_seconds"] = s.texture_lookup_seconds;
  }
  j["scene_contents"] = {{"triangles", run.scene_info.triangles},
                         {"spheres", run.scene_info.spheres},
                         {"lights", run.scene_info.lights},
                         {"bilinear_patches", run.scene_info.bilinear_patches},
                         {"curve_segments", run.scene_info.curve_segments},
                         {"instances", run.scene_info.instances},
                         {"instanced_triangles", run.scene_info.instanced_triangles}};
  return j;
}

void print_stage_summary(const RenderStats& s) {
  double rays = s.camera_ray_seconds + s.extension_ray_seconds + s.light_ray_seconds + s.shadow_ray_seconds;
  double total = rays;
  for (const auto& st : s.stage_seconds) total += st.second;
  if (total <= 0.0) return;
  char buf[96];
  std::snprintf(buf, sizeof buf, "thread time: ray queries %.0f%%", 100.0 * rays / total);
  std::string line = buf;
  for (const auto& [name, sec] : s.stage_seconds) {
    std::snprintf(buf, sizeof buf, ", %s %.0f%%", name.c_str(), 100.0 * sec / total);
    line += buf;
  }
  std::snprintf(buf, sizeof buf, "; film merge %.2f s", s.film_seconds);
  logging::line(logging::Level::Info, line + buf);
  std::snprintf(buf, sizeof buf, "subpaths: eye %.2f vertices", s.samples ? double(s.eye_vertices) / double(s.samples) : 0.0);
  line = buf;
  if (s.light_paths) {
    std::snprintf(buf, sizeof buf, ", light %.2f vertices", double(s.light_vertices) / double(s.light_paths));
    line += buf;
  }
  logging::line(logging::Level::Info, line + " on average");
}

nlohmann::json comparison_json(const ImageComparison& m) {
  auto triple = [](const std::array<double, 3>& v) { return nlohmann::json::array({v[0], v[1], v[2]}); };
  return {{"mse", m.mse}, {"relmse", m.relmse}, {"relmse_robust", m.relmse_robust},
          {"robust_excluded_pixels", m.robust_excluded}, {"mae", m.mae},
          {"psnr", std::isfinite(m.psnr) ? nlohmann::json(m.psnr) : nlohmann::json(nullptr)},
          {"pbrt_mse", triple(m.pbrt_mse)}, {"pbrt_mrse", triple(m.pbrt_mrse)},
          {"mean", triple(m.mean_a)}, {"mean_ref", triple(m.mean_ref)}, {"ratio", triple(m.ratio)},
          {"nonfinite_pixels", m.nonfinite}};
}

}  // namespace lantern
