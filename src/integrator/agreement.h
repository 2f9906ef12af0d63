// One choice for the processes of one image (RenderHooks::agree): where a
// pilot or a checkpoint decides how the render runs (vcm's merges, bdpt's
// light subpaths, the path tracer's split), MPI's ranks take the choice of
// the rank that reads the checkpoint. A pilot's sums do not depend on the
// process, but whether it fits a time budget does, and only that rank
// knows what the checkpoint was made with.
#pragma once

#include <string>
#include <type_traits>
#include <vector>

#include "lantern/render.h"
#include "math/state_io.h"

namespace lantern {

// The value `hooks` agree on, in place of this process's own. Every
// process must call it at the same points of the render, whatever its own
// choice (a collective call under MPI).
template <class T>
void agree_on(const RenderHooks& hooks, T& value) {
  static_assert(std::is_trivially_copyable_v<T>);
  if (!hooks.agree) return;
  StringWriter out;
  out.put(value);
  hooks.agree(out.bytes);
  StringReader in(out.bytes);
  value = in.get<T>();
}

template <class T>
void agree_on(const RenderHooks& hooks, std::vector<T>& values) {
  if (!hooks.agree) return;
  StringWriter out;
  out.put_vector(values);
  hooks.agree(out.bytes);
  StringReader in(out.bytes);
  values = in.template get_vector<T>(out.bytes.size() / sizeof(T));
}

}  // namespace lantern
