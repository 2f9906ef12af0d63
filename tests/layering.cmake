# The folders of src/ in layers (src/layers.cmake), bottom first: a file may include headers of
# its own folder and of folders in lower layers only, so the folders depend
# downwards and a circle cannot form (docs/architecture.md, "Layers").
# Folders in one layer do not include each other.
#
#   cmake -DSRC=<repository>/src -P tests/layering.cmake
#
# fails, naming each file, line and header, on any other include.
include(${CMAKE_CURRENT_LIST_DIR}/../src/layers.cmake)
# Known exceptions, each "folder>included/header.h" (none today).
set(EXCEPTIONS "")

cmake_minimum_required(VERSION 3.20)

if(NOT SRC)
  message(FATAL_ERROR "usage: cmake -DSRC=<repository>/src -P layering.cmake")
endif()

foreach(layer IN LISTS LANTERN_LAYERS)
  string(REPLACE "|" ";" folders "${layer}")
  foreach(f IN LISTS folders)
    set(LEVEL_${f} ${LANTERN_LEVEL_${f}})
  endforeach()
endforeach()

file(GLOB children RELATIVE "${SRC}" "${SRC}/*")
foreach(child IN LISTS children)
  if(IS_DIRECTORY "${SRC}/${child}" AND NOT DEFINED LEVEL_${child})
    message(SEND_ERROR "src/${child}/ is in no layer: add it to src/layers.cmake")
  endif()
endforeach()

set(violations 0)
file(GLOB_RECURSE files RELATIVE "${SRC}" "${SRC}/*.h" "${SRC}/*.cpp")
foreach(file IN LISTS files)
  string(REGEX MATCH "^[^/]+" folder "${file}")
  if(NOT DEFINED LEVEL_${folder})
    continue()
  endif()
  # (any spacing, quotes or angle brackets: "#  include <light/x.h>" counts)
  file(STRINGS "${SRC}/${file}" lines REGEX "^[ \t]*#[ \t]*include[ \t]*[<\"][a-z_0-9]+/")
  foreach(line IN LISTS lines)
    string(REGEX REPLACE "^[ \t]*#[ \t]*include[ \t]*[<\"]([^\">]+)[\">].*" "\\1" header "${line}")
    string(REGEX MATCH "^[^/]+" target "${header}")
    if(target STREQUAL folder OR NOT DEFINED LEVEL_${target})
      continue()  # its own folder, or the public include/lantern/ headers
    endif()
    if(LEVEL_${target} LESS LEVEL_${folder})
      continue()
    endif()
    if("${folder}>${header}" IN_LIST EXCEPTIONS)
      continue()
    endif()
    message(SEND_ERROR "src/${file}: includes \"${header}\": ${target}/ is not below ${folder}/ "
                       "(layer ${LEVEL_${target}} against ${LEVEL_${folder}})")
    math(EXPR violations "${violations} + 1")
  endforeach()
endforeach()
if(violations GREATER 0)
  message(FATAL_ERROR "${violations} include(s) against the layers")
endif()
message(STATUS "layers hold: ${level} layers, every include points downwards")
