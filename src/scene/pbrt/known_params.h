// The parameter names pbrt-v4 and pbrt-v3 read, by directive kind: what
// tells a parameter Lantern does not use (pbrt knows it) from a typo
// (nobody does), which pbrt-v4 stops on.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace lantern::pbrt {

// kind: "camera", "film", "filter", "sampler", "integrator", "accelerator",
// "shape", "material", "texture", "light", "arealight", "medium". Whether
// pbrt-v4 or pbrt-v3 reads a parameter of that name for some directive of
// the kind (an unknown kind knows every name).
bool is_known_parameter(std::string_view kind, std::string_view name);
// Those names, for "did you mean"; empty for an unknown kind.
const std::vector<std::string>& known_parameters(std::string_view kind);

}  // namespace lantern::pbrt
