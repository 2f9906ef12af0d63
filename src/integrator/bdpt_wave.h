// Structure-of-arrays pools of the bidirectional tracer's wave. Per-slot
// arrays hold the state of one sample's eye and light subpaths; per-ray
// arrays hold the hits of the current bounce (ray i belongs to active[i]);
// the light vertex pool holds every connectible light vertex of the wave.
#pragma once

#include <algorithm>
#include <vector>

#include "accel/ray_stream.h"
#include "film/film.h"
#include "integrator/bdpt_mis.h"
#include "integrator/guide_vertices.h"
#include "integrator/hit.h"
#include "integrator/vertex_grid.h"
#include "integrator/wave_stats.h"
#include "light/emission.h"
#include "material/bsdf_store.h"
#include "material/material.h"
#include "sampler/sampler.h"

namespace lantern {

// State of one subpath per slot, used once for the light and once for the
// eye subpaths.
struct SubpathPool {
  std::vector<Spectrum> beta;
  std::vector<MisState> mis;
  std::vector<Vec3> prev_p;  // origin of the ray that found the current vertex
  std::vector<Vec3> prev_n;  // its shading normal (the light sampler's context; zero at the camera)
  std::vector<float> eta_scale, rr_scale;
  std::vector<uint8_t> dispersed;  // scattered at a dispersive surface (integrator/dispersion.h)
  // With media only: the medium the subpath's ray travels in, and the
  // extinction at its last vertex (zero on a surface), for reverse densities.
  std::vector<MediumHandle> medium;
  std::vector<Spectrum> sigma_prev;
  void resize_media(uint32_t n) {
    medium.resize(n);
    sigma_prev.resize(n);
  }
  void resize(uint32_t n) {
    beta.resize(n);
    mis.resize(n);
    prev_p.resize(n);
    prev_n.resize(n);
    eta_scale.resize(n);
    rr_scale.resize(n);
    dispersed.resize(n);
  }
};

// Where each light subpath started: what the first hit needs to finish the
// light's MIS quantities.
struct LightOriginPool {
  std::vector<uint32_t> light;  // index into LightPools::all
  std::vector<Vec3> n;
  std::vector<float> emission_pdf_W, cos_light, direct_pdf_A;  // direct_pdf_A < 0: compute at the first hit
  std::vector<uint8_t> delta, infinite;
  // 1 for a subpath from a volume light, whose paths are one segment
  // shorter (integrator/volume_lights.h); else 0.
  std::vector<uint8_t> extra_depth;
  void resize(uint32_t n_) {
    extra_depth.resize(n_);
    light.resize(n_);
    n.resize(n_);
    emission_pdf_W.resize(n_);
    cos_light.resize(n_);
    direct_pdf_A.resize(n_);
    delta.resize(n_);
    infinite.resize(n_);
  }
};

// A light vertex as stored for the eye subpaths: on a surface, or (ng and
// ns zero, no BSDF) in a medium.
struct StoredLightVertex {
  Vec3 p, ng{0.f}, ns{0.f}, wo;
  float error_scale = 0.f;
  BsdfRef bsdf;                   // its BSDF, built once (none in a medium, or when no eye vertex connects)
  const Vec3* tangent = nullptr;  // a curve's
  MediumHandle medium;            // a medium vertex's
  Spectrum sigma_t{0.f};          // the extinction there
  bool dispersed = false;         // its subpath scattered at a dispersive surface (integrator/dispersion.h)
};

// Connectible (non-specular) light vertices, appended bounce by bounce and
// then grouped by slot: the vertices of slot s are order[begin[s] .. begin[s+1]).
struct LightVertexPool {
  std::vector<uint32_t> slot, depth;
  std::vector<Vec3> p, ng, ns, wo;
  std::vector<float> error_scale;
  std::vector<Spectrum> beta;
  std::vector<MisState> mis;
  std::vector<BsdfRef> bsdf;         // into bsdfs
  BsdfStore bsdfs;
  std::vector<Vec3> tangent;         // empty unless the scene has curves
  std::vector<MediumHandle> medium;  // empty unless the scene has media; a medium vertex's, else vacuum
  std::vector<Spectrum> sigma_t;          // alongside medium: the extinction at a medium vertex
  std::vector<uint8_t> dispersed;         // empty unless a vertex's subpath is dispersed
  std::vector<uint32_t> begin, order;

