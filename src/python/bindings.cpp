// The compiled part of the Python module `lantern` (python/lantern/ is the
// package around it; docs/python.md is its manual).
#include "python/bindings.h"

#include <pybind11/eval.h>

#include "lantern/error.h"

namespace lantern::python {

PYBIND11_MODULE(_lantern, m) {
  m.doc() = "Lantern: physically based rendering with bidirectional path tracing";
  // A scene that cannot be loaded: the message names file, line and column.
  py::register_exception<InputError>(m, "SceneError", PyExc_ValueError);
  py::exec("class SceneWarning(UserWarning):\n    \"\"\"A scene loader's warning (file:line:col: warning: ...)\"\"\"\n",
           m.attr("__dict__"));
  bind_scene(m);
  bind_images(m);
  bind_render(m);
}

}  // namespace lantern::python
