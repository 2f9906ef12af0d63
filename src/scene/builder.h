// Turns parsed pbrt directives into entities and component pools.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include "color/rgb_spectrum_fit.h"
#include "material/subsurface_albedo.h"
#include "scene/pbrt/params.h"
#include "scene/pbrt/parser_target.h"
#include "scene/scene.h"

namespace lantern {

// file, relative to the including scene file's folder unless absolute.
struct PlyMesh;  // scene/ply.h
// A PLY mesh's quads as a patch set when any of them is not a
// parallelogram (its triangles then become patches that collapse an edge,
// which are exactly those triangles), as pbrt-v4 traces PLY quads;
// nothing when the mesh can stay triangles (builder_patches.cpp).
std::optional<BilinearPatchSet> ply_patches(const PlyMesh& ply);
// Carries a patch set into render space and checks it (builder_patches.cpp).
void prepare_patches(BilinearPatchSet& s, const Mat4& render_from_object, bool reverse_orientation,
                     const pbrt::ParamSet& ps, const std::string& source);
std::string resolve_path(const std::string& base_dir, const std::string& file);

// A tabulated BSDF named by the file parameter `param` (relative to the
// scene's file), read by `load` (which throws with the file's problem) the
// first time any material names it; `owners` keeps what was read, `loaded`
// finds it again by path. `needs` says what the material wants when the
// parameter is missing.
template <class Table, class Load>
const Table* tabulated_bsdf_file(const pbrt::ParamSet& ps, const char* param, const char* needs,
                                 std::map<std::string, const Table*>& loaded,
                                 std::vector<std::shared_ptr<const Table>>& owners, Load&& load) {
  const std::string file = ps.get_string(param, "");
  if (file.empty()) ps.fail(needs);
  const std::string path = resolve_path(ps.base_dir, file);
  if (auto it = loaded.find(path); it != loaded.end()) return it->second;
  try {
    owners.push_back(load(path));
  } catch (const std::exception& e) {
    ps.fail(*ps.find(param), e.what());
  }
  return loaded[path] = owners.back().get();
}

// A light's "scale": a float (pbrt-v4) or a colour (pbrt-v3).
RGB light_scale(const pbrt::ParamSet& ps);

// Turns the parser's directives into entities and component pools.
class SceneBuilder final : public pbrt::ParserTarget {
 public:
  SceneBuilder(Scene& scene, WarningSink warn, std::function<void(const std::string&)> progress = nullptr)
      : scene_(scene), warn_(std::move(warn)), progress_(std::move(progress)) {}

  void warn(const SourceLocation& where, const std::string& what) const override;
  void set_texture_cache(const TextureCacheSettings& s) { texture_cache_ = s; }
  void set_lenient(bool lenient) { lenient_ = lenient; }
  void set_memory_layout(MemoryLayout l) { memory_layout_ = l; }
  void set_file_progress(std::function<void(const std::string&, size_t)> f) { file_progress_ = std::move(f); }
  void including(const std::string& path, size_t bytes) override {
    if (file_progress_) file_progress_(path, bytes);
  }
  bool lenient() const override { return lenient_; }
  void warn_line(const std::string& line) const override {
    if (warn_) warn_(line);
  }

  // The directives (pbrt/parser_target.h).
  void camera(const std::string& type, const pbrt::ParamSet& ps, const glm::dmat4& camera_from_world,
              const glm::dmat4& camera_from_world_end) override;
  void begin_world(const glm::dmat4& render_from_world, double transform_start, double transform_end) override;
  void film(const std::string& type, const pbrt::ParamSet& ps) override;
  void sampler(const std::string& type, const pbrt::ParamSet& ps) override;
  void integrator(const std::string& type, const pbrt::ParamSet& ps) override;
  void pixel_filter(const std::string& type, const pbrt::ParamSet& ps) override;
  MaterialHandle material(const std::string& type, const pbrt::ParamSet& ps,
                          const std::map<std::string, MaterialHandle>& named, const std::string& base_dir) override;
  void texture(const std::string& name, const std::string& value_type, const std::string& cls, const pbrt::ParamSet& ps,
               const Mat4& ctm, const std::string& base_dir) override;
  void shape(const std::string& type, const pbrt::ParamSet& ps, const GraphicsState& gs,
             const std::string& base_dir) override;
  void light(const std::string& type, const pbrt::ParamSet& ps, const Mat4& ctm, const std::string& base_dir,
             const std::string& medium, const SourceLocation& medium_where) override;
  // Participating media (builder_media.cpp): MakeNamedMedium, and the
  // medium named by the graphics state when the camera was declared.
  void medium(const std::string& name, const pbrt::ParamSet& ps, const Mat4& render_from_medium,
              const std::string& base_dir) override;
  void camera_medium(const std::string& name, const SourceLocation& where) override;
  void begin_object(const std::string& name, const SourceLocation& where) override;
  void end_object(const SourceLocation& where) override;
  void object_instance(const std::string& name, const glm::dmat4& world_from_object,
                       const glm::dmat4& world_from_object_end, const SourceLocation& where) override;