  size_t size() const { return slot.size(); }
  // Appends a vertex. The arrays only some scenes need are kept only once
  // a vertex has the field, padded for the vertices before it.
  void push(uint32_t s, uint32_t d, const Spectrum& b, const MisState& m, const StoredLightVertex& x) {
    slot.push_back(s);
    depth.push_back(d);
    p.push_back(x.p);
    ng.push_back(x.ng);
    ns.push_back(x.ns);
    wo.push_back(x.wo);
    error_scale.push_back(x.error_scale);
    beta.push_back(b);
    mis.push_back(m);
    bsdf.push_back(x.bsdf);
    if (x.tangent || !tangent.empty()) {
      tangent.resize(size() - 1);
      tangent.push_back(x.tangent ? *x.tangent : Vec3(0.f));
    }
    if (x.dispersed || !dispersed.empty()) {
      dispersed.resize(size() - 1);
      dispersed.push_back(x.dispersed);
    }
    if (!x.medium.vacuum()) {
      medium.resize(size() - 1);
      sigma_t.resize(size() - 1);
      medium.push_back(x.medium);
      sigma_t.push_back(x.sigma_t);
    }
  }
  bool in_medium(uint32_t j) const { return j < medium.size() && !medium[j].vacuum(); }
  bool is_dispersed(uint32_t j) const { return j < dispersed.size() && dispersed[j]; }
  void clear() {
    for (auto* v : {&slot, &depth, &order}) v->clear();
    for (auto* v : {&p, &ng, &ns, &wo}) v->clear();
    error_scale.clear();
    beta.clear();
    mis.clear();
    bsdf.clear();
    bsdfs.clear();
    tangent.clear();
    medium.clear();
    sigma_t.clear();
    dispersed.clear();
  }
};

// A strategy's s or t as stored: saturated at 255 (bdpt's maxdepth has no
// upper limit, and a wrapped count would name the wrong strategy).
inline uint8_t strategy_count(uint32_t n) { return uint8_t(std::min<uint32_t>(n, 255)); }

// The (s, t) strategy of a contribution and its value before the MIS
// weight: recorded only for per-strategy images.
struct StrategyTag {
  uint8_t s, t;
  Spectrum unweighted;
  float weight = 1.f, rescaled = 0.f;  // its MIS weight, and the part of its ratio sum of the other count class
  uint32_t light = kNoLight;           // s = 1: the light sampled (StrategyRecord::light)
};

// A connection of two vertices (or of a vertex and the lens): its shadow
// ray, what it carries if unoccluded, and its MIS weight's deferred part.
struct Connection {
  Vec3 o, d;
  float t_max = 1.f;  // (kInfinity towards a light at infinity, d its direction)
  Spectrum unweighted;
  DeferredMis mis;
  Vec2 p_raster{0.f};         // t = 1: where it lands on the film
  uint8_t s = 0, t = 0;       // its strategy (for per-strategy images)
  bool light_sample = false;  // s = 1 (for --stats)
  uint32_t light = kNoLight;  // s = 1: the light sampled (for the pilot's records)
  MediumHandle start;         // with media: the medium the ray starts in
  MediumHandle expect;        // a volume light's point: the medium the ray must end in
};

// Shadow rays of one stage and what each carries if it is unoccluded.
struct ConnectionPool {
  RayBatch rays;
  std::vector<uint32_t> slot;
  std::vector<uint8_t> light_s;  // its strategy's light vertices (what guided light subpaths learn from)
  std::vector<Spectrum> contrib;
  std::vector<Vec2> p_raster;     // light tracing: where the contribution lands on the film
  std::vector<StrategyTag> tags;  // filled only when strategies are recorded
  std::vector<uint8_t> next_event;  // s = 1: a light sample's ray (for --stats)
  // With media: the medium each ray starts in, its transmittance, and its
  // weight's deferred part (contrib then holds the unweighted value).
  std::vector<MediumHandle> medium;
  std::vector<Spectrum> T, T_mis;  // the estimate, and what MIS sees (medium_events.h)
  std::vector<DeferredMis> deferred;
  std::vector<MediumHandle> expect;  // a volume light's point: the medium the ray must end in (else vacuum)
  std::vector<SampledWavelengths> lambda;  // its sample's wavelengths
  bool media = false;
  bool record = false;
  // Queues connection k of `slot` (whose wavelengths are l, whose time is `time`) carrying
  // contrib (weighted, or with media unweighted until traced).
  void push(uint32_t s, const Connection& k, const Spectrum& c, const SampledWavelengths& l, float time) {
    const uint32_t i = rays.push(k.o, k.d, 0.f, k.t_max, time);
    if (slot.size() <= i) {
      const size_t n = rays.capacity();
      slot.resize(n);
      light_s.resize(n);
      contrib.resize(n);
      p_raster.resize(n);
      next_event.resize(n);
      if (record) tags.resize(n);
      if (media) {
        medium.resize(n);
        deferred.resize(n);
        expect.resize(n);
        lambda.resize(n);
      }
    }
    slot[i] = s;
    light_s[i] = k.s;
    contrib[i] = c;
    p_raster[i] = k.p_raster;
    next_event[i] = k.light_sample;
    if (record) tags[i] = {k.s, k.t, k.unweighted, 1.f, 0.f, k.light};  // (weight and rescaled: once weighted)
    if (media) {
      medium[i] = k.start;
      deferred[i] = k.mis;
      expect[i] = k.expect;
      lambda[i] = l;
    }
  }
};

struct BdptWave {
  void resize_media(uint32_t capacity) {
    eye.resize_media(capacity);
    light.resize_media(capacity);
    ray_medium.resize(capacity);
    u_distance.resize(capacity);
    ray_lambda.resize(capacity);
    ends.resize(capacity);
    scattered.reserve(capacity);
    shadow.media = true;
  }

