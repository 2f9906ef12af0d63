#include "app/render_watch.h"

#include <chrono>
#include <memory>

#include "app/display_server.h"
#include "app/log.h"
#include "app/outputs.h"
#include "app/session_watcher.h"

namespace lantern {

namespace {

// Partial images: the image of the passes so far, written over the output
// (atomically, as every image) with its samples in the header and
// lantern:partial. A failed write is the watcher's warning (once); the
// render goes on.
std::unique_ptr<SessionWatcher> partial_images(const Watchers& w, const RenderSession& session) {
  auto look = [&w, &session](const Image& image, uint32_t spp) {
    if (image.rgb.empty()) return;
    RenderResult partial;
    const RenderProgress p = session.progress();
    partial.stats.samples = p.samples_done;
    partial.stats.min_spp = spp;
    partial.stats.seconds = p.elapsed_seconds;
    partial.total_render_seconds = p.elapsed_seconds;
    write_output_image(w.partial_path, image, w.partial_metadata ? w.partial_metadata(partial) : ImageMetadata{});
    logging::verbose("partial image: %s, %u spp", w.partial_path.c_str(), spp);
  };
  return std::make_unique<SessionWatcher>(look, 0.0, w.partial_seconds);
}

}  // namespace

RenderResult render_watched(const Scene& scene, const RenderOptions& o, RenderHooks hooks, const Watchers& w) {
  const bool log_passes = w.log_passes && logging::enabled(logging::Level::Verbose);
  if (w.display_server.empty() && w.partial_path.empty() && !log_passes) return render(scene, o, hooks);
  std::unique_ptr<DisplayServer> display;
  std::unique_ptr<SessionWatcher> partial;
  const auto begin = std::chrono::steady_clock::now();
  hooks.pass_done = [&display, &partial, begin, log_passes, earlier = hooks.pass_done](uint32_t spp) {
    if (earlier) earlier(spp);
    if (display) display->pass_done(spp);
    if (partial) partial->pass_done(spp);
    if (log_passes)
      logging::verbose("pass: %u spp at %.2f s", spp,
                       std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count());
  };
  RenderSession session(scene, o, hooks);
  // The watchers' threads read the session: they stop before it goes,
  // however this function is left (this guard is destroyed first).
  struct StopWatchers {
    std::unique_ptr<DisplayServer>& display;
    std::unique_ptr<SessionWatcher>& partial;
    ~StopWatchers() {
      partial.reset();
      display.reset();
    }
  } guard{display, partial};
  if (!w.display_server.empty()) {
    try {
      display = std::make_unique<DisplayServer>(w.display_server, w.display_name, session.width(), session.height());
      display->watch(session);
    } catch (const std::exception& e) {
      logging::warning("warning: %s; rendering without it", e.what());
    }
  }
  if (!w.partial_path.empty()) {
    partial = partial_images(w, session);
    partial->watch(session);
  }
  RenderResult r = session.run();  // (not const: returned by move, not copied)
  if (partial) partial->stop();  // before the final image is written over its partial ones
  if (display) display->stop(r.image);
  return r;
}

}  // namespace lantern