  // Builds the acceleration structure and light tables.
  void finish();

 private:
  void mlt_parameters(const pbrt::ParamSet& ps);  // an "mlt" Integrator's
  // The media of the point and spot lights added since the given pool
  // sizes: the medium named `name` (builder_media.cpp).
  void assign_light_media(size_t points, size_t spots, size_t at_infinity, const std::string& name,
                          const SourceLocation& where);
  // Motion blur (builder_motion.cpp): a moving shape becomes a prototype
  // of its own placed by a moving instance; an instance is checked and
  // placed, moving when its two transforms differ.
  void moving_shape(const std::string& type, const pbrt::ParamSet& ps, const GraphicsState& gs,
                    const std::string& base_dir);
  // `name`: the object's, or null for a moving shape (named only in an
  // error message, built only then: millions of placements).
  void place_instance(uint32_t prototype, const glm::dmat4& m0, const glm::dmat4& m1, const std::string* name,
                      const SourceLocation& where);
  void add_light(const std::string& type, const pbrt::ParamSet& ps, const Mat4& ctm, const std::string& base_dir);
  // A material or texture parameter that may name a texture (builder_textures.cpp).
  RGBTextureRef conductor_param(const pbrt::ParamSet& ps, const std::string& name, const std::string& def);
  // A spectrum kept for the spectral renderer (TexturePools::spectra).
  int32_t add_spectrum(const PiecewiseLinearSpectrum& s);
  // A colour of a space other than sRGB as the spectrum that space's own
  // table would give it (builder_textures.cpp); -1 where there is none.
  int32_t color_space_spectrum(const pbrt::ParamSet& ps, const pbrt::Param& p, pbrt::ColorUsage usage);
  // The same as a shape and scale: nullopt for an sRGB colour, or none.
  std::optional<UnboundedSpectrum> color_space_shape(const pbrt::ParamSet& ps, const pbrt::Param& p,
                                                     pbrt::ColorUsage usage);
  // A medium's sigma_a and sigma_s of another space likewise, times scale
  // (builder_media.cpp); `given` false where both are sRGB's.
  CoefficientSpectra coefficient_spectra(const pbrt::ParamSet& ps, RGB sigma_a, RGB sigma_s, float scale);
  // An emitter's colour of such a space likewise (builder_lights.cpp).
  std::optional<PiecewiseLinearSpectrum> color_space_emission(const pbrt::ParamSet& ps, const std::string& name);
  // The table of a space other than sRGB, fitted where looked up.
  LazyRGBToSpectrumTable& color_space_table(const ColorSpace& cs);
  RGBTextureRef rgb_texture(const pbrt::ParamSet& ps, const std::string& name, RGB def,
                            pbrt::ColorUsage usage = pbrt::ColorUsage::Reflectance);
  FloatTextureRef float_texture(const pbrt::ParamSet& ps, const std::string& name, float def);
  TextureMapping texture_mapping(const pbrt::ParamSet& ps, const Mat4& ctm, bool two_d);
  // The image at path, read once per encoding; errors name parameter `param`.
  int32_t texture_image(const pbrt::ParamSet& ps, const std::string& path, ColorEncoding encoding,
                        const char* param = "filename");
  // The image at path as the texture cache reads it, prepared once per
  // encoding, registered with n's filter and wrap.
  int32_t cached_texture(const pbrt::ParamSet& ps, const std::string& path, ColorEncoding encoding,
                         const TextureNode& n, const char* param = "filename");
  // Whether an image read by `filter` stays resident: small, and within the
  // scene's budget (counted once per file and encoding).
  bool resident_fits(const pbrt::ParamSet& ps, const std::string& path, ColorEncoding encoding, ImageFilter filter);
  RGBTextureRef add_texture_node(TextureNode n);
  // Material parameters (builder_materials.cpp).
  // pbrt's roughness, uroughness and vroughness (after prefix) and remaproughness.
  RoughnessParams roughness(const pbrt::ParamSet& ps, float def, const std::string& prefix = "");
  // "eta" (or pbrt-v3's "index"): a number, a named or RGB spectrum (its
  // first channel), or a float texture. With `dispersion`, an index given
  // as a spectrum that varies with wavelength is also added to the texture
  // pools, and its index there written to *dispersion.
  FloatTextureRef eta_param(const pbrt::ParamSet& ps, float def, int32_t* dispersion = nullptr);
  // An index of refraction given as a spectrum: its index in the texture
  // pools' spectra if it varies with wavelength (the scene disperses),
  // else -1.
  int32_t dispersive_index(const pbrt::ParamSet& ps, const pbrt::Param& p, const PiecewiseLinearSpectrum& eta);
  // A light's colour `name` given as a spectrum: its index in the texture
  // pools' spectra, or -1 (builder_lights.cpp).
  std::optional<PiecewiseLinearSpectrum> emission_spectrum(const pbrt::ParamSet& ps, const std::string& name);
  int32_t light_spectrum(const pbrt::ParamSet& ps, const std::string& name);
  void crop(const pbrt::ParamSet& ps);
  void camera_sensor(const pbrt::ParamSet& ps);
  void spectral_film(const pbrt::ParamSet& ps);
  void realistic_camera(const pbrt::ParamSet& ps);  // builder_camera.cpp
  std::optional<ApertureMask> aperture_mask(const pbrt::ParamSet& ps);
  void check_lens_focus() const;
  // "displacement" and "normalmap": an index into MaterialPools::bumps, or -1.
  int32_t bump_map(const pbrt::ParamSet& ps, const std::string& base_dir);
  MaterialHandle concrete_material(const std::string& type, const pbrt::ParamSet& ps);
  MaterialHandle mix_material(const pbrt::ParamSet& ps, const std::map<std::string, MaterialHandle>& named);
  // pbrt-v3's materials, mapped as pbrt-v4's upgrade maps them (builder_v3.cpp).
  MaterialHandle mix_material_v3(const pbrt::ParamSet& ps, const std::map<std::string, MaterialHandle>& named);
  std::optional<MaterialHandle> v3_material(const std::string& type, const pbrt::ParamSet& ps);
  void coat_layer(const pbrt::ParamSet& ps, CoatLayer* c);
  MaterialHandle coated_conductor(const pbrt::ParamSet& ps);
  MaterialHandle hair_material(const pbrt::ParamSet& ps);
  MaterialHandle measured_material(const pbrt::ParamSet& ps);
  MaterialHandle fourier_material(const pbrt::ParamSet& ps);  // builder_v3.cpp
  // pbrt's subsurface and kdsubsurface: a dielectric whose shapes hold a
  // homogeneous medium (builder_subsurface.cpp).
  MaterialHandle subsurface_material(const std::string& type, const pbrt::ParamSet& ps);
  void assign_subsurface_media(size_t first_geometry, const GraphicsState& gs, const pbrt::ParamSet& ps);
  void refuse_mixed_subsurface(const pbrt::ParamSet& ps, MaterialHandle h) const;
  HomogeneousMedium subsurface_interior(const pbrt::ParamSet& ps, const std::string& type, float eta);
  MaterialHandle default_material();
  void add_shape(const std::string& type, const pbrt::ParamSet& ps, const GraphicsState& gs, const std::string& base_dir);
  // source: the PLY file the mesh came from, or empty; named in errors.
  void add_portal(InfiniteLight& e, const pbrt::ParamSet& ps, const std::string& file);
  void profiled_light(const std::string& type, const pbrt::ParamSet& ps, const Mat4& ctm, const std::string& base_dir);
  void add_subdivision_surface(const pbrt::ParamSet& ps, const GraphicsState& gs);
  void add_mesh(TriangleMesh mesh, const GraphicsState& gs, const pbrt::ParamSet& ps, const std::string& source);
  void add_quadric(const std::string& type, const pbrt::ParamSet& ps, const GraphicsState& gs);  // builder_quadrics.cpp
  void add_curve(const pbrt::ParamSet& ps, const GraphicsState& gs);  // builder_curves.cpp
  void add_bilinear_mesh(const pbrt::ParamSet& ps, const GraphicsState& gs);  // builder_patches.cpp
  void add_heightfield(const pbrt::ParamSet& ps, const GraphicsState& gs);     // builder_v3_shapes.cpp
  void add_nurbs(const pbrt::ParamSet& ps, const GraphicsState& gs);           // builder_v3_shapes.cpp
  void add_patch_set(BilinearPatchSet s, const GraphicsState& gs, const pbrt::ParamSet& ps);  // builder_patches.cpp
  // shape: the shape's directive, where errors of its emitters are reported.
  void add_area_lights(uint32_t geometry, uint32_t primitives, const GraphicsState& gs, const pbrt::ParamSet& shape);
  void add_ply_mesh(const std::string& path, const GraphicsState& gs, const pbrt::ParamSet& ps);
  void load_pending_meshes();
  void count_triangles();
  MediumHandle find_medium(const std::string& name, const SourceLocation& where) const;
  MediumInterface medium_interface(const GraphicsState& gs) const;
  void assign_media(size_t first_geometry, const GraphicsState& gs);
  void finish_media();
  void volume_lights();
  HomogeneousMedium medium_coefficients(const pbrt::ParamSet& ps, bool presets);
  DensityGrid density_grid(const pbrt::ParamSet& ps, const Mat4& render_from_medium);
  RGB medium_Le(const pbrt::ParamSet& ps);
  GridEmission grid_emission(const pbrt::ParamSet& ps, const DensityGrid& density);
  RgbGridMedium rgb_grid(const pbrt::ParamSet& ps, const Mat4& render_from_medium);
  CloudMedium cloud(const pbrt::ParamSet& ps, const Mat4& render_from_medium);
  VdbMedium vdb_medium(const pbrt::ParamSet& ps, const Mat4& render_from_medium, const std::string& base_dir);
  void grid_layout(const pbrt::ParamSet& ps, const Mat4& render_from_medium, GridLayout* g);
  void note_geometry();
  void check_objects_closed() const;

