# The folders of src/ in layers, bottom first (docs/architecture.md). A
# folder depends on folders of lower layers only, and folders of one layer
# do not depend on each other, so the dependencies cannot form a circle.
# src/CMakeLists.txt builds one library per folder from this table and
# tests/layering.cmake checks every include against it.
set(LANTERN_LAYERS
    "math"
    "color|sampler|camera|geometry|trace|guiding"
    "texture"
    "imageio|medium"
    "material"
    "film|entity"
    "light"
    "accel"
    "scene"
    "integrator"
    "distributed"
    "app"
    "python")

# LANTERN_LEVEL_<folder>: the layer of each folder.
set(_level 0)
foreach(_layer IN LISTS LANTERN_LAYERS)
  string(REPLACE "|" ";" _folders "${_layer}")
  foreach(_f IN LISTS _folders)
    set(LANTERN_LEVEL_${_f} ${_level})
  endforeach()
  math(EXPR _level "${_level} + 1")
endforeach()
