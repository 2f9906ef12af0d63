// The directives that set up the render rather than the world: Film (its
// crop and its spectral buckets), Sampler, Integrator (and mlt's
// parameters) and PixelFilter, as pbrt-v4 names and defaults them.
#include <algorithm>
#include <cmath>
#include <iterator>

#include "sampler/sampler.h"
#include "scene/builder.h"

namespace lantern {

using pbrt::ParamSet;

void SceneBuilder::film(const std::string& type, const ParamSet& ps) {
  if (type != "rgb" && type != "gbuffer" && type != "spectral" && type != "image")
    warn(ps.where, "film type \"" + printable(type) + "\" is not supported; rendering an RGB film");
  SceneSettings& s = scene_.settings;
  s.width = ps.get_int("xresolution", 1280);
  s.height = ps.get_int("yresolution", 720);
  if (s.width <= 0 || s.height <= 0 || s.width > 65536 || s.height > 65536)
    ps.fail("resolution must be between 1 and 65536 pixels per side");
  s.output = ps.get_string("filename", "pbrt.exr");
  // The sensor (color/sensor.h). pbrt-v4's other sensors are measured
  // cameras' curves, which Lantern does not have.
  s.iso = ps.get_float("iso", 100.f);
  if (!(s.iso > 0.f) || !std::isfinite(s.iso)) ps.fail(*ps.find("iso"), "\"iso\" must be a finite number > 0");
  s.whitebalance = ps.get_float("whitebalance", 0.f);
  if (!(s.whitebalance >= 0.f) || !std::isfinite(s.whitebalance))
    ps.fail(*ps.find("whitebalance"), "\"whitebalance\" must be a temperature in kelvin, or 0 for none");
  s.color_space = ps.color_space ? std::string(ps.color_space->name) : "srgb";
  // pbrt-v3's "scale" and "maxsampleluminance" are pbrt-v4's iso / 100 and
  // "maxcomponentvalue", as pbrt-v4's upgrade converts them.
  if (!ps.find("iso") && ps.find("scale")) {
    s.iso = 100.f * ps.get_float("scale", 1.f);
    if (!(s.iso > 0.f) || !std::isfinite(s.iso)) ps.fail(*ps.find("scale"), "\"scale\" must be a finite number > 0");
  }
  const char* max_name = !ps.find("maxcomponentvalue") && ps.find("maxsampleluminance") ? "maxsampleluminance"
                                                                                        : "maxcomponentvalue";
  s.max_component_value = ps.get_float(max_name, std::numeric_limits<float>::infinity());
  if (!(s.max_component_value > 0.f))
    ps.fail(*ps.find(max_name), "\"" + std::string(max_name) + "\" must be a number > 0 (the largest sensor RGB "
                                "component a sample keeps)");
  // The sensor's diagonal in mm: the realistic camera's film size.
  const float diagonal = ps.get_float("diagonal", 35.f);
  if (!(diagonal > 0.f) || !std::isfinite(diagonal)) ps.fail(*ps.find("diagonal"), "\"diagonal\" must be a length in mm > 0");
  scene_.camera.film_diagonal = 0.001f * diagonal;
  s.save_fp16 = ps.get_bool("savefp16", false);
  s.gbuffer = type == "gbuffer";
  if (s.gbuffer) {
    const std::string space = ps.get_string("coordinatesystem", "camera");
    if (space != "camera" && space != "world")
      ps.fail(*ps.find("coordinatesystem"),
              "\"coordinatesystem\" \"" + printable(space) + "\" is not known; expected \"camera\" or \"world\"");
    s.gbuffer_world = space == "world";
  }
  if (type == "spectral") spectral_film(ps);
  crop(ps);
  camera_sensor(ps);
}

// pbrt-v4's measured camera sensors (its named spectra) are curves Lantern
// does not have. A scene that names one renders with the CIE 1931 observer
// balanced as pbrt-v4 balances a camera by default, from 6500 K: pbrt-v4
// fits each camera's response to the observer's, so greys agree within 1%
// and saturated colours by a few hundredths (docs/scene-format.md).
void SceneBuilder::camera_sensor(const ParamSet& ps) {
  static const char* const kCameras[] = {
      "canon_eos_100d", "canon_eos_1dx_mkii", "canon_eos_200d", "canon_eos_200d_mkii", "canon_eos_5d",
      "canon_eos_5d_mkii", "canon_eos_5d_mkiii", "canon_eos_5d_mkiv", "canon_eos_5ds", "canon_eos_m",
      "hasselblad_l1d_20c", "nikon_d810", "nikon_d850", "sony_ilce_6400", "sony_ilce_7m3", "sony_ilce_7rm3",
      "sony_ilce_9"};
  const std::string sensor = ps.get_string("sensor", "cie1931");
  if (sensor == "cie1931") return;
  if (std::find(std::begin(kCameras), std::end(kCameras), sensor) == std::end(kCameras))
    ps.fail(*ps.find("sensor"), "sensor \"" + printable(sensor) + "\" is not known; expected \"cie1931\" (the CIE 1931 "
                                "observer, pbrt-v4's default) or one of pbrt-v4's cameras, such as \"canon_eos_5d_mkiv\"");
  warn(ps.find("sensor")->where, "sensor \"" + sensor + "\": this camera's measured curves are not available; rendering "
                                 "with the CIE 1931 observer" +
                                     std::string(scene_.settings.whitebalance == 0.f ? ", white-balanced from 6500 K as "
                                                                                       "pbrt-v4 balances a camera"
                                                                                     : "") +
                                     " (greys within 1% of pbrt-v4's image, saturated colours a few hundredths apart)");
  if (scene_.settings.whitebalance == 0.f) scene_.settings.whitebalance = 6500.f;
}

// pbrt-v4's Film "spectral": its buckets over its wavelength range, which
// lies within the visible range pbrt-v4 samples (it stops beyond it).
void SceneBuilder::spectral_film(const ParamSet& ps) {
  SceneSettings& s = scene_.settings;
  s.spectral_buckets = ps.get_int("nbuckets", 16);
  if (s.spectral_buckets < 1 || s.spectral_buckets > 4096)
    ps.fail(*ps.find("nbuckets"), "\"nbuckets\" must be between 1 and 4096");
  s.spectral_lambda_min = ps.get_float("lambdamin", 360.f);
  s.spectral_lambda_max = ps.get_float("lambdamax", 830.f);
  if (!(s.spectral_lambda_min >= 360.f && s.spectral_lambda_max <= 830.f &&
        s.spectral_lambda_min < s.spectral_lambda_max)) {
    const auto* p = ps.find("lambdamin") ? ps.find("lambdamin") : ps.find("lambdamax");
    ps.fail(*p, "\"lambdamin\" and \"lambdamax\" must lie in [360, 830] nm, lambdamin below lambdamax");
  }
}

// pbrt-v4's crop: "cropwindow" [x0 x1 y0 y1] in [0, 1] (each pair put in
// order and clamped, as pbrt-v4 does) or "pixelbounds" [x0 x1 y0 y1] in
// pixels; the pixels they cover are decided at render time, for the
// render's resolution (integrator/render_settings.h).
void SceneBuilder::crop(const ParamSet& ps) {
  SceneSettings& s = scene_.settings;
  const std::vector<float> cw = ps.get_floats("cropwindow");
  const std::vector<int> pb = ps.get_ints("pixelbounds");
  if (!cw.empty() && !pb.empty())
    ps.fail(*ps.find("pixelbounds"), "give \"cropwindow\" or \"pixelbounds\", not both");
  if (!cw.empty()) {
    if (cw.size() != 4) ps.fail(*ps.find("cropwindow"), "expected four values: x0 x1 y0 y1, each in [0, 1]");
    for (float v : cw)
      if (!std::isfinite(v)) ps.fail(*ps.find("cropwindow"), "expected finite values in [0, 1]");
    for (size_t k = 0; k < 4; k += 2) {
      s.crop_window[k] = std::clamp(std::min(cw[k], cw[k + 1]), 0.f, 1.f);
      s.crop_window[k + 1] = std::clamp(std::max(cw[k], cw[k + 1]), 0.f, 1.f);
    }
  }
  if (!pb.empty()) {
    if (pb.size() != 4 || pb[0] < 0 || pb[2] < 0 || pb[1] <= pb[0] || pb[3] <= pb[2])
      ps.fail(*ps.find("pixelbounds"), "expected four integers x0 x1 y0 y1 with 0 <= x0 < x1 and 0 <= y0 < y1");
    std::copy(pb.begin(), pb.end(), s.pixel_bounds.begin());
  }
}

// pbrt-v4's samplers, parameters and defaults (docs/samplers.md).
void SceneBuilder::sampler(const std::string& type, const ParamSet& ps) {
  SamplerSettings& s = scene_.settings.sampler;
  s = SamplerSettings{};
  // pbrt-v3's names, as pbrt-v4's upgrade maps them.
  if (type == "lowdiscrepancy" || type == "02sequence") return sampler("paddedsobol", ps);
  if (type == "maxmindist") return sampler("pmj02bn", ps);
  if (type == "random") return sampler("independent", ps);
  if (type == "pmj02bn") {
    // Its point tables come from an optimisation Lantern does not run; the
    // pattern changes noise, not the expected image.
    warn(ps.where, "sampler \"pmj02bn\" is not available; using \"zsobol\" (the same image, different noise)");
    s.type = SamplerKind::ZSobol;
  } else {
    try {
      s.type = parse_sampler(type);
    } catch (const std::invalid_argument& e) {
      ps.fail(e.what());
    }
  }
  int spp = ps.get_int("pixelsamples", 16);
  if (type == "stratified") {
    s.jitter = ps.get_bool("jitter", true);
    s.xsamples = ps.get_int("xsamples", 4);
    s.ysamples = ps.get_int("ysamples", 4);
    if (s.xsamples <= 0 || s.ysamples <= 0 || s.xsamples > 4096 || s.ysamples > 4096)
      ps.fail("\"xsamples\" and \"ysamples\" must lie in [1, 4096]");
    spp = s.xsamples * s.ysamples;
  }
  if (spp <= 0) ps.fail("\"pixelsamples\" must be positive");
  scene_.settings.spp = spp;
  s.seed = uint64_t(int64_t(ps.get_int("seed", 0)));
  if (const pbrt::Param* r = ps.find("randomization")) {
    std::string name = ps.get_string("randomization", "");
    try {
      parse_randomization(name);
    } catch (const std::invalid_argument& e) {
      ps.fail(*r, e.what());
    }
    s.randomization = name;
  }
}

// pbrt-v4's mlt parameters, with its defaults and ranges.
void SceneBuilder::mlt_parameters(const ParamSet& ps) {
  SceneSettings& st = scene_.settings;
  auto positive = [&](const char* name, int def, int* out) {
    const int v = ps.get_int(name, def);
    if (v <= 0) ps.fail(*ps.find(name), "\"" + std::string(name) + "\" must be positive");
    *out = v;
  };
  positive("mutationsperpixel", 100, &st.mlt_mutations_per_pixel);
  positive("chains", 1000, &st.mlt_chains);
  positive("bootstrapsamples", 100000, &st.mlt_bootstrap_samples);
  st.mlt_large_step_probability = ps.get_float("largestepprobability", 0.3f);
  if (!(st.mlt_large_step_probability >= 0.f && st.mlt_large_step_probability <= 1.f))
    ps.fail(*ps.find("largestepprobability"), "\"largestepprobability\" must lie in [0, 1]");
  st.mlt_sigma = ps.get_float("sigma", 0.01f);
  if (!(st.mlt_sigma > 0.f) || !std::isfinite(st.mlt_sigma)) ps.fail(*ps.find("sigma"), "\"sigma\" must be a positive number");
}

void SceneBuilder::integrator(const std::string& type, const ParamSet& ps) {
  int maxdepth = ps.get_int("maxdepth", 5);
  if (maxdepth < 0) ps.fail("\"maxdepth\" must be >= 0");
  scene_.settings.maxdepth = maxdepth;
  if (type == "path" || type == "bdpt") {
    scene_.settings.integrator = parse_integrator(type);
  } else if (type == "lightpath") {
    scene_.settings.integrator = Integrator::Lt;
  } else if (type == "directlighting") {  // pbrt-v3
    scene_.settings.integrator = Integrator::Direct;
    // "all" lights at each vertex or "one" chosen: the same image, different
    // noise; Lantern's light sampler chooses one.
    const std::string strategy = ps.get_string("strategy", "all");
    if (strategy != "all" && strategy != "one")
      ps.fail(*ps.find("strategy"), "\"strategy\" must be \"all\" or \"one\", not \"" + printable(strategy) + "\"");
  } else if (type == "ambientocclusion") {
    scene_.settings.integrator = Integrator::AmbientOcclusion;
    scene_.settings.ao_cos_sample = ps.get_bool("cossample", true);
    if (const pbrt::Param* d = ps.find("maxdistance")) {
      const float dist = ps.get_float("maxdistance", 0.f);
      if (!(dist > 0.f)) ps.fail(*d, "\"maxdistance\" must be positive");
      scene_.settings.ao_max_distance = dist;
    }
  } else if (type == "mlt") {
    scene_.settings.integrator = Integrator::Mlt;
    mlt_parameters(ps);
  } else if (type == "volpath") {  // pbrt's path tracer with media: Lantern's path tracer has them
    scene_.settings.integrator = Integrator::Path;
  } else if (type == "sppm") {
    // Stochastic progressive photon mapping converges to the same image as
    // vertex connection and merging, which also merges photons.
    // Its "radius" is the first merging radius, as in pbrt-v4; left out,
    // Lantern's automatic one (pbrt-v4's default of 1 does not scale with
    // the scene). Its "seed" changes only the noise.
    scene_.settings.integrator = Integrator::Vcm;
    if (const pbrt::Param* r = ps.find("radius")) {
      const float radius = ps.get_float("radius", 0.f);
      if (!(radius > 0.f) || !std::isfinite(radius)) ps.fail(*r, "\"radius\" must be a positive number");
      scene_.settings.merge_radius = radius;
    }
    // Its "photonsperiteration" is how many light subpaths each eye vertex
    // merges with in a pass (a wave's: --wave-size), pbrt-v4's default of
    // -1 a pass's pixels.
    scene_.settings.photons_per_iteration = -1;
    if (const pbrt::Param* n = ps.find("photonsperiteration")) {
      const int photons = ps.get_int("photonsperiteration", -1);
      if (photons == 0 || photons < -1)
        ps.fail(*n, "\"photonsperiteration\" must be a positive number of light paths, or -1 for the image's pixels");
      scene_.settings.photons_per_iteration = photons;
    }
    ps.find("seed");
  } else {
    warn(ps.where, "integrator \"" + printable(type) + "\" is not available; using \"path\" (choose with --integrator)");
    scene_.settings.integrator = Integrator::Path;
  }
  std::string light_sampler = ps.get_string("lightsampler", "bvh");
  if (light_sampler == "exhaustive") {
    // pbrt-v4's exhaustive sampler weighs every light at every point: the
    // same image as the BVH's, at a cost linear in the number of lights.
    warn(ps.where, "light sampler \"exhaustive\" is not available; using \"bvh\" (the same image, different noise)");
    light_sampler = "bvh";
  }
  if (light_sampler != "bvh" && light_sampler != "power" && light_sampler != "uniform")
    ps.fail(*ps.find("lightsampler"), "unknown light sampler \"" + printable(light_sampler) +
                                          "\" (expected bvh, power, uniform or exhaustive)");
  scene_.settings.light_sampler = parse_light_sampler(light_sampler);
  for (const char* p : {"regularize", "visualizestrategies", "visualizeweights"})
    ps.find(p);  // affect noise or debug output only
}

void SceneBuilder::pixel_filter(const std::string& type, const ParamSet& ps) {
  using T = PixelFilter::Type;
  struct Kind {
    const char* name;
    T type;
    float radius;  // pbrt-v4's default
  };
  static constexpr Kind kKinds[] = {
      {"box", T::Box, 0.5f}, {"triangle", T::Triangle, 2.f}, {"gaussian", T::Gaussian, 1.5f},
      {"mitchell", T::Mitchell, 2.f}, {"sinc", T::Sinc, 4.f}};
  PixelFilter& f = scene_.filter;
  const Kind* kind = std::find_if(std::begin(kKinds), std::end(kKinds), [&](const Kind& k) { return type == k.name; });
  if (kind == std::end(kKinds)) {
    warn(ps.where, "pixel filter \"" + printable(type) + "\" is not supported; using a gaussian of radius 1.5");
    for (const char* p : {"B", "C", "tau", "xradius", "yradius"}) ps.find(p);
    f.type = T::Gaussian;
    f.radius = Vec2(1.5f);
  } else {
    f.type = kind->type;
    // pbrt-v3's "xwidth", "ywidth" and a gaussian's "alpha" (exp(-alpha
    // x^2)) are pbrt-v4's radii and sigma = 1 / sqrt(2 alpha), as pbrt-v4's
    // upgrade converts them.
    const char* xr = !ps.find("xradius") && ps.find("xwidth") ? "xwidth" : "xradius";
    const char* yr = !ps.find("yradius") && ps.find("ywidth") ? "ywidth" : "yradius";
    f.radius = Vec2(ps.get_float(xr, kind->radius), ps.get_float(yr, kind->radius));
    if (!(f.radius.x > 0.f && f.radius.y > 0.f) || !std::isfinite(f.radius.x) || !std::isfinite(f.radius.y))
      ps.fail("filter radii must be positive");
    if (f.type == T::Gaussian) {
      f.sigma = ps.get_float("sigma", 0.5f);
      if (!ps.find("sigma") && ps.find("alpha")) {
        const float alpha = ps.get_float("alpha", 2.f);
        if (!(alpha > 0.f) || !std::isfinite(alpha)) ps.fail(*ps.find("alpha"), "\"alpha\" must be a number > 0");
        f.sigma = 1.f / std::sqrt(2.f * alpha);
      }
    }
  }
  bool normalises = true;
  if (f.type == T::Mitchell) {
    const double B = ps.get_float("B", 1.f / 3.f), C = ps.get_float("C", 1.f / 3.f);
    if (!std::isfinite(B) || !std::isfinite(C)) ps.fail("\"B\" and \"C\" must be finite");
    normalises = make_mitchell_filter(f, B, C);
  } else if (f.type == T::Sinc) {
    const double tau = ps.get_float("tau", 3.f);
    if (!(tau > 0.0) || !std::isfinite(tau)) ps.fail("\"tau\" must be positive");
    normalises = make_sinc_filter(f, tau);
  }
  if (!normalises) ps.fail("this filter's weights sum to zero or less over its radius");
  if (f.type == T::Gaussian) {
    if (!(f.sigma > 0.f) || !std::isfinite(f.sigma)) ps.fail("\"sigma\" must be positive");
    for (int axis = 0; axis < 2; ++axis) f.gaussian[axis] = GaussianFilterTable(f.radius[axis], f.sigma);
  }
}

}  // namespace lantern