  BdptWave(uint32_t capacity, RayStream s) : stream(std::move(s)) {
    pixel.resize(capacity);
    sampler.resize(capacity);
    lambda.resize(capacity);
    time.resize(capacity);
    L.resize(capacity);
    raster.resize(capacity);
    eye.resize(capacity);
    light.resize(capacity);
    origin.resize(capacity);
    active.resize(capacity);
    hits.resize(capacity);
    rays.reserve(capacity);
    shadow.rays.reserve(capacity);
    vertices.begin.resize(capacity + 1);
  }

  // per slot
  std::vector<uint32_t> pixel;
  std::vector<PathSampler> sampler;
  std::vector<SampledWavelengths> lambda;  // shared by the slot's eye and light subpaths
  std::vector<float> time;                 // so is its time in the shutter (integrator/shutter.h)
  std::vector<Spectrum> L;
  std::vector<Vec2> raster;  // Metropolis: where its camera sample lies (anywhere on the image)
  GuideVertices guide;       // the eye vertices' records while the guiding field learns
  // While the importance field learns (guided light subpaths): the light
  // vertices' records, each one's depth, and per slot and strategy s what
  // the strategies with s light vertices brought (light_strategies per slot).
  GuideVertices light_guide;
  std::vector<uint8_t> light_guide_depth;
  std::vector<Spectrum> gathered;
  uint32_t light_strategies = 0;
  SubpathPool eye, light;
  LightOriginPool origin;
  uint32_t depth = 0;  // bounce of the current phase

  // per ray of the current bounce
  std::vector<uint32_t> active;
  RayBatch rays;
  HitPool hits;

