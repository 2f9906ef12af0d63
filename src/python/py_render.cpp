// Renders from Python. The keyword arguments are the command line's options
// (app/render_request.h: one word, one meaning), and a render is the same
// RenderSession the command line runs. Python waits for it in slices with
// the GIL released, so that its threads run, Ctrl-C is seen within a tenth
// of a second, and a progress callback runs on Python's own thread.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>

#include "app/outputs.h"
#include "app/provenance.h"
#include "app/render_request.h"
#include "app/stats_report.h"
#include "imageio/replace_file.h"
#include "python/bindings.h"

namespace lantern::python {

namespace {

// What a render writes and keeps besides its options.
struct Outputs {
  std::string image;       // output=: the image file ("" none)
  std::string stats;       // stats=: the --stats JSON file ("" none)
  std::string checkpoint;  // checkpoint_file=
  double checkpoint_seconds = 0.0;
  bool resume = false, keep_checkpoint = false;
  bool collect_stats = false;
};

template <class T>
T cast_option(const char* name, const py::handle& v) {
  try {
    return v.cast<T>();
  } catch (const py::cast_error&) {
    throw py::type_error(std::string(name) + "=" + py::repr(v).cast<std::string>() + ": expected " +
                         py::type_id<T>());
  }
}

// "auto" or a number (an integer unless `floats`), as the text the command
// line reads (Python's own repr of a number: every digit kept), checked by
// `parse`; anything else is refused with what `expected` says.
template <class Parse>
std::string auto_or_number(const char* name, const py::handle& v, bool floats, const char* expected, Parse&& parse) {
  const bool number =
      (py::isinstance<py::int_>(v) || (floats && py::isinstance<py::float_>(v))) && !py::isinstance<py::bool_>(v);
  const std::string refusal = std::string(name) + ": expected " + expected;
  if (!number && !py::isinstance<py::str>(v)) throw py::value_error(refusal);
  std::string text = py::str(v);
  try {
    parse(text);
  } catch (const std::invalid_argument&) {
    throw py::value_error(refusal);
  }
  return text;
}

// The keyword arguments of render() and RenderSession(), checked as the
// command line checks its options.
void read_options(const py::kwargs& kw, RenderRequest& r, Outputs& out) {
  for (auto [key, value] : kw) {
    const std::string k = key.cast<std::string>();
    auto positive = [&](double v, const char* what) {
      if (!(v > 0)) throw py::value_error(k + "=" + py::repr(value).cast<std::string>() + ": expected " + what);
      return v;
    };
    if (value.is_none()) continue;  // the default
    if (k == "integrator") r.integrator = cast_option<std::string>("integrator", value);
    else if (k == "sampler") r.sampler = cast_option<std::string>("sampler", value);
    else if (k == "light_sampler") r.light_sampler = cast_option<std::string>("light_sampler", value);
    else if (k == "light_choice")
      r.light_choice = cast_option<std::string>("light_choice", value);
    else if (k == "mis") r.mis = cast_option<std::string>("mis", value);
    else if (k == "rays") r.rays = cast_option<std::string>("rays", value);
    else if (k == "spp") r.spp = int(positive(cast_option<int>("spp", value), "a positive integer"));
    else if (k == "time") r.time = positive(cast_option<double>("time", value), "a positive number of seconds");
    else if (k == "target_error") r.target_error = positive(cast_option<double>("target_error", value), "a positive number");
    else if (k == "maxdepth") {
      r.maxdepth = cast_option<int>("maxdepth", value);
      if (r.maxdepth < 0) throw py::value_error("maxdepth: expected an integer of 0 or more");
    } else if (k == "threads") r.threads = int(positive(cast_option<int>("threads", value), "a positive integer"));
    else if (k == "wave_size") {
      r.wave_size = cast_option<int>("wave_size", value);
      if (r.wave_size < 1 || r.wave_size > (1 << 22)) throw py::value_error("wave_size: expected 1 to 4194304");
    } else if (k == "seed") {
      const long long s = cast_option<long long>("seed", value);
      if (s < 0) throw py::value_error("seed: expected an integer of 0 or more");
      r.seed = uint64_t(s);
    } else if (k == "vcm_radius") r.vcm_radius = float(positive(cast_option<double>("vcm_radius", value), "a positive number"));
    else if (k == "vcm_alpha") {
      r.vcm_alpha = cast_option<float>("vcm_alpha", value);
      if (!(r.vcm_alpha >= 0.01f && r.vcm_alpha <= 1.f)) throw py::value_error("vcm_alpha: expected 0.01 to 1");
    } else if (k == "roulette") {
      r.roulette = cast_option<float>("roulette", value);
      if (!(r.roulette >= 0.01f && r.roulette <= 100.f)) throw py::value_error("roulette: expected 0.01 to 100");
    } else if (k == "split") {
      r.split = auto_or_number("split", value, false, "\"auto\", 1, 2, 4, 8 or 16", parse_split);
    } else if (k == "light_subpaths") {
      r.light_subpaths =
          auto_or_number("light_subpaths", value, true, "\"auto\", 0 or a number from 0.01 to 1", parse_light_subpaths);
    } else if (k == "merging") {
      r.merging = cast_option<std::string>("merging", value);
      if (r.merging != "auto" && r.merging != "on") throw py::value_error("merging: expected \"auto\" or \"on\"");
    } else if (k == "spectral")
      r.spectral = cast_option<bool>("spectral", value);
    else if (k == "guide") r.guide = cast_option<bool>("guide", value);
    else if (k == "guide_light") r.guide_light = cast_option<bool>("guide_light", value);
    else if (k == "guide_distribution")
      r.guide_distribution = cast_option<std::string>("guide_distribution", value);
    else if (k == "guide_stop") {
      r.guide_stop = cast_option<std::string>("guide_stop", value);
      if (r.guide_stop != "auto" && r.guide_stop != "never")
        throw py::value_error("guide_stop: expected \"auto\" or \"never\"");
    } else if (k == "adaptive")
      r.adaptive = cast_option<bool>("adaptive", value);
    else if (k == "resolution") r.resolution = cast_option<std::vector<int>>("resolution", value);
    else if (k == "cropwindow") r.crop_window = cast_option<std::vector<float>>("cropwindow", value);
    else if (k == "pixelbounds") r.pixel_bounds = cast_option<std::vector<int>>("pixelbounds", value);
    else if (k == "pixel") r.pixel = cast_option<std::vector<int>>("pixel", value);
    else if (k == "output") out.image = cast_option<std::string>("output", value);
    else if (k == "stats") out.stats = cast_option<std::string>("stats", value);
    else if (k == "collect_stats") out.collect_stats = cast_option<bool>("collect_stats", value);
    else if (k == "checkpoint") out.checkpoint_seconds = positive(cast_option<double>("checkpoint", value), "seconds");
    else if (k == "checkpoint_file") out.checkpoint = cast_option<std::string>("checkpoint_file", value);
    else if (k == "resume") out.resume = cast_option<bool>("resume", value);
    else if (k == "keep_checkpoint") out.keep_checkpoint = cast_option<bool>("keep_checkpoint", value);
    else
      throw py::type_error(
          "unknown render option '" + k +
          "'; the options are the command line's: integrator, spp, time, target_error, maxdepth, "
          "seed, sampler, light_sampler, light_choice, resolution, cropwindow, pixelbounds, pixel, spectral, guide, "
          "guide_light, guide_distribution, guide_stop, adaptive, threads, wave_size, rays, mis, vcm_radius, "
          "vcm_alpha, roulette, split, light_subpaths, merging, output, stats, collect_stats, checkpoint, "
          "checkpoint_file, resume, keep_checkpoint");
  }
  if (r.time > 0 && r.spp > 0)
    throw py::value_error("spp and time: give one budget (time renders passes until the time is up), as on the "
                          "command line");
}

Provenance python_provenance() {
  py::list argv = py::module_::import("sys").attr("argv");
  std::vector<std::string> words{"python3"};
  for (const auto& a : argv) words.push_back(py::str(a).cast<std::string>());
  std::vector<char*> ptrs;
  for (std::string& w : words) ptrs.push_back(w.data());
  return provenance(int(ptrs.size()), ptrs.data());
}

struct Progress {
  RenderProgress p;
  double pixels = 1.0;
};

struct PyResult {
  py::object image, stats;
  bool interrupted = false;
  uint64_t samples = 0, resumed_samples = 0;
  uint32_t spp = 0;
  double seconds = 0.0;
  std::string output;  // where the image was written ("" none); a rescue copy's name when that failed
};

class PySession {
 public:
  PySession(std::shared_ptr<PyScene> scene, const py::kwargs& kw) : scene_(std::move(scene)) {
    read_options(kw, request_, out_);
    options_ = resolve_render_options(*scene_->scene, request_);
    options_.collect_stats = out_.collect_stats || !out_.stats.empty();
    options_.checkpoint_key = scene_->key;
    if (out_.checkpoint_seconds > 0 || out_.resume || out_.keep_checkpoint) {
      options_.checkpoint_path = !out_.checkpoint.empty() ? out_.checkpoint
                                 : !out_.image.empty()    ? out_.image + ".ckpt"
                                                          : throw py::value_error("checkpoint or resume: give "
                                                                                  "checkpoint_file or output");
      options_.checkpoint_seconds = out_.checkpoint_seconds;
      options_.resume = out_.resume;
      options_.keep_checkpoint = out_.keep_checkpoint;
    }
    // Every file the render will write, before it starts.
    if (!out_.image.empty()) check_image_path(out_.image);
    if (!out_.stats.empty()) check_writable(out_.stats, "the statistics");
    if (!options_.checkpoint_path.empty()) check_writable(options_.checkpoint_path, "the checkpoint");
    provenance_ = python_provenance();
    session_ = std::make_unique<RenderSession>(*scene_->scene, options_);
    pixels_ = double(session_->width()) * double(session_->height());  // the film's (a crop's) pixels
  }
  ~PySession() {
    if (session_ && started_ && !collected_) {
      py::gil_scoped_release release;  // the render's threads may not need it, but waiting must not hold it
      session_.reset();                // cancels and joins
    }
  }

