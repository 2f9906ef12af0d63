#include "app/viewer.h"

#define GLFW_INCLUDE_NONE
#include <GL/gl.h>
#include <GLFW/glfw3.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <glm/gtc/matrix_transform.hpp>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "lantern/error.h"
#include "lantern/render.h"
#include "integrator/render_settings.h"
#include "scene/scene.h"

namespace lantern {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// Lines on standard output for whoever drives the window (a script, the
// test under Xvfb): "view: <event> ...", flushed at once.
void say(const std::string& line) {
  std::printf("view: %s\n", line.c_str());
  std::fflush(stdout);
}

// What the keys ask for, taken from GLFW's callbacks and done by the loop.
struct Requests {
  bool screenshot = false, reload = false, restart = false;
  int integrator = -1;    // index into option_words::kIntegrators
  int spp_scale = 0;      // +1 doubles the budget, -1 halves it
  float exposure_scale = 1.f;
  glm::vec3 move{0.f};    // camera-space steps (x right, y up, z forward)
  glm::vec2 turn{0.f};    // degrees: yaw, pitch
  bool dragging = false;
  double drag_x = 0, drag_y = 0;
};

void on_key(GLFWwindow* w, int key, int, int action, int) {
  if (action == GLFW_RELEASE) return;
  auto& q = *static_cast<Requests*>(glfwGetWindowUserPointer(w));
  switch (key) {
    case GLFW_KEY_ESCAPE: glfwSetWindowShouldClose(w, GLFW_TRUE); break;
    case GLFW_KEY_F1: q.screenshot = true; break;
    case GLFW_KEY_R: q.reload = true; break;
    case GLFW_KEY_EQUAL: case GLFW_KEY_KP_ADD: q.exposure_scale *= 2.f; break;
    case GLFW_KEY_MINUS: case GLFW_KEY_KP_SUBTRACT: q.exposure_scale *= 0.5f; break;
    case GLFW_KEY_RIGHT_BRACKET: ++q.spp_scale; break;
    case GLFW_KEY_LEFT_BRACKET: --q.spp_scale; break;
    case GLFW_KEY_W: q.move.z += 1; break;
    case GLFW_KEY_S: q.move.z -= 1; break;
    case GLFW_KEY_D: q.move.x += 1; break;
    case GLFW_KEY_A: q.move.x -= 1; break;
    case GLFW_KEY_E: q.move.y += 1; break;
    case GLFW_KEY_Q: q.move.y -= 1; break;
    case GLFW_KEY_LEFT: q.turn.x -= 5; break;
    case GLFW_KEY_RIGHT: q.turn.x += 5; break;
    case GLFW_KEY_UP: q.turn.y -= 5; break;
    case GLFW_KEY_DOWN: q.turn.y += 5; break;
    default:
      if (key >= GLFW_KEY_1 && key < GLFW_KEY_1 + int(option_words::kIntegrators.size())) q.integrator = key - GLFW_KEY_1;
  }
}

void on_mouse_button(GLFWwindow* w, int button, int action, int) {
  auto& q = *static_cast<Requests*>(glfwGetWindowUserPointer(w));
  if (button != GLFW_MOUSE_BUTTON_LEFT) return;
  q.dragging = action == GLFW_PRESS;
  glfwGetCursorPos(w, &q.drag_x, &q.drag_y);
}

void on_cursor(GLFWwindow* w, double x, double y) {
  auto& q = *static_cast<Requests*>(glfwGetWindowUserPointer(w));
  if (!q.dragging) return;
  q.turn += glm::vec2(float(x - q.drag_x), float(y - q.drag_y)) * 0.25f;  // a quarter degree a pixel
  q.drag_x = x;
  q.drag_y = y;
}

// sRGB-encoded 8-bit rows, bottom row first (OpenGL's order), through a
// table of the encoding at 4096 steps: a pow per value cost the render a
// few percent of a core at two snapshots a second.
void tonemap(const Image& im, float exposure, std::vector<uint8_t>& out) {
  static const std::vector<uint8_t> table = [] {
    std::vector<uint8_t> t(4097);
    for (size_t i = 0; i < t.size(); ++i) {
      const double v = double(i) / 4096.0;
      t[i] = uint8_t(255.0 * (v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055) + 0.5);
    }
    return t;
  }();
  out.resize(size_t(im.width) * im.height * 3);
  const float scale = exposure * 4096.f;
  for (int y = 0; y < im.height; ++y) {
    const float* src = im.at(0, y);
    uint8_t* dst = &out[size_t(im.height - 1 - y) * im.width * 3];
    for (int i = 0; i < im.width * 3; ++i) {
      const float v = src[i] * scale;  // NaN fails both tests: 0
      dst[i] = table[v > 0.f ? (v < 4096.f ? size_t(v + 0.5f) : 4096) : 0];
    }
  }
}

class Viewer {
 public:
  Viewer(const ViewArgs& a, const Provenance& p)
      : args_(a), provenance_(p), request_(a.req), kept_request_(a.req), exposure_(a.exposure) {
    load();
  }
  ~Viewer() { stop(); }

