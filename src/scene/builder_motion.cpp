// Motion blur in the scene (docs/motion-blur.md): instances that move
// while the shutter is open, and moving shapes, which become instances.
#include <glm/gtc/matrix_inverse.hpp>

#include "scene/builder.h"

namespace lantern {

using pbrt::ParamSet;

// As pbrt-v4 builds a moving shape: the shape in its own space, placed by
// a transform that moves. Here the shape becomes a prototype of its own
// and the transform an Embree instance with motion steps.
void SceneBuilder::moving_shape(const std::string& type, const ParamSet& ps, const GraphicsState& gs,
                                const std::string& base_dir) {
  if (object_)
    ps.fail("a moving shape inside ObjectBegin \"" + printable(object_->name) +
            "\" is not supported (instances cannot nest); move its ObjectInstance instead");
  if (gs.area_light) ps.fail("a moving area light is not supported (nor in pbrt-v4): give the emitting shape one transform");
  const uint32_t prototype = uint32_t(scene_.shapes.prototypes.size());
  scene_.shapes.prototypes.push_back({});
  object_ = OpenObject{"", prototype};
  GraphicsState still = gs;
  still.render_from_object = still.render_from_object_end = glm::dmat4(1.0);
  try {
    shape(type, ps, still, base_dir);
  } catch (...) {
    object_.reset();
    throw;
  }
  object_.reset();
  if (scene_.shapes.prototypes[prototype].count == 0) return;  // nothing to trace (an empty PLY)
  place_instance(prototype, gs.render_from_object, gs.render_from_object_end, nullptr, ps.where);
}

void SceneBuilder::object_instance(const std::string& name, const glm::dmat4& world_from_object,
                                   const glm::dmat4& world_from_object_end, const SourceLocation& where) {
  if (object_)
    throw InputError(where, "ObjectInstance inside ObjectBegin \"" + printable(object_->name) +
                                "\": nested instancing is not supported (nor is it in pbrt-v4)");
  auto it = objects_.find(name);
  if (it == objects_.end())
    throw InputError(where, "ObjectInstance \"" + printable(name) + "\": no object of that name was defined with ObjectBegin");
  if (scene_.shapes.prototypes[it->second].count == 0) return;  // an empty object: nothing to trace
  place_instance(it->second, world_from_object, world_from_object_end, &name, where);
}

void SceneBuilder::place_instance(uint32_t prototype, const glm::dmat4& m0, const glm::dmat4& m1,
                                  const std::string* name, const SourceLocation& where) {
  auto what = [&] { return name ? "ObjectInstance \"" + printable(*name) + "\"" : std::string("a moving shape"); };
  for (const glm::dmat4* m : {&m0, &m1}) {
    const Mat4 M(*m);
    for (int c = 0; c < 4; ++c)
      if (!is_finite(Vec3(M[c])) || !std::isfinite(M[c][3])) throw InputError(where, what() + ": the transform is not finite");
    if (std::fabs(glm::determinant(glm::mat3(M))) < 1e-30f) throw InputError(where, what() + ": the transform is singular");
  }
  ShapePools& s = scene_.shapes;
  // (as pbrt-v4: a motion too small to change a float is no motion)
  if (Mat4(m0) == Mat4(m1)) {
    s.instances.push_back(Placement::of(prototype, Mat4(m0)));
    return;
  }
  s.motions.push_back(motion_path(m0, m1));
  s.instances.push_back(Placement::of(prototype, s.motions.back().steps.front(), uint32_t(s.motions.size() - 1)));
}

}  // namespace lantern
