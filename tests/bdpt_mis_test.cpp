// The recursive MIS weights of integrator/bdpt_mis.h against weights built
// from scratch out of the full path densities (Veach 1997, eq. 10.9): on
// random paths, each strategy's weight must equal p_s^beta / sum_i p_i^beta,
// and the weights of all strategies must sum to one.
#include "integrator/bdpt_mis.h"

#include "integrator/light_subpath_rate.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

namespace lantern {
namespace {

// A random path x0 (on an area light) ... xk (a pinhole camera) through
// Lambertian vertices, with every density the strategies use.
struct RandomPath {
  std::vector<Vec3> x, n;  // n[0]: light normal; n[k] unused (camera)
  Vec3 forward;            // camera axis
  float film_area = 1.3f;
  float emission_pos_A = 0.8f;  // light's positional density (pmf included)
  float direct_pdf_A = 2.7f;    // next-event density of x0, deliberately unlike emission_pos_A
  int k() const { return int(x.size()) - 1; }

  Vec3 dir(int from, int to) const { return glm::normalize(x[size_t(to)] - x[size_t(from)]); }
  float dist2(int a, int b) const { return glm::dot(x[size_t(a)] - x[size_t(b)], x[size_t(a)] - x[size_t(b)]); }
  float cos_at(int i, int other) const { return std::fabs(glm::dot(n[size_t(i)], dir(i, other))); }
  // Lambertian density at vertex i of leaving towards `to` (whatever it came from).
  float bsdf_pdf(int i, int to) const { return cos_at(i, to) / kPi; }
  float emission_dir_W(int to) const { return cos_at(0, to) / kPi; }
  float camera_dir_W(int to) const {
    float c = glm::dot(dir(k(), to), forward);
    return 1.f / (film_area * c * c * c);
  }
  // Area density of vertex i generated from neighbour j's side (j = i +- 1).
  float area_pdf(int i, int j) const {
    float solid;
    if (j == k())
      solid = camera_dir_W(i);
    else if (j == 0)
      solid = emission_dir_W(i);
    else
      solid = bsdf_pdf(j, i);
    return solid * cos_at(i, j) / dist2(i, j);
  }
};

RandomPath make_path(int k, std::mt19937& rng) {
  std::uniform_real_distribution<float> u(-1.f, 1.f);
  RandomPath p;
  p.forward = Vec3(0, 0, 1);
  for (int i = 0; i <= k; ++i) {
    p.x.push_back(Vec3(u(rng), u(rng), u(rng)) * 2.f);
    p.n.push_back(glm::normalize(Vec3(u(rng), u(rng), u(rng)) + Vec3(0.f, 0.f, 0.01f)));
  }
  // The camera looks at every vertex from in front: put it behind them all.
  p.x[size_t(k)] = Vec3(0.f, 0.f, -6.f);
  return p;
}

// p_s: light subpath x0..x_{s-1}, eye subpath x_s..x_k.
double explicit_pdf(const RandomPath& p, int s) {
  const int k = p.k();
  const int t = k + 1 - s;
  double pdf = 1.0;
  if (s >= 1) pdf *= (s == 1 && t >= 2) ? p.direct_pdf_A : p.emission_pos_A;
  for (int i = 1; i <= s - 1; ++i) pdf *= p.area_pdf(i, i - 1);
  for (int i = s; i <= k - 1; ++i) pdf *= p.area_pdf(i, i + 1);
  return pdf;
}

// Replays what the integrator computes for strategy s; *rescaled, if
// asked for, the part of its ratio sum that the light subpath rate
// rescales.
float recursive_weight(const RandomPath& p, int s, MisPower mis, float* rescaled = nullptr) {
  float unused = 0.f;
  if (!rescaled) rescaled = &unused;
  *rescaled = 0.f;
  const int k = p.k();
  const int t = k + 1 - s;
  auto emission_W = [&](int to) { return p.emission_pos_A * p.emission_dir_W(to); };
  MisState light, eye;
  if (s >= 2) {  // light subpath up to x_{s-1}
    light = mis_light_start(p.direct_pdf_A, emission_W(1), p.cos_at(0, 1), false, mis);
    mis_after_hit(light, p.dist2(0, 1), p.cos_at(1, 0), true, mis);
    for (int i = 1; i <= s - 2; ++i) {
      mis_after_scatter(light, p.cos_at(i, i + 1), p.bsdf_pdf(i, i + 1), p.bsdf_pdf(i, i - 1), false, mis);
      mis_after_hit(light, p.dist2(i, i + 1), p.cos_at(i + 1, i), true, mis);
    }
  }
  if (t >= 2) {  // eye subpath down to x_s
    eye = mis_camera_start(p.camera_dir_W(k - 1), mis);
    mis_after_hit(eye, p.dist2(k, k - 1), p.cos_at(k - 1, k), true, mis);
    for (int i = k - 1; i >= std::max(s, 1) + 1; --i) {
      mis_after_scatter(eye, p.cos_at(i, i - 1), p.bsdf_pdf(i, i - 1), p.bsdf_pdf(i, i + 1), false, mis);
      mis_after_hit(eye, p.dist2(i, i - 1), p.cos_at(i - 1, i), true, mis);
    }
  }
  if (s == 0) {  // the eye subpath hits the light at x0
    if (k == 1) return mis_weight_hit_light_direct(eye, p.emission_pos_A, mis);
    // eye is at x1; one more bounce to x0
    mis_after_scatter(eye, p.cos_at(1, 0), p.bsdf_pdf(1, 0), p.bsdf_pdf(1, 2), false, mis);
    mis_after_hit(eye, p.dist2(1, 0), p.cos_at(0, 1), true, mis);
    return mis_weight_hit_light(eye, p.direct_pdf_A, emission_W(1), mis, rescaled);
  }
  auto weighed = [&](const DeferredMis& d) {
    *rescaled = mis_rescaled_vacuum(d);
    return mis_weight_vacuum(d);
  };
  if (s == 1 && t == 1)
    return weighed(mis_sums_light_origin(p.camera_dir_W(0) * p.cos_at(0, 1) / p.dist2(0, 1), p.emission_pos_A, false, mis));
  if (s == 1) {  // next-event estimation from x1
    float light_pdf_W = p.direct_pdf_A * p.dist2(0, 1) / p.cos_at(0, 1);
    float emission_fwd_A = emission_W(1) * p.cos_at(1, 0) / p.dist2(0, 1);
    return weighed(mis_sums_next_event(eye, light_pdf_W, p.bsdf_pdf(1, 0), emission_fwd_A, p.direct_pdf_A,
                                       p.bsdf_pdf(1, 2), mis));
  }
  if (t == 1) {  // light tracing from x_{k-1}
    float camera_pdf_A = p.camera_dir_W(k - 1) * p.cos_at(k - 1, k) / p.dist2(k - 1, k);
    return weighed(mis_sums_light_trace(light, camera_pdf_A, p.bsdf_pdf(k - 1, k - 2), mis));
  }
  // connection between x_{s-1} (light) and x_s (eye)
  const int l = s - 1, e = s;
  float d2 = p.dist2(l, e);
  float eye_fwd_A = p.bsdf_pdf(e, l) * p.cos_at(l, e) / d2;
  float light_fwd_A = p.bsdf_pdf(l, e) * p.cos_at(e, l) / d2;
  return weighed(mis_sums_connect(eye, light, eye_fwd_A, p.bsdf_pdf(e, e + 1), light_fwd_A, p.bsdf_pdf(l, l - 1), mis));
}

class MisWeights : public ::testing::TestWithParam<float> {};

TEST_P(MisWeights, MatchExplicitPathDensitiesAndSumToOne) {
  const MisPower mis{GetParam()};
  std::mt19937 rng(12345);
  for (int trial = 0; trial < 300; ++trial) {
    const int k = 1 + trial % 6;  // path lengths 1 .. 6 edges
    RandomPath p = make_path(k, rng);
    std::vector<double> pdf(size_t(k) + 1);
    double sum = 0.0;
    for (int s = 0; s <= k; ++s) sum += std::pow(pdf[size_t(s)] = explicit_pdf(p, s), double(mis.beta));
    double total = 0.0;
    for (int s = 0; s <= k; ++s) {
      double expected = std::pow(pdf[size_t(s)], double(mis.beta)) / sum;
      double w = recursive_weight(p, s, mis);
      EXPECT_NEAR(w, expected, 1e-3 * std::max(1.0, expected)) << "k=" << k << " s=" << s << " trial " << trial;
      total += w;
    }
    EXPECT_NEAR(total, 1.0, 1e-3) << "k=" << k << " trial " << trial;
  }
}

// With a light subpath rate q (a camera sample traces a light subpath
// beyond the light with probability q), the strategies that use one
// (s >= 2) are run q times per camera sample and the others once: each
// weight must be (n_s p_s)^beta / sum_i (n_i p_i)^beta (Veach 1997, eq.
// 9.13, with sample counts n_i), and they still sum to one. And the weight
// at any rate follows from the weight at rate 1 and the part of its ratio
// sum of the other count class (what the pilot of light_subpath_rate.h
// reads). Leaving the counts out of either subpath's start, or out of
// next-event estimation or emission found, breaks the first; not carrying
// the start's share along the light subpath breaks the second (checked).
TEST_P(MisWeights, CountTheLightSubpathRate) {
  const float beta = GetParam();
  std::mt19937 rng(777);
  for (const float q : {0.5f, 0.2f}) {
    MisPower at_rate{beta}, at_one{beta};
    at_rate.with_light = at_rate(q);
    at_rate.without_light = at_rate(1.f / q);
    for (int trial = 0; trial < 200; ++trial) {
      const int k = 1 + trial % 6;
      RandomPath p = make_path(k, rng);
      std::vector<double> term(size_t(k) + 1);
      double sum = 0.0;
      for (int s = 0; s <= k; ++s) sum += term[size_t(s)] = std::pow((s >= 2 ? q : 1.0) * explicit_pdf(p, s), double(beta));
      double total = 0.0;
      for (int s = 0; s <= k; ++s) {
        const double expected = term[size_t(s)] / sum;
        const double w = recursive_weight(p, s, at_rate);
        EXPECT_NEAR(w, expected, 1e-3 * std::max(1.0, expected)) << "q=" << q << " k=" << k << " s=" << s;
        float rescaled = 0.f;
        const float w1 = recursive_weight(p, s, at_one, &rescaled);
        EXPECT_NEAR(weight_at_rate(w1, rescaled, s >= 2, q, beta), expected, 1e-3 * std::max(1.0, expected))
            << "from rate 1: q=" << q << " k=" << k << " s=" << s;
        total += w;
      }
      EXPECT_NEAR(total, 1.0, 1e-3) << "q=" << q << " k=" << k;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Heuristics, MisWeights, ::testing::Values(1.f, 2.f),
                         [](const auto& info) { return info.param == 1.f ? "Balance" : "Power"; });

// Vertex merging (vcm) at interior vertex x_i: the light subpath reaches
// x_i, the eye subpath reaches within the radius of it, with density
// p_light(x_0..x_i) p_eye(x_k..x_i) eta (Georgiev et al. 2012, eq. 10).
double explicit_merge_pdf(const RandomPath& p, int i, double eta) {
  double pdf = p.emission_pos_A * eta;
  for (int m = 1; m <= i; ++m) pdf *= p.area_pdf(m, m - 1);
  for (int m = i; m <= p.k() - 1; ++m) pdf *= p.area_pdf(m, m + 1);
  return pdf;
}

// What the integrator computes for merging at x_i.
float recursive_merge_weight(const RandomPath& p, int i, MisPower mis) {
  const int k = p.k();
  MisState light = mis_light_start(p.direct_pdf_A, p.emission_pos_A * p.emission_dir_W(1), p.cos_at(0, 1), false, mis);
  mis_after_hit(light, p.dist2(0, 1), p.cos_at(1, 0), true, mis);
  for (int m = 1; m <= i - 1; ++m) {
    mis_after_scatter(light, p.cos_at(m, m + 1), p.bsdf_pdf(m, m + 1), p.bsdf_pdf(m, m - 1), false, mis);
    mis_after_hit(light, p.dist2(m, m + 1), p.cos_at(m + 1, m), true, mis);
  }
  MisState eye = mis_camera_start(p.camera_dir_W(k - 1), mis);
  mis_after_hit(eye, p.dist2(k, k - 1), p.cos_at(k - 1, k), true, mis);
  for (int m = k - 1; m >= i + 1; --m) {
    mis_after_scatter(eye, p.cos_at(m, m - 1), p.bsdf_pdf(m, m - 1), p.bsdf_pdf(m, m + 1), false, mis);
    mis_after_hit(eye, p.dist2(m, m - 1), p.cos_at(m - 1, m), true, mis);
  }
  return mis_weight_merge(eye, light, p.bsdf_pdf(i, i - 1), p.bsdf_pdf(i, i + 1), MergeKind::Surface, mis);
}

// With merging, every connection strategy and every merge of a path weigh
// p^beta / (the sum over all of them), and all sum to one.
TEST_P(MisWeights, WithMergingMatchExplicitDensitiesAndSumToOne) {
  std::mt19937 rng(777);
  for (int trial = 0; trial < 300; ++trial) {
    const double eta = std::pow(10.0, double(trial % 7) - 3.0);  // from 1e-3 to 1e3
    MisPower mis{GetParam()};
    mis.vm_weight = mis(float(eta));
    const int k = 1 + trial % 6;
    RandomPath p = make_path(k, rng);
    double sum = 0.0;
    std::vector<double> vc(size_t(k) + 1), vm(size_t(k) + 1, 0.0);
    for (int s = 0; s <= k; ++s) sum += std::pow(vc[size_t(s)] = explicit_pdf(p, s), double(mis.beta));
    for (int i = 1; i <= k - 1; ++i) sum += std::pow(vm[size_t(i)] = explicit_merge_pdf(p, i, eta), double(mis.beta));
    double total = 0.0;
    for (int s = 0; s <= k; ++s) {
      const double expected = std::pow(vc[size_t(s)], double(mis.beta)) / sum, w = recursive_weight(p, s, mis);
      EXPECT_NEAR(w, expected, 2e-3 * std::max(1.0, expected)) << "k=" << k << " s=" << s << " trial " << trial;
      total += w;
    }
    for (int i = 1; i <= k - 1; ++i) {
      const double expected = std::pow(vm[size_t(i)], double(mis.beta)) / sum, w = recursive_merge_weight(p, i, mis);
      EXPECT_NEAR(w, expected, 2e-3 * std::max(1.0, expected)) << "k=" << k << " merge at " << i << " trial " << trial;
      total += w;
    }
    EXPECT_NEAR(total, 1.0, 2e-3) << "k=" << k << " trial " << trial;
  }
}

// In a scene with media a vertex may lie in a medium: it connects (its
// connections weighted once their transmittance is known, here 1) and
// merges in a ball, with its own eta. With `merge` saying how each vertex
// merges, every connection's and every merge's weight is p^beta over the
// sum over all those strategies, and they sum to one; so too for merges
// alone (bpm).
struct MediaPath {
  RandomPath p;
  std::vector<MergeKind> merge;  // per vertex; the ends (light, camera) never merge
};

MisState light_subpath_to(const MediaPath& mp, int last, MisPower mis) {
  const RandomPath& p = mp.p;
  MisState light = mis_light_start(p.direct_pdf_A, p.emission_pos_A * p.emission_dir_W(1), p.cos_at(0, 1), false, mis);
  mis_after_hit(light, p.dist2(0, 1), p.cos_at(1, 0), true, mis);
  for (int m = 1; m <= last - 1; ++m) {
    mis_after_scatter(light, p.cos_at(m, m + 1), p.bsdf_pdf(m, m + 1), p.bsdf_pdf(m, m - 1), false, mis,
                      mp.merge[size_t(m)]);
    mis_after_hit(light, p.dist2(m, m + 1), p.cos_at(m + 1, m), true, mis);
  }
  return light;
}

MisState eye_subpath_to(const MediaPath& mp, int last, MisPower mis) {
  const RandomPath& p = mp.p;
  const int k = p.k();
  MisState eye = mis_camera_start(p.camera_dir_W(k - 1), mis);
  mis_after_hit(eye, p.dist2(k, k - 1), p.cos_at(k - 1, k), true, mis);
  for (int m = k - 1; m >= last + 1; --m) {
    mis_after_scatter(eye, p.cos_at(m, m - 1), p.bsdf_pdf(m, m - 1), p.bsdf_pdf(m, m + 1), false, mis,
                      mp.merge[size_t(m)]);
    mis_after_hit(eye, p.dist2(m, m - 1), p.cos_at(m - 1, m), true, mis);
  }
  return eye;
}

// What the integrator computes for strategy s of a path through media:
// connections weighted as deferred ones (transmittance 1).
float media_connection_weight(const MediaPath& mp, int s, MisPower mis) {
  const RandomPath& p = mp.p;
  const int k = p.k(), t = k + 1 - s;
  const Spectrum T(1.f);
  DeferredMis d;
  if (s == 0) {
    if (k == 1) return mis_weight_hit_light_direct(eye_subpath_to(mp, 1, mis), p.emission_pos_A, mis);
    MisState eye = eye_subpath_to(mp, 1, mis);
    mis_after_scatter(eye, p.cos_at(1, 0), p.bsdf_pdf(1, 0), p.bsdf_pdf(1, 2), false, mis, mp.merge[1]);
    mis_after_hit(eye, p.dist2(1, 0), p.cos_at(0, 1), true, mis);
    return mis_weight_hit_light(eye, p.direct_pdf_A, p.emission_pos_A * p.emission_dir_W(1), mis);
  }
  if (s == 1 && t == 1)
    return mis_weight_vacuum(mis_sums_light_origin(p.camera_dir_W(0) * p.cos_at(0, 1) / p.dist2(0, 1), p.emission_pos_A, false, mis));
  if (s == 1) {  // next-event estimation from x1
    const float light_pdf_W = p.direct_pdf_A * p.dist2(0, 1) / p.cos_at(0, 1);
    const float emission_fwd_A = p.emission_pos_A * p.emission_dir_W(1) * p.cos_at(1, 0) / p.dist2(0, 1);
    d.a = mis(p.bsdf_pdf(1, 0) / light_pdf_W);
    d.b = mis(emission_fwd_A / p.direct_pdf_A) *
          mis_connection_sum(eye_subpath_to(mp, 1, mis), p.bsdf_pdf(1, 2), mp.merge[1], mis);
    return mis_weight_deferred(d, T, mis);
  }
  if (t == 1) {  // light tracing from x_{k-1}
    const float camera_pdf_A = p.camera_dir_W(k - 1) * p.cos_at(k - 1, k) / p.dist2(k - 1, k);
    d.a = mis(camera_pdf_A) *
          mis_connection_sum(light_subpath_to(mp, k - 1, mis), p.bsdf_pdf(k - 1, k - 2), mp.merge[size_t(k - 1)], mis);
    return mis_weight_deferred(d, T, mis);
  }
  const int l = s - 1, e = s;
  const float d2 = p.dist2(l, e);
  d.a = mis(p.bsdf_pdf(e, l) * p.cos_at(l, e) / d2) *
        mis_connection_sum(light_subpath_to(mp, l, mis), p.bsdf_pdf(l, l - 1), mp.merge[size_t(l)], mis);
  d.b = mis(p.bsdf_pdf(l, e) * p.cos_at(e, l) / d2) *
        mis_connection_sum(eye_subpath_to(mp, e, mis), p.bsdf_pdf(e, e + 1), mp.merge[size_t(e)], mis);
  return mis_weight_deferred(d, T, mis);
}

TEST_P(MisWeights, MediumVerticesMergeInABall) {
  std::mt19937 rng(31337);
  std::bernoulli_distribution in_medium(0.4);
  for (int trial = 0; trial < 400; ++trial) {
    // eta of a surface merge (pi r^2 n) and of a medium merge (4/3 pi r^3 n),
    // unrelated here; every fourth trial without medium merges (ppm's case)
    const double eta = std::pow(10.0, double(trial % 7) - 3.0), eta_medium = std::pow(10.0, double(trial % 5) - 2.5);
    const bool medium_merges = trial % 4 != 3, connections = trial % 3 != 2;  // bpm's case: merges alone
    MisPower mis{GetParam()};
    mis.vm_weight = mis(float(eta));
    mis.vm_medium = medium_merges ? mis(float(eta_medium)) : 0.f;
    mis.connect = connections ? 1.f : 0.f;
    const int k = 1 + trial % 6;
    MediaPath mp{make_path(k, rng), std::vector<MergeKind>(size_t(k) + 1, MergeKind::None)};
    for (int i = 1; i <= k - 1; ++i)
      mp.merge[size_t(i)] = !in_medium(rng) ? MergeKind::Surface : medium_merges ? MergeKind::Medium : MergeKind::None;
    std::vector<double> vc(size_t(k) + 1), vm(size_t(k) + 1, 0.0);
    double sum = 0.0, total = 0.0;
    for (int s = 0; s <= k && connections; ++s) sum += std::pow(vc[size_t(s)] = explicit_pdf(mp.p, s), double(mis.beta));
    for (int i = 1; i <= k - 1; ++i) {
      const MergeKind kind = mp.merge[size_t(i)];
      if (kind == MergeKind::None) continue;
      vm[size_t(i)] = explicit_merge_pdf(mp.p, i, kind == MergeKind::Medium ? eta_medium : eta);
      sum += std::pow(vm[size_t(i)], double(mis.beta));
    }
    if (!(sum > 0.0)) continue;  // merges alone, and no vertex merges: emission's only (mis_weight_hit_light_merging_only)
    for (int s = 0; s <= k && connections; ++s) {
      const double expected = std::pow(vc[size_t(s)], double(mis.beta)) / sum, w = media_connection_weight(mp, s, mis);
      EXPECT_NEAR(w, expected, 2e-3 * std::max(1.0, expected)) << "k=" << k << " s=" << s << " trial " << trial;
      total += w;
    }
    for (int i = 1; i <= k - 1; ++i) {
      if (mp.merge[size_t(i)] == MergeKind::None) continue;
      const MisState light = light_subpath_to(mp, i, mis), eye = eye_subpath_to(mp, i, mis);
      const double expected = std::pow(vm[size_t(i)], double(mis.beta)) / sum,
                   w = mis_weight_merge(eye, light, mp.p.bsdf_pdf(i, i - 1), mp.p.bsdf_pdf(i, i + 1),
                                        mp.merge[size_t(i)], mis);
      EXPECT_NEAR(w, expected, 2e-3 * std::max(1.0, expected)) << "k=" << k << " merge at " << i << " trial " << trial;
      total += w;
    }
    EXPECT_NEAR(total, 1.0, 2e-3) << "k=" << k << " trial " << trial;
  }
}

// Without connections (bpm: vc = 0) the merges of a path are its only
// strategies: each weighs p^beta / (the sum over the merges), and they sum
// to one. Emission found by the eye subpath counts only where no vertex
// can merge, which dVM tells.
TEST_P(MisWeights, MergesAloneMatchExplicitDensitiesAndSumToOne) {
  std::mt19937 rng(4242);
  for (int trial = 0; trial < 300; ++trial) {
    const double eta = std::pow(10.0, double(trial % 7) - 3.0);
    MisPower mis{GetParam()};
    mis.vm_weight = mis(float(eta));
    mis.connect = 0.f;
    const int k = 2 + trial % 5;
    RandomPath p = make_path(k, rng);
    std::vector<double> vm(size_t(k), 0.0);
    double sum = 0.0, total = 0.0;
    for (int i = 1; i <= k - 1; ++i) sum += std::pow(vm[size_t(i)] = explicit_merge_pdf(p, i, eta), double(mis.beta));
    for (int i = 1; i <= k - 1; ++i) {
      const double expected = std::pow(vm[size_t(i)], double(mis.beta)) / sum, w = recursive_merge_weight(p, i, mis);
      EXPECT_NEAR(w, expected, 2e-3 * std::max(1.0, expected)) << "k=" << k << " merge at " << i << " trial " << trial;
      total += w;
    }
    EXPECT_NEAR(total, 1.0, 2e-3) << "k=" << k << " trial " << trial;
  }
  MisPower mis{GetParam()};
  mis.vm_weight = mis(0.5f);
  mis.connect = 0.f;
  MisState eye = mis_camera_start(0.3f, mis);
  mis_after_hit(eye, 2.f, 0.5f, true, mis);
  EXPECT_EQ(mis_weight_hit_light_merging_only(eye), 1.f);  // a light seen directly
  mis_after_scatter(eye, 0.7f, 1.f, 1.f, true, mis);
  mis_after_hit(eye, 2.f, 0.5f, true, mis);
  EXPECT_EQ(mis_weight_hit_light_merging_only(eye), 1.f);  // through a mirror
  mis_after_scatter(eye, 0.7f, 0.2f, 0.3f, false, mis);
  mis_after_hit(eye, 2.f, 0.5f, true, mis);
  EXPECT_EQ(mis_weight_hit_light_merging_only(eye), 0.f);  // past a diffuse vertex, where merges sample it
}

}  // namespace
}  // namespace lantern