  const Scene& scene() const { return *scene_; }
  // The image's size: the session's, or before the first one, the one it will have.
  int width() const { return session_ ? session_->width() : image_region(*scene_, resolve_render_options(*scene_, request_)).width; }
  int height() const { return session_ ? session_->height() : image_region(*scene_, resolve_render_options(*scene_, request_)).height; }
  float exposure() const { return exposure_; }

  // (Re)starts the render with the current request and camera.
  void restart() {
    stop();
    const Mat4 base = base_camera_;
    scene_->camera.world_from_camera = base * camera_delta_;
    options_ = resolve_render_options(*scene_, request_);
    options_.checkpoint_key.clear();
    RenderHooks hooks;
    hooks.pass_done = [this](uint32_t spp) {
      std::lock_guard<std::mutex> lock(passes_mutex_);
      passes_.push_back(spp);
    };
    {
      std::lock_guard<std::mutex> lock(passes_mutex_);  // (before the new session can report one)
      passes_.clear();
    }
    result_.reset();
    failed_ = false;
    session_ = std::make_unique<RenderSession>(*scene_, options_, hooks);
    session_->start();
    say(std::string("started ") + name(options_.integrator) + " " +
        (options_.time_limit_seconds > 0 ? std::to_string(options_.time_limit_seconds) + " s"
                                         : std::to_string(options_.spp) + " spp"));
  }

  // The image to show, and whether it changed since the last call.
  bool poll(Image& image) {
    bool changed = false;
    {
      // Every pass, even when several ended since the last look.
      std::lock_guard<std::mutex> lock(passes_mutex_);
      for (uint32_t spp : passes_) say("pass " + std::to_string(spp) + " spp");
      changed = !passes_.empty();
      passes_.clear();
    }
    if (failed_) return false;
    if (!result_ && session_->wait_for(0.0)) {
      try {
        result_ = session_->wait();
      } catch (const std::exception& e) {
        say(std::string("render failed: ") + e.what());  // the window stays; another key may start a render that works
        failed_ = true;
        return false;
      }
      const RenderStats& s = result_->stats;
      char buf[160];
      std::snprintf(buf, sizeof buf, "done %u spp %.3f s %.3f Msamples/s", s.min_spp, s.seconds,
                    s.seconds > 0 ? double(s.samples) / s.seconds * 1e-6 : 0.0);
      say(buf);
      image = result_->image;
      return true;
    }
    if (result_) return false;
    if (changed || seconds_since(last_snapshot_) > 1.0) {
      last_snapshot_ = Clock::now();
      image = session_->snapshot();
      return !image.rgb.empty();
    }
    return false;
  }

  std::string title() const {
    const RenderProgress p = session_->progress();
    const double pixels = double(width()) * height();
    const double spp = result_ ? double(result_->stats.samples) / pixels : double(p.samples_done) / pixels;
    const double rate = result_ ? double(result_->stats.samples) / std::max(result_->stats.seconds, 1e-9)
                                : double(p.samples_done) / std::max(p.elapsed_seconds, 1e-9);
    char buf[256];
    std::snprintf(buf, sizeof buf, "lantern: %s  %s  %.1f spp%s  %.2f Msamples/s  exposure %g",
                  std::filesystem::path(args_.scene).filename().c_str(), name(options_.integrator), spp,
                  result_ ? " (done)" : "", rate * 1e-6, exposure_);
    return buf;
  }