  void start() {
    if (started_) throw std::logic_error("a render session runs once");
    started_ = true;
    session_->start();
  }
  void cancel() { session_->cancel(); }
  // Leaving a `with` block: the render stopped and its threads ended.
  void close() {
    if (!session_) return;
    session_->cancel();
    if (started_ && !collected_) wait(std::nullopt, py::none());
  }
  bool done() const { return collected_ || (started_ && session_->wait_for(0.0)); }  // (collected_ once it failed)
  Progress progress() const { return {session_->progress(), pixels_}; }
  py::object snapshot() const {
    Image im;
    {
      py::gil_scoped_release release;
      im = session_->snapshot();
    }
    if (im.rgb.empty()) {  // not begun: black
      im.width = session_->width();
      im.height = session_->height();
      im.rgb.assign(size_t(im.width) * size_t(im.height) * 3, 0.f);
    }
    return to_array(std::move(im));
  }
  py::object settings() const { return from_json_text(render_settings_json(options_).dump()); }

  // The result when the render has ended (None after `timeout` seconds).
  // Without a timeout: waits, checking for Ctrl-C (which cancels the
  // render, writes what it has, then raises KeyboardInterrupt) and calling
  // progress(p) (a false value cancels; an exception cancels and is raised).
  py::object wait(std::optional<double> timeout, const py::object& on_progress) {
    if (!started_) throw std::logic_error("wait() needs a started render session (start())");
    if (failure_) std::rethrow_exception(failure_);  // the render failed: every later call says so
    if (collected_) return py::cast(result_);
    const auto t0 = std::chrono::steady_clock::now();
    std::optional<py::error_already_set> raised;
    for (bool ended = false; !ended;) {
      double slice = 0.1;
      if (timeout && !raised) {  // (once cancelled by Ctrl-C or the callback: to the end, then raise)
        const double left = *timeout - std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        if (left <= 0) return py::none();
        slice = std::min(slice, left);
      }
      {
        py::gil_scoped_release release;
        ended = session_->wait_for(slice);
      }
      if (raised) continue;  // cancelled: wait for the waves in flight
      try {
        if (PyErr_CheckSignals() != 0) throw py::error_already_set();
        if (!on_progress.is_none()) {
          // False (or anything false but None) cancels; None, what a
          // callback that only reports returns, goes on.
          const py::object go_on = on_progress(progress());
          if (!go_on.is_none() && PyObject_IsTrue(go_on.ptr()) == 0) session_->cancel();
        }
      } catch (py::error_already_set& e) {
        raised.emplace(std::move(e));
        session_->cancel();
      }
    }
    collect();
    if (!on_progress.is_none() && !raised) on_progress(progress());
    if (raised) throw std::move(*raised);
    return py::cast(result_);
  }

