// The pieces of the Python module, one file each: scenes (loading, their
// settings), images (NumPy arrays in and out, comparisons) and renders
// (options as keyword arguments, sessions, results).
#pragma once

#include <pybind11/pybind11.h>

#include <memory>
#include <string>

#include "lantern/image.h"
#include "lantern/scene.h"

namespace lantern::python {

namespace py = pybind11;

// A loaded scene as Python holds it: renders keep it alive.
struct PyScene {
  std::shared_ptr<Scene> scene;
  std::string path;  // the file, or "" for a scene given as text
  std::string key;   // what checkpoints of it must agree with (app/render_request.h)
  double load_seconds = 0.0;
  py::list warnings;
};

// An image as a (height, width, 3) float32 array that owns it: no copy.
py::object to_array(Image&& image);
// An array of shape (height, width, 3) (any real type, any strides) as an
// Image. Throws ValueError for any other shape.
Image from_array(const py::handle& array);
// A JSON value as the Python value json.loads makes of it.
py::object from_json_text(const std::string& text);

void bind_scene(py::module_& m);
void bind_images(py::module_& m);
void bind_render(py::module_& m);

}  // namespace lantern::python