  void handle(Requests& q) {
    if (q.exposure_scale != 1.f) {
      exposure_ *= q.exposure_scale;
      q.exposure_scale = 1.f;
      say("exposure " + std::to_string(exposure_));
    }
    if (q.screenshot) {
      q.screenshot = false;
      screenshot();
    }
    bool restart_now = false;
    if (q.reload) {
      q.reload = false;
      try {
        load();
        say("reloaded " + args_.scene);
        restart_now = true;
      } catch (const std::exception& e) {
        say(std::string("reload failed: ") + e.what());  // the scene shown stays
      }
    }
    if (q.integrator >= 0) {
      request_.integrator = option_words::kIntegrators[size_t(q.integrator)].word;
      q.integrator = -1;
      restart_now = true;
    }
    if (q.spp_scale != 0) {
      request_.spp = std::clamp(int(std::ldexp(double(options_.spp), q.spp_scale)), 1, 1 << 20);
      request_.time = 0.0;
      q.spp_scale = 0;
      restart_now = true;
    }
    if (q.move != glm::vec3(0.f) || q.turn != glm::vec2(0.f)) {
      move_camera(q.move, q.turn);
      q.move = glm::vec3(0.f);
      q.turn = glm::vec2(0.f);
      restart_now = true;
    }
    if (restart_now) restart_or_keep();
  }

  // A combination the renderer refuses (guiding with bdpt, ...) is said and
  // undone: the previous settings render again.
  void restart_or_keep() {
    try {
      restart();
      kept_request_ = request_;
    } catch (const std::exception& e) {
      say(std::string("refused: ") + e.what());
      request_ = kept_request_;
      restart();
    }
  }

 private:
  void load() {
    LoadOptions lo;
    lo.texture_cache_mb = args_.texture_cache_mb;
    lo.texture_directory = args_.texture_dir;
    lo.lenient = args_.lenient;
    lo.warn = [](const std::string& w) { std::fprintf(stderr, "%s\n", w.c_str()); };
    std::shared_ptr<Scene> s = load_scene(args_.scene, lo);
    stop();  // the old scene outlives its session
    scene_ = std::move(s);
    base_camera_ = scene_->camera.world_from_camera;
    if (scene_->camera.motion) {
      scene_->camera.motion = nullptr;  // the viewer's camera stands still at the shutter's opening
      say("the camera moves during the shutter: shown still, at its opening position");
    }
  }

  void stop() {
    if (session_) session_->cancel();
    session_.reset();  // joins
  }

  // Steps of 2% of the scene's diagonal, turns about the camera's own axes.
  void move_camera(glm::vec3 steps, glm::vec2 degrees) {
    const float step = 0.02f * glm::length(scene_->bounds_hi - scene_->bounds_lo);
    camera_delta_ = glm::translate(camera_delta_, steps * step);
    camera_delta_ = glm::rotate(camera_delta_, glm::radians(degrees.x), glm::vec3(0, 1, 0));
    camera_delta_ = glm::rotate(camera_delta_, glm::radians(degrees.y), glm::vec3(1, 0, 0));
  }

  void screenshot() {
    Image im = result_ ? result_->image : session_->snapshot();
    if (im.rgb.empty()) return say("screenshot: nothing rendered yet");
    RenderResult r;
    const RenderProgress p = session_->progress();
    r.stats = result_ ? result_->stats : RenderStats{};
    if (!result_) {
      r.stats.samples = p.samples_done;
      r.stats.min_spp = uint32_t(p.samples_done / uint64_t(std::max(1, width() * height())));
      r.interrupted = true;  // a render still running
    }
    r.total_render_seconds = result_ ? result_->stats.seconds : p.elapsed_seconds;
    const ImageMetadata md = render_metadata(*scene_, args_.scene, options_, r, provenance_);
    std::string prefix = args_.screenshot;
    if (prefix.empty()) prefix = std::filesystem::path(scene_->settings.output).replace_extension().string() + "-view";
    const std::string base = prefix + "-" + std::to_string(++shots_);
    try {
      write_image(base + ".exr", im, md);
      for (float& v : im.rgb) v *= exposure_;  // the PNG as shown
      write_image(base + ".png", im, md);
      say("screenshot " + base + ".exr " + base + ".png");
    } catch (const std::exception& e) {
      say(std::string("screenshot failed: ") + e.what());
    }
  }

