// Guided light subpaths (--guide-light, docs/guiding.md): bdpt and vcm
// whose light subpaths sample an importance field, at their surface
// vertices and at an area light's point, converge to their unguided
// images, the same on one and two threads (and bdpt after stops and
// resumes); what it cannot do is refused.
#include <gtest/gtest.h>

#include <cstring>

#include "lantern/error.h"
#include "lantern/render.h"
#include "lantern/scene.h"
#include "sanitizer.h"
#include "stat_compare.h"
#include "stop_and_resume.h"

using namespace lantern;

namespace {

// Two rooms joined by a gap in the wall between them (x from -0.25 to
// 0.25). The main light, a panel in the far room, faces the gap; the camera
// sees the near room, lit by what comes through, and a small ball of light
// there, whose own pixels light tracing (s = 1, t = 1) shares. Unguided, a light subpath
// goes through the gap with its cosine's small share of directions; the
// importance field learns to send more that way, from the panel and from
// the far room's walls.
std::shared_ptr<Scene> two_rooms() {
  return load_scene_from_string(R"(
LookAt 0.6 1.2 -2.8  -0.3 0.4 -0.5  0 1 0
Camera "perspective" "float fov" [ 65 ]
Film "rgb" "integer xresolution" [ 32 ] "integer yresolution" [ 32 ]
WorldBegin
Material "diffuse" "rgb reflectance" [ 0.7 0.65 0.6 ]
# floor and ceiling of both rooms, their side and end walls
Shape "trianglemesh" "point3 P" [ -2 0 -3  2 0 -3  2 0 2  -2 0 2 ] "integer indices" [ 0 2 1 0 3 2 ]
Shape "trianglemesh" "point3 P" [ -2 2 -3  2 2 -3  2 2 2  -2 2 2 ] "integer indices" [ 0 1 2 0 2 3 ]
Shape "trianglemesh" "point3 P" [ -2 0 -3  -2 2 -3  -2 2 2  -2 0 2 ] "integer indices" [ 0 1 2 0 2 3 ]
Shape "trianglemesh" "point3 P" [ 2 0 -3  2 2 -3  2 2 2  2 0 2 ] "integer indices" [ 0 2 1 0 3 2 ]
Shape "trianglemesh" "point3 P" [ -2 0 -3  2 0 -3  2 2 -3  -2 2 -3 ] "integer indices" [ 0 2 1 0 3 2 ]
Shape "trianglemesh" "point3 P" [ -2 0 2  2 0 2  2 2 2  -2 2 2 ] "integer indices" [ 0 1 2 0 2 3 ]
# the wall between them, with its gap
Shape "trianglemesh" "point3 P" [ -2 0 0  -0.25 0 0  -0.25 2 0  -2 2 0 ] "integer indices" [ 0 1 2 0 2 3 ]
Shape "trianglemesh" "point3 P" [ 0.25 0 0  2 0 0  2 2 0  0.25 2 0 ] "integer indices" [ 0 1 2 0 2 3 ]
Material "coateddiffuse" "rgb reflectance" [ 0.2 0.5 0.8 ] "float roughness" [ 0.2 ]
AttributeBegin
  Translate 0.5 0.3 -1.2
  Shape "sphere" "float radius" [ 0.3 ]
AttributeEnd
AttributeBegin
  AreaLightSource "diffuse" "rgb L" [ 6 6 6 ]
  Translate -0.8 0.8 -0.8
  Shape "sphere" "float radius" [ 0.06 ]
AttributeEnd
AttributeBegin
  AreaLightSource "diffuse" "rgb L" [ 30 28 24 ]
  Shape "trianglemesh" "point3 P" [ -0.4 0.6 1.5  0.4 0.6 1.5  0.4 1.4 1.5  -0.4 1.4 1.5 ]
    "integer indices" [ 0 1 2 0 2 3 ]
AttributeEnd
)",
                                "two-rooms.pbrt");
}

RenderOptions options(bool guide_light, bool guide_eye = false) {
  RenderOptions o;
  o.integrator = Integrator::Bdpt;
  o.guide_light_subpaths = guide_light;
  o.guiding = guide_eye;
  o.guide_stop = false;                         // (these tests hold the guided estimator: guided to the end,
  o.guide_distribution = GuideModel::Quadtree;  // with the quadtree they were written for)
  o.spp = 64;
  o.maxdepth = 5;
  return o;
}

}  // namespace

