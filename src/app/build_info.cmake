# Writes OUT, the build's identity for `lantern --version` and provenance
# (src/app/provenance.h), at every build, touching it only when it changes:
# the commit (with "-modified" when tracked files differ from it; "unknown"
# outside a git checkout), and what the configure step knew.
# cmake -DSOURCE_DIR=... -DOUT=... -DVERSION=... -DBUILD_TYPE=... -DCOMPILER=... -P build_info.cmake
set(commit "unknown")
find_package(Git QUIET)
if(GIT_FOUND)
  execute_process(COMMAND ${GIT_EXECUTABLE} -C ${SOURCE_DIR} rev-parse --short=12 HEAD
                  OUTPUT_VARIABLE head RESULT_VARIABLE failed OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
  if(NOT failed AND head)
    set(commit ${head})
    execute_process(COMMAND ${GIT_EXECUTABLE} -C ${SOURCE_DIR} status --porcelain --untracked-files=no
                    OUTPUT_VARIABLE changes OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
    if(changes)
      set(commit "${commit}-modified")
    endif()
  endif()
endif()
set(text "// Written by src/app/build_info.cmake at build time.
#include \"app/provenance.h\"
namespace lantern {
const BuildInfo kBuildInfo{\"${VERSION}\", \"${commit}\", \"${BUILD_TYPE}\", \"${COMPILER}\"};
}  // namespace lantern
")
if(EXISTS ${OUT})
  file(READ ${OUT} old)
endif()
if(NOT old STREQUAL text)
  file(WRITE ${OUT} "${text}")
endif()
