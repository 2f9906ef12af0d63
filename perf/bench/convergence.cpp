// Error against time: each integrator renders the scene for doubling time
// budgets, and relMSE against the reference is recorded. From the curve,
// the time each integrator needs to reach relMSE 1e-2 and 1e-3.
#include <cmath>
#include <cstdio>
#include <map>

#include "bench.h"
#include "film/image_metrics.h"

namespace bench {

namespace {

struct Point {
  double seconds, relmse;
};

// Time at which the log-log curve reaches `target`, interpolating between
// the points that bracket it, or extrapolating the last two points' slope.
std::string time_to(const std::vector<Point>& pts, double target) {
  for (size_t i = 0; i + 1 < pts.size(); ++i) {
    const Point &a = pts[i], &b = pts[i + 1];
    if (i == 0 && a.relmse <= target) return "< " + fmt(a.seconds);
    if (a.relmse > target && b.relmse <= target) {
      double t = std::log(target / a.relmse) / std::log(b.relmse / a.relmse);
      return fmt(std::exp(std::log(a.seconds) + t * std::log(b.seconds / a.seconds)));
    }
  }
  if (pts.size() < 2) return "n/a";
  const Point &a = pts[pts.size() - 2], &b = pts.back();
  double slope = std::log(b.relmse / a.relmse) / std::log(b.seconds / a.seconds);
  if (!(slope < -0.1)) return "not converging";
  return fmt(b.seconds * std::pow(target / b.relmse, 1.0 / slope)) + " (extrapolated)";
}

}  // namespace

int convergence(const Common& c, const std::string& name, const std::string& reference_path, double max_seconds,
                const std::vector<std::string>& integrators) {
  auto scene = load(c, name);
  lantern::Image reference = lantern::read_image(reference_path);
  Table t;
  t.header = {"integrator", "budget (s)", "render (s)", "spp", "relMSE"};
  std::map<std::string, std::vector<Point>> curves;
  for (const std::string& integrator : integrators) {
    for (double budget = max_seconds / 32.0; budget <= max_seconds * 1.001; budget *= 2.0) {
      lantern::RenderOptions o = scene_options(c, *scene, integrator);
      o.time_limit_seconds = budget;
      o.width = reference.width;
      o.height = reference.height;
      o.seed = 99;
      lantern::RenderResult r = lantern::render(*scene, o);
      double err = lantern::compare_images(r.image, reference).relmse;
      curves[integrator].push_back({r.stats.seconds, err});
      t.rows.push_back({integrator, fmt(budget), fmt(r.stats.seconds), std::to_string(r.stats.min_spp), fmt(err, 4)});
      std::fprintf(stderr, "convergence: %s %s %.2f s -> relMSE %.4g\n", name.c_str(), integrator.c_str(), budget, err);
    }
  }
  std::printf("Convergence: %s against %s\n\n", name.c_str(), reference_path.c_str());
  t.print();
  t.save_csv(c, "convergence_" + name);

  Table s;
  s.header = {"integrator", "time to relMSE 1e-2 (s)", "time to relMSE 1e-3 (s)"};
  for (const std::string& integrator : integrators)
    s.rows.push_back({integrator, time_to(curves[integrator], 1e-2), time_to(curves[integrator], 1e-3)});
  std::printf("Time to reach an error, %s\n\n", name.c_str());
  s.print();
  s.save_csv(c, "time_to_error_" + name);
  return 0;
}

}  // namespace bench
