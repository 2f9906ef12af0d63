// The Camera directive: pbrt-v4's perspective, orthographic, spherical
// and realistic cameras (camera/camera.h, camera/lens_system.h).
#include <filesystem>

#include "scene/builder.h"
#include "texture/image.h"

namespace lantern {

using pbrt::ParamSet;

void SceneBuilder::camera(const std::string& type, const ParamSet& ps, const glm::dmat4& camera_from_world,
                          const glm::dmat4& camera_from_world_end) {
  CameraDesc& c = scene_.camera;
  if (type == "perspective") {
    c.projection = Projection::Perspective;
  } else if (type == "orthographic") {
    c.projection = Projection::Orthographic;
  } else if (type == "spherical" || type == "environment") {
    // (pbrt-v3's "environment" is pbrt-v4's spherical camera in the
    // equirectangular mapping, as pbrt-v4's upgrade writes it)
    c.projection = Projection::Spherical;
    scene_.settings.screen_window = true;  // the whole sphere, whatever the image's shape
    std::string mapping = ps.get_string("mapping", type == "environment" ? "equirectangular" : "equalarea");
    if (mapping != "equalarea" && mapping != "equirectangular")
      ps.fail(*ps.find("mapping"), "spherical \"mapping\" \"" + printable(mapping) +
                                       "\" is not known; expected \"equalarea\" or \"equirectangular\"");
    c.equal_area = mapping == "equalarea";
  } else if (type == "realistic") {
    realistic_camera(ps);
  } else {
    ps.fail("camera type \"" + printable(type) +
            "\" is not supported; expected perspective, orthographic, spherical, realistic or environment");
  }
  world_from_camera_ = glm::inverse(camera_from_world);
  world_from_camera_end_ = glm::inverse(camera_from_world_end);
  c.world_from_camera = Mat4(world_from_camera_);
  if (c.projection == Projection::Perspective) {
    c.fov_degrees = ps.get_float("fov", 90.f);
    if (!(c.fov_degrees > 0.f && c.fov_degrees < 180.f)) ps.fail("\"fov\" must lie strictly between 0 and 180 degrees");
  }
  if (c.projection != Projection::Spherical && c.projection != Projection::Realistic) {
    c.lens_radius = ps.get_float("lensradius", 0.f);
    c.focal_distance = ps.get_float("focaldistance", 1e6f);
    if (!(c.lens_radius >= 0.f) || !std::isfinite(c.lens_radius) || !(c.focal_distance > 0.f))
      ps.fail("\"lensradius\" must be >= 0 and \"focaldistance\" > 0");
  }
  // The shutter's interval scales the image (pbrt-v4's imaging ratio,
  // color/sensor.h) and is the time over which what moves blurs.
  const float open = ps.get_float("shutteropen", 0.f), close = ps.get_float("shutterclose", 1.f);
  scene_.settings.exposure_time = close - open;
  c.shutter.open = open;
  c.shutter.close = close;
  if (!(close > open) || !std::isfinite(close - open))
    ps.fail("\"shutterclose\" (" + std::to_string(close) + ") must come after \"shutteropen\" (" +
            std::to_string(open) + "): a shutter that never opens makes a black image");
  std::vector<float> sw = ps.get_floats("screenwindow");
  if (!sw.empty()) {
    if (sw.size() != 4) ps.fail("\"screenwindow\" needs 4 values: xmin xmax ymin ymax");
    c.has_screen_window = true;
    scene_.settings.screen_window = true;
    std::copy(sw.begin(), sw.end(), c.screen_window);
  }
  // pbrt-v4's "frameaspectratio": the screen window of a frame of that
  // shape (its shorter side from -1 to 1, where the fov applies) instead of
  // the image's; a "screenwindow" wins. The spherical camera reads it and,
  // as in pbrt-v4, nothing changes.
  if (const pbrt::Param* f = ps.find("frameaspectratio")) {
    const float frame = ps.get_float("frameaspectratio", 1.f);
    if (!(frame > 0.f) || !std::isfinite(frame)) ps.fail(*f, "\"frameaspectratio\" must be a positive number");
    if (sw.empty() && (c.projection == Projection::Perspective || c.projection == Projection::Orthographic)) {
      const float window[4] = {frame > 1.f ? -frame : -1.f, frame > 1.f ? frame : 1.f, frame > 1.f ? -1.f : -1.f / frame,
                               frame > 1.f ? 1.f : 1.f / frame};
      std::copy(window, window + 4, c.screen_window);
      c.has_screen_window = true;
      scene_.settings.screen_window = true;
    }
  }
}

// pbrt-v4's realistic camera: "lensfile" (relative to the scene's
// folder), "aperturediameter" (mm, 1 by default: the stop's own diameter
// when that is smaller), "focusdistance" (10); the Film's "diagonal" sizes
// the film. Focusing waits for the film (camera/camera.cpp).
void SceneBuilder::realistic_camera(const ParamSet& ps) {
  CameraDesc& c = scene_.camera;
  camera_where_ = ps.find("focusdistance") ? ps.find("focusdistance")->where : ps.where;
  c.projection = Projection::Realistic;
  const std::string file = ps.get_string("lensfile", "");
  if (file.empty()) ps.fail("the realistic camera needs a \"lensfile\" (its lens elements, four numbers each)");
  const float aperture = ps.get_float("aperturediameter", 1.f);
  if (!(aperture > 0.f) || !std::isfinite(aperture))
    ps.fail(*ps.find("aperturediameter"), "\"aperturediameter\" must be a diameter in mm > 0");
  c.focus_distance = ps.get_float("focusdistance", 10.f);
  if (!(c.focus_distance > 0.f) || !std::isfinite(c.focus_distance))
    ps.fail(*ps.find("focusdistance"), "\"focusdistance\" must be a distance > 0");
  const std::filesystem::path path = std::filesystem::path(file).is_absolute()
                                         ? std::filesystem::path(file)
                                         : std::filesystem::path(ps.base_dir) / file;
  LensSystem lens;
  try {
    lens = LensSystem(read_lens_file(path.string()), aperture);
  } catch (const std::exception& e) {
    ps.fail(*ps.find("lensfile"), e.what());
  }
  if (std::optional<ApertureMask> mask = aperture_mask(ps)) lens.set_aperture(std::move(*mask));
  c.lens = std::make_shared<const LensSystem>(std::move(lens));
}

// pbrt-v4's "aperture": a built-in shape's name, or an image (relative to
// the scene's folder; 8-bit files decoded as pbrt-v4 decodes them, colour
// averaged) whose top row lies towards +y on the stop.
std::optional<ApertureMask> SceneBuilder::aperture_mask(const ParamSet& ps) {
  const pbrt::Param* p = ps.find("aperture");
  const std::string name = ps.get_string("aperture", "");
  if (!p || name.empty()) return std::nullopt;
  if (std::optional<ApertureMask> m = builtin_aperture(name)) return m;
  try {
    const TextureImage img = load_texture_image(resolve_path(ps.base_dir, name), ColorEncoding{ColorEncoding::SRGB});
    std::vector<float> v(size_t(img.width) * size_t(img.height));
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x) {
        const RGB& t = img.texels[size_t(img.height - 1 - y) * size_t(img.width) + size_t(x)];
        v[size_t(y) * size_t(img.width) + size_t(x)] = (t[0] + t[1] + t[2]) / 3.f;
      }
    return ApertureMask(img.width, img.height, std::move(v));
  } catch (const std::exception& e) {
    ps.fail(*p, std::string(e.what()) + " (\"aperture\" is an image file or one of gaussian, square, pentagon, star)");
  }
}

// A realistic camera's lens must focus at its distance for the Film's
// diagonal (known only once both are read): checked at load, so that the
// error names the Camera's line rather than coming from the render.
void SceneBuilder::check_lens_focus() const {
  const CameraDesc& c = scene_.camera;
  if (c.projection != Projection::Realistic) return;
  try {
    LensSystem lens = *c.lens;
    lens.focus(c.focus_distance, 0.001f * c.film_diagonal);
  } catch (const std::exception& e) {
    throw InputError(camera_where_, std::string("Camera \"realistic\": ") + e.what());
  }
}

}  // namespace lantern
