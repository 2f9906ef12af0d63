// What the pbrt parser drives: one call per directive, in file order, with
// the parameters parsed and the transformations composed. The parser keeps
// the parsing state (the current transformation, named coordinate systems,
// the attribute stack, named materials) and knows nothing of what the
// target makes of a directive; SceneBuilder makes a Scene of them, and any
// other target (a converter, a test's recorder) can stand in its place.
#pragma once

#include <map>
#include <optional>
#include <string>

#include "lantern/error.h"
#include "material/material.h"
#include "math/common.h"
#include "scene/pbrt/params.h"

namespace lantern {

// The part of pbrt's graphics state that shapes and lights read.
struct GraphicsState {
  // pbrt's current transformation matrix, world from object, composed in
  // double precision so that a scene far from the origin keeps its detail.
  glm::dmat4 world_from_object{1.0};
  // The same at the end of the motion (pbrt's ActiveTransform EndTime): a
  // shape or instance whose two differ moves while the shutter is open.
  glm::dmat4 world_from_object_end{1.0};
  uint8_t active_transforms = 3;  // ActiveTransform: 1 StartTime, 2 EndTime, 3 All
  // Where shapes are stored: the render space (docs/scene-format.md, "Far
  // from the origin"), from the object; set by the parser before each use.
  glm::dmat4 render_from_object{1.0}, render_from_object_end{1.0};
  bool moving() const { return render_from_object != render_from_object_end; }
  bool reverse_orientation = false;
  std::optional<MaterialHandle> material;  // none yet: pbrt's default diffuse
  std::optional<pbrt::ParamSet> area_light;
  std::string area_light_dir;  // folder of the file that gave the AreaLightSource (for its "filename")
  // pbrt's current MediumInterface, by name ("" is vacuum), and where it was given.
  std::string inside_medium, outside_medium;
  SourceLocation medium_where;
  // pbrt-v4's ColorSpace: the space of the "rgb" values that follow (null:
  // sRGB, the default).
  const ColorSpace* color_space = nullptr;
  // pbrt-v4's Attribute: default parameters per kind ("shape", "light",
  // "material", "medium", "texture") for the directives that follow.
  std::map<std::string, std::vector<pbrt::Param>> attributes;
};

namespace pbrt {

class ParserTarget {
 public:
  virtual ~ParserTarget() = default;

  virtual void warn(const SourceLocation& where, const std::string& what) const = 0;
  virtual void warn_line(const std::string& line) const = 0;  // a whole "file:line:col: warning: ..." line
  // A parameter neither pbrt-v4 nor pbrt-v3 knows is a warning, not an
  // error (--lenient).
  virtual bool lenient() const { return false; }
  // An Include'd (or Import'ed) file of `bytes` is about to be parsed: what
  // a load of many files reports while it parses them.
  virtual void including(const std::string& path, size_t bytes) {}

  // Rendering options, before WorldBegin.
  // camera_from_world at the start and the end of the motion (equal for a
  // camera that stands still).
  virtual void camera(const std::string& type, const ParamSet& ps, const glm::dmat4& camera_from_world,
                      const glm::dmat4& camera_from_world_end) = 0;
  // The medium camera rays start in (the graphics state's outside medium).
  virtual void camera_medium(const std::string& name, const SourceLocation& where) = 0;
  virtual void film(const std::string& type, const ParamSet& ps) = 0;
  virtual void sampler(const std::string& type, const ParamSet& ps) = 0;
  virtual void integrator(const std::string& type, const ParamSet& ps) = 0;
  virtual void pixel_filter(const std::string& type, const ParamSet& ps) = 0;
  // At WorldBegin: everything from here on is given in render space;
  // transforms move from time transform_start to transform_end
  // (TransformTimes).
  virtual void begin_world(const glm::dmat4& render_from_world, double transform_start, double transform_end) = 0;

  // The world. named: the materials MakeNamedMaterial defined so far (for "mix").
  virtual MaterialHandle material(const std::string& type, const ParamSet& ps,
                                  const std::map<std::string, MaterialHandle>& named, const std::string& base_dir) = 0;
  virtual void texture(const std::string& name, const std::string& value_type, const std::string& cls,
                       const ParamSet& ps, const Mat4& ctm, const std::string& base_dir) = 0;
  virtual void shape(const std::string& type, const ParamSet& ps, const GraphicsState& gs,
                     const std::string& base_dir) = 0;
  // A LightSource; a point or spot light emits into the medium named
  // `medium` (the graphics state's outside medium).
  virtual void light(const std::string& type, const ParamSet& ps, const Mat4& ctm, const std::string& base_dir,
                     const std::string& medium, const SourceLocation& medium_where) = 0;
  virtual void medium(const std::string& name, const ParamSet& ps, const Mat4& render_from_medium,
                      const std::string& base_dir) = 0;
  // Object instancing: shapes between begin_object and end_object form a
  // prototype; object_instance places it with a transform.
  virtual void begin_object(const std::string& name, const SourceLocation& where) = 0;
  virtual void end_object(const SourceLocation& where) = 0;
  // world_from_object at the start and the end of the motion.
  virtual void object_instance(const std::string& name, const glm::dmat4& world_from_object,
                               const glm::dmat4& world_from_object_end, const SourceLocation& where) = 0;
};

}  // namespace pbrt
}  // namespace lantern