  ViewArgs args_;
  Provenance provenance_;
  RenderRequest request_, kept_request_;  // asked for; the last that rendered
  bool failed_ = false;                   // the render threw: said, nothing more to show
  float exposure_;
  std::shared_ptr<Scene> scene_;
  Mat4 base_camera_{1.f}, camera_delta_{1.f};  // the file's camera, and the user's moves in its space
  RenderOptions options_;
  std::unique_ptr<RenderSession> session_;
  std::optional<RenderResult> result_;
  std::mutex passes_mutex_;
  std::vector<uint32_t> passes_;  // ended since the window last looked (from the film's merging thread)
  Clock::time_point last_snapshot_;
  int shots_ = 0;
};

// pixels: w x h, or anything else (an image of another size, after a reload
// changed the resolution), which is not drawn.
void draw(GLFWwindow* window, int w, int h, const std::vector<uint8_t>& pixels) {
  int fw = 0, fh = 0;
  glfwGetFramebufferSize(window, &fw, &fh);
  glViewport(0, 0, fw, fh);
  glClearColor(0.f, 0.f, 0.f, 1.f);
  glClear(GL_COLOR_BUFFER_BIT);
  if (pixels.size() == size_t(w) * size_t(h) * 3) {
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glRasterPos2f(-1.f, -1.f);
    glPixelZoom(float(fw) / float(w), float(fh) / float(h));
    glDrawPixels(w, h, GL_RGB, GL_UNSIGNED_BYTE, pixels.data());
  }
  glfwSwapBuffers(window);
}

}  // namespace

int run_view(const ViewArgs& args, const Provenance& provenance) {
  glfwSetErrorCallback([](int, const char* what) { std::fprintf(stderr, "window: %s\n", what); });
  if (!glfwInit()) {
    std::fprintf(stderr, "error: no display to open a window on (is DISPLAY set?); `lantern render` renders without one\n");
    return 1;
  }
  struct Terminate {
    ~Terminate() { glfwTerminate(); }
  } terminate;
  Viewer viewer(args, provenance);
  // The window at the image's size, scaled down to fit a 1600x1000 screen.
  const double fit = std::min({1.0, 1600.0 / viewer.width(), 1000.0 / viewer.height()});
  GLFWwindow* window = glfwCreateWindow(std::max(1, int(viewer.width() * fit)), std::max(1, int(viewer.height() * fit)),
                                        "lantern", nullptr, nullptr);
  if (!window) {
    std::fprintf(stderr, "error: the window could not be opened (no OpenGL on this display?)\n");
    return 1;
  }
  Requests requests;
  glfwSetWindowUserPointer(window, &requests);
  glfwSetKeyCallback(window, on_key);
  glfwSetMouseButtonCallback(window, on_mouse_button);
  glfwSetCursorPosCallback(window, on_cursor);
  glfwMakeContextCurrent(window);
  glfwSwapInterval(0);
  // One frame before the render starts: the OpenGL driver's set-up (a
  // software one compiles its shaders on first use) does not take time
  // from the render.
  draw(window, 1, 1, std::vector<uint8_t>(3, 0));
  say("window " + std::to_string(viewer.width()) + "x" + std::to_string(viewer.height()));
  viewer.restart();
  Image image;
  std::vector<uint8_t> pixels;
  float shown_exposure = viewer.exposure();
  int shown_fw = 0, shown_fh = 0;
  auto last_title = Clock::now() - std::chrono::seconds(1);
  while (!glfwWindowShouldClose(window)) {
    // The render runs on its own threads; this thread wakes for input or
    // every 50 ms to look for a new pass.
    glfwWaitEventsTimeout(0.25);
    viewer.handle(requests);
    const bool fresh = viewer.poll(image);
    int fw = 0, fh = 0;
    glfwGetFramebufferSize(window, &fw, &fh);
    if (fresh || viewer.exposure() != shown_exposure || fw != shown_fw || fh != shown_fh) {
      shown_fw = fw;
      shown_fh = fh;
      shown_exposure = viewer.exposure();
      if (!image.rgb.empty() && image.width == viewer.width() && image.height == viewer.height())
        tonemap(image, shown_exposure, pixels);
      draw(window, viewer.width(), viewer.height(), pixels);
    }
    if (seconds_since(last_title) > 0.5) {
      last_title = Clock::now();
      glfwSetWindowTitle(window, viewer.title().c_str());
    }
  }
  glfwDestroyWindow(window);
  say("closed");
  return 0;
}

}  // namespace lantern
