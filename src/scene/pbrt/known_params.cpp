#include "scene/pbrt/known_params.h"

#include <algorithm>
#include <array>
#include <sstream>

namespace lantern::pbrt {
namespace {

// The names each version's Create functions (and scene-wide readers:
// shape "alpha", material "normalmap") look up, for every type of the
// kind, as read from pbrt-v4's and pbrt-v3's sources (pbrt-v3's disney
// material, which Lantern refuses, included: its parameters are known).
struct KindNames {
  std::string_view kind, v4, v3;
};
constexpr std::array<KindNames, 12> kNames{{
    {"camera",
     "aperture aperturediameter focaldistance focusdistance fov frameaspectratio lensfile lensradius mapping "
     "screenwindow shutterclose shutteropen",
     "aperturediameter focaldistance focusdistance fov frameaspectratio halffov lensfile lensradius screenwindow "
     "shutterclose shutteropen simpleweighting"},
    {"film",
     "coordinatesystem cropwindow diagonal filename iso lambdamax lambdamin maxcomponentvalue nbuckets pixelbounds "
     "savefp16 sensor whitebalance xresolution yresolution",
     "cropwindow diagonal filename maxsampleluminance pixelbounds scale xresolution yresolution"},
    {"filter", "B C sigma tau xradius yradius", "B C alpha tau xwidth ywidth"},
    {"sampler", "jitter pixelsamples randomization seed xsamples ysamples",
     "dimensions jitter pixelsamples samplepixelcenter xsamples ysamples"},
    {"integrator",
     "bootstrapsamples chains cossample filename function imagefilename largestepprobability lightsampler maxdepth "
     "maxdistance mutationsperpixel photonsperiteration radius regularize samplebsdf samplelights seed sigma skipbad "
     "visualizestrategies visualizeweights",
     "bootstrapsamples chains cossample imagewritefrequency iterations largestepprobability lightsamplestrategy "
     "maxdepth mutationsperpixel nsamples numiterations photonsperiteration pixelbounds radius rrthreshold sigma "
     "strategy visualizestrategies visualizeweights"},
    {"accelerator", "emptybonus intersectcost maxdepth maxnodeprims maxprims splitmethod traversalcost",
     "emptybonus intersectcost maxdepth maxnodeprims maxprims splitmethod traversalcost"},
    {"shape",
     "N P S alpha basis degree displacement edgelength emissionfilename faceIndices filename height indices "
     "innerradius levels phimax radius scheme splitdepth type uv width width0 width1 zmax zmin",
     "N P Pw Pz S alpha basis degree displacement edgelength filename height indices innerradius nlevels nu nv p1 p2 "
     "phimax radius shadowalpha splitdepth st type u0 u1 uknots uorder uv v0 v1 vknots vorder width width0 width1 "
     "zmax zmin"},
    {"material",
     "albedo alpha amount beta_m beta_n color conductor.eta conductor.k conductor.roughness conductor.uroughness "
     "conductor.vroughness displacement eta eumelanin filename g interface.eta interface.roughness "
     "interface.uroughness interface.vroughness k materials maxdepth mfp name normalmap nsamples pheomelanin "
     "reflectance remaproughness roughness scale sigma_a sigma_s thickness transmittance type uroughness vroughness",
     "Kd Kr Ks Kt alpha amount anisotropic beta_m beta_n bsdffile bumpmap clearcoat clearcoatgloss color difftrans eta "
     "eumelanin flatness g index k metallic mfp name namedmaterial1 namedmaterial2 opacity pheomelanin reflect "
     "remaproughness roughness scale scatterdistance sheen sheentint sigma sigma_a sigma_s spectrans speculartint thin "
     "transmit type uroughness vroughness"},
    {"texture",
     "amount dimension dir encoding filename filter inside invert mapping maxanisotropy octaves outside roughness "
     "scale tex tex1 tex2 udelta uscale v00 v01 v1 v10 v11 v2 value variation vdelta vscale wrap",
     "aamode amount dimension filename gamma inside mapping maxanisotropy octaves outside roughness scale tex tex1 "
     "tex2 trilinear udelta uscale v00 v01 v1 v10 v11 v2 value variation vdelta vscale wrap"},
    {"light", "I L coneangle conedeltaangle filename fov from illuminance portal power scale to",
     "I L coneangle conedeltaangle fov from mapname nsamples samples scale to"},
    {"arealight", "L filename power scale twosided", "L nsamples samples scale twosided"},
    {"medium",
     "Le Lescale density filename frequency g gridname nx ny nz p0 p1 preset scale sigma_a sigma_s temperature "
     "temperaturecutoff temperatureoffset temperaturename temperaturescale type wispiness",
     "density g nx ny nz p0 p1 preset scale sigma_a sigma_s type"},
}};

struct Table {
  std::string_view kind;
  std::vector<std::string> names;  // sorted, unique
};

const std::vector<Table>& tables() {
  static const std::vector<Table> t = [] {
    std::vector<Table> out;
    for (const KindNames& k : kNames) {
      Table tb{k.kind, {}};
      for (std::string_view list : {k.v4, k.v3}) {
        std::istringstream in{std::string(list)};
        for (std::string w; in >> w;) tb.names.push_back(w);
      }
      std::sort(tb.names.begin(), tb.names.end());
      tb.names.erase(std::unique(tb.names.begin(), tb.names.end()), tb.names.end());
      out.push_back(std::move(tb));
    }
    return out;
  }();
  return t;
}

const Table* table(std::string_view kind) {
  for (const Table& t : tables())
    if (t.kind == kind) return &t;
  return nullptr;
}

}  // namespace

bool is_known_parameter(std::string_view kind, std::string_view name) {
  const Table* t = table(kind);
  if (!t) return true;
  const auto less = [](std::string_view a, std::string_view b) { return a < b; };
  if (std::binary_search(t->names.begin(), t->names.end(), name, less)) return true;
  // pbrt-v3 lets a Shape carry its material's parameters (a per-shape
  // material over the current one).
  return kind == "shape" && is_known_parameter("material", name);
}

const std::vector<std::string>& known_parameters(std::string_view kind) {
  static const std::vector<std::string> none;
  const Table* t = table(kind);
  return t ? t->names : none;
}

}  // namespace lantern::pbrt