 private:
  void collect() {
    RenderResult r;
    try {
      py::gil_scoped_release release;
      r = session_->wait();
    } catch (...) {
      failure_ = std::current_exception();
      collected_ = true;
      throw;
    }
    collected_ = true;
    result_.interrupted = r.interrupted;
    result_.samples = r.stats.samples;
    result_.resumed_samples = r.resumed_samples;
    result_.spp = r.stats.min_spp;
    result_.seconds = r.stats.seconds;
    const Scene& scene = *scene_->scene;
    RunInfo run{scene_->path, name(options_.integrator), out_.image, name(options_.ray_backend), r.image.width,
                r.image.height, options_.wave_size, scene_->load_seconds, scene_info(scene),
                scene_settings(scene).sampler, options_.sampler, name(scene_settings(scene).light_sampler), {}};
    nlohmann::json j = stats_json(run, r.stats);
    j["colour"] = options_.spectral ? "spectral" : "rgb";
    j["settings"] = render_settings_json(options_);
    j["provenance"] = provenance_json(provenance_);
    // The image first, then the stats; a file that cannot be written is
    // raised after both were tried and the result is complete (wait()
    // raises it; the image itself stays in the result, or its rescue copy).
    std::string failure;
    if (!out_.image.empty()) {
      const ImageMetadata md = render_metadata(scene, scene_->path, options_, r, provenance_);
      const ImageWrite w = write_image_or_rescue(out_.image, r.image, md, options_.checkpoint_path);
      result_.output = w.written ? out_.image : w.rescue;
      if (!w.written)
        failure = w.error + (w.rescue.empty() ? "; no rescue copy could be written either"
                                              : "; the image is saved instead in " + w.rescue);
    }
    result_.stats = from_json_text(j.dump());
    result_.image = to_array(std::move(r.image));
    if (!out_.stats.empty()) {
      const std::string tmp = temporary_output(out_.stats, "");
      std::ofstream f(tmp, std::ios::binary);
      f << j.dump(2) << "\n";
      if (f.flush()) {
        f.close();
        place_output(tmp, out_.stats);
      } else {
        std::remove(tmp.c_str());
        failure += (failure.empty() ? "" : "; ") + std::string("cannot write ") + out_.stats + " (disk full?)";
      }
    }
    if (!failure.empty()) throw std::runtime_error(failure);
  }

