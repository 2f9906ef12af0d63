// Scenes from Python: loaded from a file or from text (python/lantern/
// builder.py writes the text of a scene built in Python), with their
// settings and figures as dicts.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <charconv>
#include <chrono>
#include <mutex>
#include <tuple>
#include <utility>
#include <vector>

#include "app/render_request.h"
#include "python/bindings.h"

namespace lantern::python {

namespace {

// Warnings arrive while the GIL is released (loading may take minutes and
// read PLY files on several threads): kept here, then given to Python.
struct WarningBuffer {
  std::mutex mutex;
  std::vector<std::string> lines;
  WarningSink sink() {
    return [this](const std::string& w) {
      std::lock_guard<std::mutex> lock(mutex);
      lines.push_back(w);
    };
  }
};

// Each warning goes to `on_warning` when given, else to Python's warnings
// module (lantern.SceneWarning), and into the scene's `warnings` list.
void deliver(PyScene& s, const WarningBuffer& buffer, const py::object& on_warning) {
  py::object warn = py::module_::import("warnings").attr("warn");
  py::object category = py::module_::import("lantern._lantern").attr("SceneWarning");
  for (const std::string& w : buffer.lines) {
    s.warnings.append(w);
    if (!on_warning.is_none()) on_warning(w);
    else warn(w, category, 2);
  }
}

// Loads with the GIL released (loading may take minutes), timing it, then
// hands the warnings to Python. load(lo) returns the scene and the key its
// checkpoints must carry.
template <class Load>
std::shared_ptr<PyScene> load_with(double texture_cache_mb, const std::string& texture_dir,
                                   const py::object& on_warning, LoadOptions lo, Load load) {
  WarningBuffer buffer;
  if (!(texture_cache_mb >= 1.0)) throw std::invalid_argument("texture_cache_mb: expected 1 or more megabytes");
  lo.texture_cache_mb = texture_cache_mb;
  lo.texture_directory = texture_dir;
  lo.warn = buffer.sink();
  auto s = std::make_shared<PyScene>();
  {
    py::gil_scoped_release release;
    const auto t0 = std::chrono::steady_clock::now();
    std::tie(s->scene, s->key) = load(lo);
    s->load_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  deliver(*s, buffer, on_warning);
  return s;
}

std::shared_ptr<PyScene> load(const std::string& path, double texture_cache_mb, const std::string& texture_dir,
                              const py::object& on_warning, bool lenient, const std::string& memory_layout) {
  LoadOptions options;
  options.lenient = lenient;
  options.memory_layout = parse_memory_layout(memory_layout);
  auto s = load_with(texture_cache_mb, texture_dir, on_warning, options, [&](const LoadOptions& lo) {
    std::shared_ptr<Scene> scene = load_scene(path, lo);
    return std::pair(scene, scene_key(path, scene_info(*scene)));
  });
  s->path = path;
  return s;
}

std::shared_ptr<PyScene> load_text(const std::string& text, const std::string& name, const std::string& base_dir,
                                   double texture_cache_mb, const std::string& texture_dir,
                                   const py::object& on_warning, bool lenient, const std::string& memory_layout) {
  LoadOptions lo;
  lo.base_directory = base_dir;  // as a scene file's folder
  lo.lenient = lenient;
  lo.memory_layout = parse_memory_layout(memory_layout);
  return load_with(texture_cache_mb, texture_dir, on_warning, lo, [&](const LoadOptions& o) {
    std::shared_ptr<Scene> scene = load_scene_from_string(text, name, o);
    return std::pair(scene, scene_key_of_text(name, text, scene_info(*scene)));
  });
}

py::dict settings_dict(const PyScene& s) {
  const SceneSettings& ss = scene_settings(*s.scene);
  py::dict d;
  d["integrator"] = name(ss.integrator);
  d["spp"] = ss.spp;
  d["maxdepth"] = ss.maxdepth;
  d["resolution"] = py::make_tuple(ss.width, ss.height);
  d["output"] = ss.output;
  d["sampler"] = name(ss.sampler.type);
  d["light_sampler"] = name(ss.light_sampler);
  d["color_space"] = ss.color_space;
  d["dispersive"] = ss.dispersive;
  d["iso"] = ss.iso;
  d["whitebalance"] = ss.whitebalance;
  d["exposure_time"] = ss.exposure_time;
  d["max_component_value"] = ss.max_component_value;
  d["crop_window"] = py::make_tuple(ss.crop_window[0], ss.crop_window[1], ss.crop_window[2], ss.crop_window[3]);
  return d;
}

py::dict info_dict(const PyScene& s) {
  const SceneInfo i = scene_info(*s.scene);
  py::dict d;
  d["triangles"] = i.triangles;
  d["spheres"] = i.spheres;
  d["lights"] = i.lights;
  d["instances"] = i.instances;
  d["instanced_triangles"] = i.instanced_triangles;
  d["bvh_build_seconds"] = i.bvh_build_seconds;
  d["bvh_bytes"] = i.bvh_bytes;
  d["geometry_bytes"] = i.geometry_bytes;
  d["load_seconds"] = s.load_seconds;
  return d;
}

// Numbers as pbrt text, each as the shortest decimal that reads back to the
// same double (std::to_chars), so a scene built in Python and written as
// text loses nothing. Integer arrays are written as integers.
std::string format_numbers(const py::handle& values) {
  py::array a = py::array::ensure(values);
  if (!a) throw py::type_error("format_numbers: expected numbers or an array of them");
  const char kind = a.dtype().kind();
  const bool integral = kind == 'i' || kind == 'u' || kind == 'b';
  std::string out;
  char buf[32];
  if (integral) {
    auto v = py::array_t<int64_t, py::array::c_style | py::array::forcecast>::ensure(a);
    const int64_t* p = v.data();
    out.reserve(size_t(v.size()) * 8);
    for (py::ssize_t i = 0; i < v.size(); ++i) {
      auto r = std::to_chars(buf, buf + sizeof buf, p[i]);
      if (i) out += ' ';
      out.append(buf, r.ptr);
    }
    return out;
  }
  auto v = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
  if (!v) throw py::type_error("format_numbers: expected real numbers");
  const double* p = v.data();
  out.reserve(size_t(v.size()) * 12);
  for (py::ssize_t i = 0; i < v.size(); ++i) {
    if (!std::isfinite(p[i])) throw py::value_error("format_numbers: a value is not finite (NaN or infinity)");
    auto r = std::to_chars(buf, buf + sizeof buf, p[i]);
    if (i) out += ' ';
    out.append(buf, r.ptr);
  }
  return out;
}

}  // namespace

void bind_scene(py::module_& m) {
  py::class_<PyScene, std::shared_ptr<PyScene>>(m, "Scene", "A loaded scene; render it with lantern.render.")
      .def_property_readonly("path", [](const PyScene& s) { return s.path; }, "The scene file (empty for text)")
      .def_property_readonly("settings", &settings_dict,
                             "What the scene file asks for: integrator, spp, maxdepth, resolution, output, sampler, ...")
      .def_property_readonly("info", &info_dict, "What loading made: triangles, lights, instances, BVH, load time")
      .def_property_readonly("warnings", [](const PyScene& s) { return s.warnings; }, "The loader's warnings")
      .def("__repr__", [](const PyScene& s) {
        const SceneInfo i = scene_info(*s.scene);
        return "<lantern.Scene " + (s.path.empty() ? std::string("(text)") : s.path) + ": " +
               std::to_string(i.triangles) + " triangles, " + std::to_string(i.lights) + " lights>";
      });
  m.def("load_scene", &load, py::arg("path"), py::kw_only(), py::arg("texture_cache_mb") = 1024.0,
        py::arg("texture_dir") = "", py::arg("on_warning") = py::none(), py::arg("lenient") = false,
        py::arg("memory_layout") = "auto",
        "Load a pbrt-v4 scene file (pbrt-v3 names too). Errors raise lantern.SceneError naming file, line and "
        "column (a parameter neither pbrt-v4 nor pbrt-v3 reads is one, unless lenient); warnings go to "
        "on_warning(line), else to Python's warnings as lantern.SceneWarning. memory_layout: 'auto', 'fast' or "
        "'compact', as the command line's --memory-layout.");
  m.def("load_scene_from_string", &load_text, py::arg("text"), py::kw_only(), py::arg("name") = "<string>",
        py::arg("base_dir") = "", py::arg("texture_cache_mb") = 1024.0, py::arg("texture_dir") = "",
        py::arg("on_warning") = py::none(), py::arg("lenient") = false, py::arg("memory_layout") = "auto",
        "Load a scene from pbrt-v4 text; relative file names resolve against base_dir (default: the working "
        "directory); messages name the text `name`.");
  m.def("format_numbers", &format_numbers, py::arg("values"),
        "Numbers as pbrt text, separated by spaces, each read back exactly (the scene builder's writer).");
}

}  // namespace lantern::python