// Light subpaths whose directions come from the mixture of the BSDF (or
// the light's cosine) and the importance field converge to the unguided
// image, alone and with guided eye subpaths: MIS keeps the BSDF's and the
// light's own densities, the throughput divides by the mixture's.
// Dividing the emission's throughput by the light's own density instead
// of the mixture's puts the guided means 48 standard errors off, and the
// surface vertices' by the BSDF's 6.0; ending the whole subpath where the
// guide drew an emission direction the light cannot, its first point's
// s = 1, t = 1 strategy with it, puts them 4.9-5.3 standard errors off
// (checked).
TEST(LightGuiding, BdptAndVcmConvergeToTheirUnguidedImages) {
  if (LANTERN_ASAN) GTEST_SKIP() << "statistics only: the Release suite runs it";
  const auto scene = two_rooms();
  std::vector<Region> regions;
  for (int y = 0; y < 32; y += 8)
    for (int x = 0; x < 32; x += 8) regions.push_back({x, y, 8, 8});
  regions.push_back({8, 11, 3, 3});  // the ball of light's own pixels
  const RegionStats plain = stats_of(render_runs(*scene, options(false), 8, 100), regions);
  const RegionStats light = stats_of(render_runs(*scene, options(true), 8, 200), regions);
  const RegionStats both = stats_of(render_runs(*scene, options(true, true), 8, 300), regions);
  max_z(plain, light);
  max_z(plain, both);
  expect_means_agree(plain, light, 0.0, "guided light subpaths");
  expect_means_agree(plain, both, 0.0, "guided light and eye subpaths");
  // vcm learns from its merges too (what a light vertex brings to other
  // samples' pixels); guided and unguided carry the same merging bias.
  RenderOptions vcm_plain = options(false), vcm_guided = options(true);
  vcm_plain.integrator = vcm_guided.integrator = Integrator::Vcm;
  const RegionStats vcm = stats_of(render_runs(*scene, vcm_plain, 8, 400), regions);
  const RegionStats vcm_light = stats_of(render_runs(*scene, vcm_guided, 8, 500), regions);
  max_z(vcm, vcm_light);
  expect_means_agree(vcm, vcm_light, 0.0, "vcm, guided light subpaths");
  // The field was learnt and sampled: the same seed draws other paths.
  RenderOptions o = options(true), p = options(false);
  o.seed = p.seed = 5;
  o.collect_stats = true;
  const RenderResult r = render(*scene, o);
  EXPECT_GE(r.stats.guiding_iterations, 2u);
  EXPECT_GE(r.stats.guiding_light_leaves, 1u) << "the importance field is reported";
  EXPECT_NE(r.image.rgb, render(*scene, p).image.rgb);
}

TEST(LightGuiding, SameImageOnOneAndTwoThreads) {
  const auto scene = two_rooms();
  RenderOptions o = options(true, true);
  o.spp = 16;
  expect_thread_invariant(*scene, o, {"bdpt", "vcm"});
}

// A checkpoint carries the importance field: stopped inside the learning
// iterations and after them, on one and two threads in turn, the resumed
// render makes the straight render's image bit for bit. A checkpoint of
// eye guiding alone is not resumed with light subpaths guided (its
// settings say so before its field would).
TEST(LightGuiding, ResumesWithTheFieldItLearnt) {
  const auto scene = two_rooms();
  RenderOptions o = options(true);
  o.spp = 16;
  o.wave_size = 128;
  const RenderResult straight = render(*scene, o);
  const std::string checkpoint = ::testing::TempDir() + "/lantern_light_guided_resume.ckpt";
  int runs = 0;
  const RenderResult r = render_stopped_and_resumed(*scene, o, checkpoint, 7, 11, &runs);
  EXPECT_GE(runs, 4);
  EXPECT_EQ(0, std::memcmp(r.image.rgb.data(), straight.image.rgb.data(), r.image.rgb.size() * sizeof(float)));
  std::remove(checkpoint.c_str());

  RenderOptions eye = options(false, true);
  eye.spp = 8;
  eye.checkpoint_path = ::testing::TempDir() + "/lantern_eye_guided.ckpt";
  eye.keep_checkpoint = true;
  render(*scene, eye);
  RenderOptions both = eye;
  both.guide_light_subpaths = true;
  both.resume = true;
  try {
    render(*scene, both);
    ADD_FAILURE() << "an eye-guided checkpoint was resumed with light subpaths guided";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("guide-light"), std::string::npos) << e.what();
  }
  std::remove(eye.checkpoint_path.c_str());
}

TEST(LightGuiding, RefusesWhatItCannotDo) {
  const auto scene = two_rooms();
  for (Integrator other : {Integrator::Path, Integrator::Lt, Integrator::Bpm, Integrator::Ppm, Integrator::Mlt}) {
    RenderOptions o = options(true);
    o.integrator = other;
    EXPECT_THROW(render(*scene, o), std::invalid_argument) << name(other);
  }
  RenderOptions o = options(true);
  o.share_count = 2;
  o.film_path = "/tmp/never-written.film";
  EXPECT_THROW(render(*scene, o), std::invalid_argument);
  RenderHooks tickets;
  tickets.next_ticket = [] { return UINT64_MAX; };
  EXPECT_THROW(render(*scene, options(true), tickets), std::invalid_argument);
}
