// The render's choices as types: which integrator, MIS heuristic, sampler,
// light sampler and ray back end. The command line, a scene file's Integrator
// directive and bindings name them with the words below; parse_* turns a
// word into the choice (std::invalid_argument for any other word, naming
// those it accepts) and name() back.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <string_view>

namespace lantern {

enum class Integrator : uint8_t {
  Path,  // unidirectional path tracing with next-event estimation
  Bdpt,  // bidirectional path tracing (docs/bdpt.md)
  Lt,    // light tracing: bdpt's t = 1 strategies alone
  Vcm,   // vertex connection and merging (docs/vcm.md)
  Bpm,   // bidirectional photon mapping: merges without connections
  Ppm,   // progressive photon mapping
  // pbrt-v3's "directlighting": light arriving straight from the lights at
  // each vertex (next-event estimation and BSDF sampling, with MIS), the
  // path continuing only through specular scattering; the path tracer
  // with its paths cut after their first non-specular bounce.
  Direct,
  // pbrt-v4's "ambientocclusion": at the first surface a camera ray hits,
  // one direction of the hemisphere about the geometric normal, white
  // where nothing lies within SceneSettings::ao_max_distance (lights and
  // media play no part).
  AmbientOcclusion,
  // pbrt-v4's "mlt": Metropolis light transport in primary sample space
  // over bidirectional path tracing (integrator/metropolis.h).
  Mlt,
};
enum class MisHeuristic : uint8_t { Power, Balance };  // bdpt's: beta = 2 or 1
// What guided paths learn directions with (docs/guiding.md).
enum class GuideModel : uint8_t { Quadtree, Vmm };
// pbrt-v4's samplers (docs/samplers.md).
enum class SamplerKind : uint8_t { Independent, Stratified, Halton, Sobol, PaddedSobol, ZSobol };
enum class LightSamplerKind : uint8_t { Bvh, Power, Uniform };  // next-event estimation's choice of light
// How light subpaths choose their light (RenderOptions::light_choice).
enum class LightChoiceKind : uint8_t { Auto, Power, Uniform };
// Embree's interfaces, on the same batches: rtcIntersectNp (stream),
// rtcIntersect1M, rtcIntersect1, 16-wide packets.
enum class RayBackend : uint8_t { StreamNp, Stream1M, Single, Packet16 };
// How the scene is laid out for Embree (accel/embree_scene.h): fast places
// ObjectInstances by Embree's instance geometries and builds its fastest
// BVH; compact places still instances by one user geometry (56 bytes of
// transform each and a box) and builds Embree's compact BVH (a quarter to
// a third less memory); auto chooses each by the scene's size.
enum class MemoryLayout : uint8_t { Auto, Fast, Compact };

namespace option_words {
template <class E>
struct Word {
  E value;
  const char* word;
};
inline constexpr std::array<Word<Integrator>, 9> kIntegrators{{{Integrator::Path, "path"},
                                                               {Integrator::Bdpt, "bdpt"},
                                                               {Integrator::Lt, "lt"},
                                                               {Integrator::Vcm, "vcm"},
                                                               {Integrator::Bpm, "bpm"},
                                                               {Integrator::Ppm, "ppm"},
                                                               {Integrator::Direct, "directlighting"},
                                                               {Integrator::AmbientOcclusion, "ambientocclusion"},
                                                               {Integrator::Mlt, "mlt"}}};
inline constexpr std::array<Word<MisHeuristic>, 2> kMis{{{MisHeuristic::Power, "power"}, {MisHeuristic::Balance, "balance"}}};
inline constexpr std::array<Word<GuideModel>, 2> kGuideModels{
    {{GuideModel::Quadtree, "quadtree"}, {GuideModel::Vmm, "vmm"}}};
inline constexpr std::array<Word<SamplerKind>, 6> kSamplers{{{SamplerKind::ZSobol, "zsobol"},
                                                             {SamplerKind::PaddedSobol, "paddedsobol"},
                                                             {SamplerKind::Sobol, "sobol"},
                                                             {SamplerKind::Halton, "halton"},
                                                             {SamplerKind::Stratified, "stratified"},
                                                             {SamplerKind::Independent, "independent"}}};
inline constexpr std::array<Word<LightSamplerKind>, 3> kLightSamplers{
    {{LightSamplerKind::Bvh, "bvh"}, {LightSamplerKind::Power, "power"}, {LightSamplerKind::Uniform, "uniform"}}};
inline constexpr std::array<Word<LightChoiceKind>, 3> kLightChoices{
    {{LightChoiceKind::Auto, "auto"}, {LightChoiceKind::Power, "power"}, {LightChoiceKind::Uniform, "uniform"}}};
inline constexpr std::array<Word<MemoryLayout>, 3> kMemoryLayouts{
    {{MemoryLayout::Auto, "auto"}, {MemoryLayout::Fast, "fast"}, {MemoryLayout::Compact, "compact"}}};
inline constexpr std::array<Word<RayBackend>, 4> kRayBackends{{{RayBackend::StreamNp, "stream"},
                                                               {RayBackend::Stream1M, "stream-1m"},
                                                               {RayBackend::Single, "single"},
                                                               {RayBackend::Packet16, "packet16"}}};

template <class E, size_t N>
E parse(std::string_view w, const std::array<Word<E>, N>& words, const char* what) {
  for (const Word<E>& x : words)
    if (w == x.word) return x.value;
  std::string expected;
  for (size_t i = 0; i < N; ++i) expected += (i == 0 ? "" : i + 1 == N ? " or " : ", ") + std::string(words[i].word);
  throw std::invalid_argument("unknown " + std::string(what) + " \"" + std::string(w) + "\"; expected " + expected);
}
template <class E, size_t N>
const char* name(E e, const std::array<Word<E>, N>& words) {
  for (const Word<E>& x : words)
    if (x.value == e) return x.word;
  return "?";
}
}  // namespace option_words

inline Integrator parse_integrator(std::string_view w) { return option_words::parse(w, option_words::kIntegrators, "integrator"); }
inline MisHeuristic parse_mis(std::string_view w) { return option_words::parse(w, option_words::kMis, "MIS heuristic"); }
inline GuideModel parse_guide_model(std::string_view w) {
  return option_words::parse(w, option_words::kGuideModels, "guide distribution");
}
inline SamplerKind parse_sampler(std::string_view w) { return option_words::parse(w, option_words::kSamplers, "sampler"); }
inline LightSamplerKind parse_light_sampler(std::string_view w) {
  return option_words::parse(w, option_words::kLightSamplers, "light sampler");
}
inline LightChoiceKind parse_light_choice(std::string_view w) {
  return option_words::parse(w, option_words::kLightChoices, "light choice");
}
// ("stream-np" is accepted too, for the stream back end.)
inline RayBackend parse_ray_backend(std::string_view w) {
  return w == "stream-np" ? RayBackend::StreamNp : option_words::parse(w, option_words::kRayBackends, "ray back end");
}
inline MemoryLayout parse_memory_layout(std::string_view w) {
  return option_words::parse(w, option_words::kMemoryLayouts, "memory layout");
}
inline const char* name(MemoryLayout l) { return option_words::name(l, option_words::kMemoryLayouts); }
inline const char* name(Integrator i) { return option_words::name(i, option_words::kIntegrators); }
inline const char* name(MisHeuristic m) { return option_words::name(m, option_words::kMis); }
inline const char* name(GuideModel g) { return option_words::name(g, option_words::kGuideModels); }
inline const char* name(SamplerKind s) { return option_words::name(s, option_words::kSamplers); }
inline const char* name(LightSamplerKind l) { return option_words::name(l, option_words::kLightSamplers); }
inline const char* name(LightChoiceKind l) { return option_words::name(l, option_words::kLightChoices); }
inline const char* name(RayBackend b) { return option_words::name(b, option_words::kRayBackends); }

// The integrators the path tracer runs (integrator/path_tracer.h).
inline bool traces_paths(Integrator i) {
  return i == Integrator::Path || i == Integrator::Direct || i == Integrator::AmbientOcclusion;
}
// The integrators that merge light and eye vertices (docs/vcm.md).
inline bool merges_vertices(Integrator i) { return i == Integrator::Vcm || i == Integrator::Bpm || i == Integrator::Ppm; }
// Paths per wave by default (RenderOptions::wave_size): 4096, and for the
// integrators that merge, 16384 light subpaths for each eye vertex to merge
// with; a scene that asks for photon mapping (an "sppm" Integrator) merges
// with its "photonsperiteration", by default a whole pass's (one sample of
// every pixel), at most kPhotonWaveLimit per wave (docs/vcm.md, "Light
// subpaths per merge").
inline constexpr int kPathWaveSize = 4096, kMergingWaveSize = 16384, kPhotonWaveLimit = 1 << 17;
inline int default_wave_size(Integrator i, int64_t photons_per_iteration) {
  if (!merges_vertices(i)) return kPathWaveSize;
  if (photons_per_iteration == 0) return kMergingWaveSize;
  return photons_per_iteration < 0 ? kPhotonWaveLimit : int(std::min<int64_t>(photons_per_iteration, kPhotonWaveLimit));
}
// Whose Russian roulette RenderOptions::roulette_scale scales (the others keep pbrt-v4's rule).
inline bool scales_roulette(Integrator i) { return i == Integrator::Path; }

// RenderOptions::light_subpath_rate: bdpt's alone (vcm's merges need every
// light subpath; lt and mlt are made of them), "auto", 0 (none: the path
// tracer, integrator/light_subpath_rate.h) or 0.01 to 1.
inline bool uses_light_subpath_rate(Integrator i) { return i == Integrator::Bdpt; }
// The path tracer's split camera samples (RenderOptions::split): path, and
// bdpt where it renders the eye subpaths alone with the path tracer's kernel.
inline bool splits_camera_samples(Integrator i) { return i == Integrator::Path || i == Integrator::Bdpt; }
inline constexpr float kLightSubpathsAuto = -1.f;
// RenderOptions::split chosen per scene by a pilot (integrator/split_choice.h).
inline constexpr uint32_t kSplitAuto = 0;

// A float option as text that reads back as the same float (headers,
// fingerprints).
inline std::string exact_text(float v) {
  char s[32];
  std::snprintf(s, sizeof s, "%.9g", double(v));
  return s;
}
inline std::string light_subpaths_text(float rate) { return rate == kLightSubpathsAuto ? "auto" : exact_text(rate); }
inline float parse_light_subpaths(const std::string& w) {
  if (w == "auto") return kLightSubpathsAuto;
  size_t end = 0;
  float v = 0.f;
  try {
    v = std::stof(w, &end);
  } catch (const std::exception&) {
    end = 0;
  }
  if (end == 0 || end != w.size() || !(v == 0.f || (v >= 0.01f && v <= 1.f)))
    throw std::invalid_argument("light subpaths \"" + w + "\": expected auto, 0 or a number from 0.01 to 1");
  return v;
}
inline std::string split_text(uint32_t split) { return split == kSplitAuto ? "auto" : std::to_string(split); }
inline uint32_t parse_split(const std::string& w) {
  for (uint32_t k : {1u, 2u, 4u, 8u, 16u})
    if (w == std::to_string(k)) return k;
  if (w == "auto") return kSplitAuto;
  throw std::invalid_argument("split \"" + w + "\": expected auto, 1, 2, 4, 8 or 16");
}

}  // namespace lantern