  std::shared_ptr<PyScene> scene_;
  RenderRequest request_;
  Outputs out_;
  RenderOptions options_;
  Provenance provenance_;
  std::unique_ptr<RenderSession> session_;
  double pixels_ = 1.0;
  bool started_ = false, collected_ = false;
  std::exception_ptr failure_;  // what the render threw
  PyResult result_;
};

}  // namespace

void bind_render(py::module_& m) {
  py::class_<Progress>(m, "Progress", "How far a render has come")
      .def_property_readonly("fraction", [](const Progress& p) { return p.p.fraction; },
                             "Of the sample budget, or of the time budget")
      .def_property_readonly("elapsed_seconds", [](const Progress& p) { return p.p.elapsed_seconds; })
      .def_property_readonly("samples_done", [](const Progress& p) { return p.p.samples_done; })
      .def_property_readonly("samples_total", [](const Progress& p) { return p.p.samples_total; })
      .def_property_readonly("spp", [](const Progress& p) { return double(p.p.samples_done) / p.pixels; },
                             "Samples per pixel so far, on average")
      .def("__repr__", [](const Progress& p) {
        char buf[128];
        std::snprintf(buf, sizeof buf, "<lantern.Progress %.1f%%, %.2f s, %.1f spp>", 100 * p.p.fraction,
                      p.p.elapsed_seconds, double(p.p.samples_done) / p.pixels);
        return std::string(buf);
      });
  py::class_<PyResult>(m, "RenderResult", "A finished (or interrupted) render")
      .def_readonly("image", &PyResult::image, "The image: a (height, width, 3) float32 array, linear")
      .def_readonly("stats", &PyResult::stats, "The measurements as a dict: what `lantern render --stats` writes")
      .def_readonly("interrupted", &PyResult::interrupted)
      .def_readonly("samples", &PyResult::samples)
      .def_readonly("resumed_samples", &PyResult::resumed_samples)
      .def_readonly("spp", &PyResult::spp, "Samples in the least-sampled pixel")
      .def_readonly("seconds", &PyResult::seconds, "Render time of this run")
      .def_readonly("output", &PyResult::output, "The image file written (\"\" if none was asked for)");
  py::class_<PySession>(m, "RenderSession",
                        "One render of a scene, watched while it runs: start(), snapshot(), progress, cancel(), "
                        "wait(). Options as render()'s.")
      .def(py::init<std::shared_ptr<PyScene>, const py::kwargs&>(), py::arg("scene"))
      .def("start", &PySession::start, "Start rendering on the session's threads")
      .def("cancel", &PySession::cancel, "Stop after the waves in flight")
      .def("snapshot", &PySession::snapshot, "The image so far, as an array")
      .def_property_readonly("progress", &PySession::progress)
      .def_property_readonly("done", &PySession::done)
      .def_property_readonly("settings", &PySession::settings, "Every setting that changes the image")
      .def("wait", &PySession::wait, py::arg("timeout") = py::none(), py::arg("progress") = py::none(),
           "The RenderResult once the render ends (None if timeout seconds pass first)")
      .def("__enter__", [](PySession& s) -> PySession& { return s; })
      .def("__exit__", [](PySession& s, const py::args&) { s.close(); });
  m.def(
      "render",
      [](std::shared_ptr<PyScene> scene, const py::object& progress, const py::kwargs& kw) {
        PySession s(std::move(scene), kw);
        s.start();
        return s.wait(std::nullopt, progress);
      },
      py::arg("scene"), py::kw_only(), py::arg("progress") = py::none(),
      "Render a scene; keyword arguments are the command line's options (integrator, spp, time, target_error, "
      "maxdepth, seed, sampler, light_sampler, light_choice, resolution, cropwindow, pixelbounds, pixel, spectral, "
      "guide, "
      "guide_light, guide_distribution, guide_stop, adaptive, threads, "
      "wave_size, rays, mis, "
      "vcm_radius, vcm_alpha, roulette, split, light_subpaths, checkpoint, checkpoint_file, resume, keep_checkpoint) "
      "and the files to write (output, stats). "
      "progress(p) is called about ten times a second; returning False cancels (None goes on). Ctrl-C cancels, writes "
      "the "
      "image so far to output, and raises KeyboardInterrupt.");
  m.def("version", &version_line, "The build's version line, as `lantern --version` prints it");
}

}  // namespace lantern::python