  ConnectionPool shadow;
  LightVertexPool vertices;
  // With media: per ray, the distance numbers and where segments ended, and
  // the rays that scattered in a medium this bounce.
  std::vector<MediumHandle> ray_medium;
  std::vector<float> u_distance;
  std::vector<SampledWavelengths> ray_lambda;
  SegmentEnds ends;
  std::vector<uint32_t> scattered;
  CrossingScratch crossing;
  // Light subpaths from volume lights, waiting for the medium of their point.
  std::vector<EmissionSample> volume_starts;
  std::vector<uint32_t> volume_slots;
  std::vector<Vec3> volume_points;
  std::vector<MediumHandle> volume_media;
  std::vector<float> volume_times;
  // The MIS exponent and, for vcm, this wave's merging factors; the
  // merging radius, 1 / (pi r^2 n) and 1 / (4/3 pi r^3 n), and the grid
  // over the light vertices.
  MisPower mis;
  float vm_radius = 0.f, vm_normalization = 0.f, vm_normalization_medium = 0.f;
  VertexGrid grid;
  RayStream stream;
  uint32_t first_sample = 0, samples_per_pixel = 1;  // of the wave: a slot's sample index
  uint32_t half_bit = 1;                             // (WaveDesc::half_bit)
  bool odd_sample(uint32_t slot) const { return ((first_sample + slot % samples_per_pixel) & half_bit) != 0; }
  WaveOutput* out = nullptr;  // of the wave being traced
  MetropolisSampler* chains = nullptr;  // of the wave being traced (WaveDesc::chains)
  WaveStats stats;

  size_t memory_bytes() const {
    const SubpathPool* subpaths[] = {&eye, &light};
    size_t b = vector_bytes(pixel) + vector_bytes(sampler) + vector_bytes(lambda) + vector_bytes(time) + vector_bytes(L) + vector_bytes(raster) + vector_bytes(active) + guide.memory_bytes() +
               light_guide.memory_bytes() + vector_bytes(light_guide_depth) + vector_bytes(gathered) +
               rays.memory_bytes() + hits.memory_bytes() + shadow.rays.memory_bytes() + vector_bytes(shadow.slot) + vector_bytes(shadow.light_s) +
               vector_bytes(shadow.contrib) + vector_bytes(shadow.p_raster) + vector_bytes(shadow.tags) +
               vector_bytes(shadow.next_event);
    for (const SubpathPool* p : subpaths)
      b += vector_bytes(p->beta) + vector_bytes(p->mis) + vector_bytes(p->prev_p) + vector_bytes(p->prev_n) + vector_bytes(p->eta_scale) +
           vector_bytes(p->rr_scale) + vector_bytes(p->dispersed);
    const LightOriginPool& o = origin;
    b += vector_bytes(o.light) + vector_bytes(o.n) + vector_bytes(o.emission_pdf_W) + vector_bytes(o.cos_light) +
         vector_bytes(o.direct_pdf_A) + vector_bytes(o.delta) + vector_bytes(o.infinite);
    const LightVertexPool& v = vertices;
    b += vector_bytes(v.slot) + vector_bytes(v.depth) + vector_bytes(v.p) + vector_bytes(v.ng) + vector_bytes(v.ns) +
         vector_bytes(v.wo) + vector_bytes(v.tangent) + vector_bytes(v.error_scale) + vector_bytes(v.beta) +
         vector_bytes(v.mis) + vector_bytes(v.bsdf) + v.bsdfs.memory_bytes() + vector_bytes(v.begin) + vector_bytes(v.order) +
         vector_bytes(v.medium) + vector_bytes(v.sigma_t) + vector_bytes(v.dispersed);
    for (const SubpathPool* p : subpaths) b += vector_bytes(p->medium) + vector_bytes(p->sigma_prev);
    b += vector_bytes(shadow.medium) + vector_bytes(shadow.T) + vector_bytes(shadow.T_mis) + vector_bytes(shadow.deferred) + vector_bytes(ray_medium) +
         vector_bytes(u_distance) + ends.memory_bytes() + vector_bytes(scattered) + crossing.memory_bytes() +
         vector_bytes(shadow.expect) + vector_bytes(shadow.lambda) + vector_bytes(ray_lambda) + vector_bytes(o.extra_depth) + vector_bytes(volume_starts) + vector_bytes(volume_slots) +
         vector_bytes(volume_points) + vector_bytes(volume_media) + vector_bytes(volume_times) + grid.memory_bytes();
    return b;
  }
};

}  // namespace lantern