  struct OpenObject {
    std::string name;
    uint32_t prototype;
  };
  std::optional<OpenObject> object_;
  SourceLocation object_where_;
  std::map<std::string, uint32_t> objects_;  // name -> prototype
  std::map<std::string, MediumHandle> named_media_;
  std::map<uint32_t, MediumHandle> subsurface_media_;  // a subsurface material's (by handle bits) interior
  std::map<std::pair<float, float>, SlabAlbedoTable> slab_tables_;  // by boundary eta and phase g
  SourceLocation camera_where_;  // a realistic camera's focus distance
  std::string camera_medium_;
  SourceLocation camera_medium_where_;
  bool camera_medium_named_later_ = false;  // than the Camera: pbrt-v4 refuses that

  // PLY meshes whose place in the pools is taken, read at finish().
  struct PendingMesh {
    uint32_t mesh, geometry;
    std::string path;
    Mat4 ctm;
    bool reverse_orientation;
    pbrt::ParamSet ps;  // for messages
  };
  std::vector<PendingMesh> pending_;

  Scene& scene_;
  bool lenient_ = false;
  MemoryLayout memory_layout_ = MemoryLayout::Auto;
  WarningSink warn_;
  std::function<void(const std::string&)> progress_;
  std::function<void(const std::string&, size_t)> file_progress_;
  std::map<std::string, RGBTextureRef> rgb_textures_;
  std::map<std::string, int32_t> color_space_spectra_;  // fitted colours, by space and value
  std::map<std::string, std::unique_ptr<LazyRGBToSpectrumTable>> color_space_tables_;
  std::map<std::string, FloatTextureRef> float_textures_;
  std::map<std::string, const MeasuredBRDF*> measured_files_;  // path -> its tables
  std::map<std::string, const FourierTable*> fourier_files_;
  std::map<std::string, int32_t> images_;  // "encoding|path" -> TexturePools::images
  std::map<std::string, PreparedTexture> prepared_;  // "encoding|path" -> its prepared file
  TextureCacheSettings texture_cache_;
  // Small images (point or bilinear filtered) are resident up to a budget.
  static constexpr int64_t kMaxResidentTexels = 256 * 256, kResidentTexelBudget = int64_t(4) << 20;  // 64 MB of float RGBA
  int64_t resident_texels_ = 0;
  std::optional<MaterialHandle> default_material_;
  glm::dmat4 world_from_camera_{1.0}, world_from_camera_end_{1.0};  // at the start and end of the motion
  glm::dmat4 render_from_world_{1.0};
};

}  // namespace lantern
