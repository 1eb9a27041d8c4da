// SceneDescription: the editable, parsed scene. Plain data, no behaviour.
//
// Every importer (native JSON, Path of Light, CGR) produces one of these; nothing
// after parsing looks at JSON. Every value carries the place in the file it came
// from (Sourced<T>), so that problems found later (a texture that fails to decode,
// a mesh whose indices are out of range) are still reported at file:line:col.
//
// Units and conventions (the importers translate the course conventions into these):
//  - World space is right-handed; there is no preferred up axis.
//  - Colours are linear RGB.
//  - A point light of intensity I makes a white Lambertian surface facing it at
//    distance r shine with radiance I / r^2 (the classic integrator's I cos / r^2
//    with no 1/pi): physically radiant intensity pi I (docs/path-tracing.md).
//  - Angles are in degrees in the description.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <utility>
#include <string>
#include <variant>
#include <vector>

#include "core/color.h"
#include "core/diagnostics.h"
#include "core/math.h"
#include "geometry/shapes.h"

namespace pt {

// A value together with where it was written. Converts implicitly to its value.
template <class T>
struct Sourced {
  T value{};
  SourceLocation where;

  Sourced() = default;
  Sourced(T v) : value(std::move(v)) {}  // NOLINT: implicit by design (defaults)
  Sourced(T v, SourceLocation w) : value(std::move(v)), where(std::move(w)) {}
  operator const T&() const { return value; }  // NOLINT
  const T& operator*() const { return value; }
  const T* operator->() const { return &value; }
};

// ---------------------------------------------------------------- camera
// The projections (render/camera/*.h): perspective (pinhole, thin lens),
// orthographic and spherical (equirectangular 360 degrees).
enum class CameraType { Pinhole, ThinLens, Orthographic, Spherical };

struct CameraDesc {
  SourceLocation where;
  CameraType type = CameraType::Pinhole;
  Sourced<Vec3f> position{Vec3f(0, 0, 0)};
  Sourced<Vec3f> look_at{Vec3f(0, 0, -1)};  // a target point
  Sourced<Vec3f> up{Vec3f(0, 1, 0)};        // need not be unit length or orthogonal
  Sourced<float> fov_y_deg{45.0f};          // vertical full angle
  // Right-handed: image right = forward x up. Left-handed (the CGR family):
  // image right = up x forward, i.e. the image is mirrored left-right.
  Sourced<bool> left_handed{false};
  // Thin lens only (a pinhole ignores them): lens radius in scene units, and the
  // distance along the view direction of the plane in focus.
  Sourced<float> lens_radius{0.0f};
  Sourced<float> focus_distance{1.0f};
  // Orthographic only: the visible rectangle in scene units, its height, or its
  // width when view_width > 0 (0: not given); the other side follows from the
  // image's aspect ratio.
  Sourced<float> view_height{2.0f};
  Sourced<float> view_width{0.0f};
  // Added to every film position (pixels) before the camera maps it to a ray:
  // (0, 0) samples pixel (x, y) at its centre (x + 0.5, y + 0.5). Set only by the
  // CGR importer, whose course renders sample one pixel to the left (docs/rendering.md).
  Vec2f film_offset{0.0f, 0.0f};
};

// ---------------------------------------------------------------- film / output
// How linear radiance becomes 8-bit values in PNG/PPM (EXR is always linear).
enum class DisplayTransform {
  Srgb,       // exposure scale, clamp, sRGB OETF (native default)
  Linear,     // exposure scale, clamp, value*255 (the Path of Light course's PPM)
  CgrCourse,  // the CGR course's mapping, see docs/scene-format.md
};
// The scene file's names of the transforms ("film.display"), in enum order.
inline constexpr const char* kDisplayTransformNames[] = {"srgb", "linear", "cgr"};

struct FilmDesc {
  Sourced<int> width{640};
  Sourced<int> height{480};
  Sourced<DisplayTransform> display{DisplayTransform::Srgb};
  Sourced<float> exposure{0.0f};  // stops; display images are scaled by 2^exposure
};

// ---------------------------------------------------------------- textures
// A texture (docs/scene-format.md, "Textures"; docs/textures.md): an image
// file, or a procedural checker or noise, read through a mapping. Materials
// refer to them by index into SceneDescription::textures.
enum class TextureType { Image, Checker, Noise };
inline constexpr const char* kTextureTypeNames[] = {"image", "checker", "noise"};

// How an image texture is filtered (pbrt-v4's ImageTexture "filter"): the
// nearest texel or bilinear on the finest level (point lookups), trilinear
// between two MIP levels chosen by the footprint's longer axis, or
// OpenImageIO's anisotropic filter (trilinear probes along the footprint).
enum class TextureFilter { Point, Bilinear, Trilinear, Anisotropic };
inline constexpr const char* kTextureFilterNames[] = {"point", "bilinear", "trilinear", "anisotropic"};

// What a lookup outside [0, 1] reads (pbrt-v4's "wrap"; "mirror" is OpenImageIO's).
enum class TextureWrap { Repeat, Clamp, Black, Mirror };
inline constexpr const char* kTextureWrapNames[] = {"repeat", "clamp", "black", "mirror"};

struct TextureDesc {
  SourceLocation where;
  std::string written;   // image: the path as written in the scene file
  std::string resolved;  // image: the file that exists on disk
  // Texel values used as they are, without sRGB decoding ("encoding": "linear";
  // the Path of Light course's linear pipeline: docs/rendering.md).
  bool raw = false;
  TextureType type = TextureType::Image;
  std::string name;      // its name in the native "textures", if it has one
  Sourced<TextureFilter> filter{TextureFilter::Anisotropic};  // image
  Sourced<TextureWrap> wrap{TextureWrap::Repeat};             // image
  Sourced<RGB> color0{RGB(0.0f)};  // checker, noise
  Sourced<RGB> color1{RGB(1.0f)};
  Sourced<int> octaves{6};         // noise
  Sourced<float> roughness{0.5f};  // noise: amplitude ratio of successive octaves
  // Mapping: texture coordinates c = scale * transform^-1(x), x = (u, v, 0) or
  // the object-space position ("mapping": "object").
  Sourced<bool> object_mapping{false};
  Sourced<Vec3f> scale{Vec3f(1.0f)};
  std::optional<Sourced<Transform>> transform;
  // An image embedded in a model file (glTF): its encoded bytes (PNG, JPEG,
  // ...) and a format hint ("png"); `resolved` is then empty.
  std::shared_ptr<const std::vector<unsigned char>> embedded;
  std::string embedded_format;
};

// ---------------------------------------------------------------- render settings
// Pixel reconstruction filter (docs/path-tracing.md): a 1-pixel box, a
// Gaussian (radius 1.5, sigma 0.5) or Mitchell-Netravali (radius 2, B = C = 1/3).
enum class PixelFilterType { Box, Gaussian, Mitchell };
// The names of the filters (scene files, --filter, the EXR header, run records), in enum order.
inline constexpr const char* kPixelFilterNames[] = {"box", "gaussian", "mitchell"};

// How the path integrator chooses the light of each next-event estimate
// (docs/path-tracing.md, "Choosing a light"): by importance at the shading
// point through a light BVH, or in proportion to each light's power.
enum class LightSamplerType { Bvh, Power };
inline constexpr const char* kLightSamplerNames[] = {"bvh", "power"};

// Cycles' per-object "Shadow Terminator > Geometry Offset" (its default): how
// near the terminator the rays leaving a smooth-shaded mesh start from the
// smooth surface its vertex normals imply (docs/rendering.md, "Shadow terminator").
inline constexpr float kDefaultShadowTerminatorOffset = 0.1f;

inline constexpr int kDefaultLightGuiding = 0;
inline constexpr int kDefaultPathGuiding = 0;

struct RenderDesc {
  Sourced<std::string> integrator{std::string("whitted")};  // registry name, see render/integrators
  Sourced<int> max_depth{5};     // recursion limit (nbounces in the course files)
  Sourced<int> spp{1};           // samples per pixel
  // Radiance of rays that hit nothing; the path integrator also treats it as a
  // uniform environment that lights the scene (docs/path-tracing.md).
  Sourced<RGB> background{RGB(0, 0, 0)};
  Sourced<PixelFilterType> filter{PixelFilterType::Box};
  Sourced<float> clamp{0.0f};    // firefly clamp on each sample's radiance; 0 = off
  Sourced<LightSamplerType> light_sampler{LightSamplerType::Bvh};  // the path integrator's light choice
  // In [0, 1]; 0 turns the shadow-terminator offset off.
  Sourced<float> shadow_terminator_geometry_offset{kDefaultShadowTerminatorOffset};
  // An image behind the scene in screen space, stretched over the frame: what
  // camera rays that leave the scene see instead of `background` or the
  // environment. Bounce rays do not see it and it lights nothing.
  std::optional<TextureDesc> background_image;
  // Cycles' Film > Transparent: what camera rays see when they hit nothing is
  // left out of the image (alpha 0); it still lights the scene.
  Sourced<bool> film_transparent{false};
  // The path integrator's light guiding: pre-pass paths per pixel, 0 = off
  // (render/guiding/light_guide.h; docs/path-tracing.md, "Light guiding").
  Sourced<int> light_guiding{kDefaultLightGuiding};
  // The path integrator's path guiding of bounce directions: pre-pass paths
  // per pixel, 0 = off (render/guiding/path_guide.h; docs/path-tracing.md, "Path guiding").
  Sourced<int> path_guiding{kDefaultPathGuiding};
};


// ---------------------------------------------------------------- materials
// Phong: the course material model. The classic (Whitted) integrator reads it
// as Blinn-Phong + mirror + Fresnel refraction; the path integrator as a
// normalised Blinn-Phong BRDF with a mirror lobe, or a dielectric when
// `refractive`. Lambert, Mirror and Glass are the physical materials of the
// path integrator; Conductor, Dielectric and CoatedDiffuse its microfacet
// materials (GGX, docs/path-tracing.md); MetallicRoughness glTF's blend of a
// Schlick conductor and a coated diffuse by `metallic`. Each type reads only
// some of the keys (docs/scene-format.md).
enum class MaterialType { Phong, Lambert, Mirror, Glass, Conductor, Dielectric, CoatedDiffuse, MetallicRoughness };

// A material parameter that may be textured (docs/scene-format.md, "Textured
// parameters"): the constant `value`, times the texture's value where
// `texture` is set (an index into SceneDescription::textures).
// The model-file importers also read one channel of a texture and square it
// (glTF's roughness is the green channel of its metallic-roughness texture,
// and its GGX alpha the square of the roughness); the native format writes
// neither (docs/importing.md).
template <class T>
struct TexturedParam {
  Sourced<T> value;
  std::optional<int> texture;
  int channel = -1;      // a float parameter: the texel's channel 0, 1 or 2; -1: the mean of the three
  bool squared = false;  // a float parameter: value * t^2 instead of value * t
};

struct MaterialDesc {
  SourceLocation where;
  std::string name;
  Sourced<MaterialType> type{MaterialType::Phong};
  Sourced<float> kd{1.0f};
  Sourced<float> ks{0.0f};
  Sourced<RGB> diffuse{RGB(0.8f, 0.8f, 0.8f)};
  Sourced<RGB> specular{RGB(1, 1, 1)};
  Sourced<float> exponent{1.0f};       // Blinn-Phong exponent
  Sourced<float> reflectivity{0.0f};   // mirror weight in [0,1] (kr)
  Sourced<bool> refractive{false};
  Sourced<float> ior{1.0f};             // glass, dielectric, the coating of coateddiffuse
  std::optional<Sourced<float>> ka;     // weight of the classic ambient term; absent: kd (the path equivalent's)
  Sourced<RGB> emission{RGB(0, 0, 0)};  // emitted radiance, on the front (ng) side only unless two_sided
  std::optional<int> emission_texture;  // index into SceneDescription::textures; multiplies `emission`
  // Glass and dielectric: the colour transmitted light is multiplied by at
  // each crossing of the surface (MTL's Tf); white: clear.
  Sourced<RGB> transmittance{RGB(1, 1, 1)};
  Sourced<bool> two_sided{false};       // emission from both sides
  // The classic (whitted) integrator's samples of this emitter per shading
  // point (a Path of Light area light's "samples"); 0: its default (16).
  Sourced<int> light_samples{0};
  std::optional<int> texture;           // index into SceneDescription::textures; modulates diffuse
  // Alpha cutout (docs/scene-format.md): the surface is there where alpha is at
  // least 0.5 (the constant, or the texture's alpha at the hit) and absent
  // for every ray elsewhere.
  Sourced<float> alpha{1.0f};
  std::optional<int> alpha_texture;     // index into SceneDescription::textures; replaces `alpha`
  // The alpha from which the surface is there: 0.5 in the native format; the
  // importers set it (glTF's alphaCutoff, MTL's d times map_d; docs/importing.md).
  float alpha_cutoff = 0.5f;
  // "alpha_mode": "blend": alpha is an opacity instead: a ray meets the surface
  // with probability alpha (the constant times the texture's alpha, cutoff not
  // used) and passes through otherwise (glTF's BLEND, MTL's partial dissolve).
  Sourced<bool> alpha_blend{false};

  // Microfacet materials: GGX roughness along the shading frame's two tangent
  // axes ("roughness" sets both; "uroughness", "vroughness" each), in [0, 1];
  // alpha = sqrt(roughness) when remap_roughness (pbrt-v4's remaproughness).
  TexturedParam<float> uroughness{Sourced<float>(0.0f), {}};
  TexturedParam<float> vroughness{Sourced<float>(0.0f), {}};
  Sourced<bool> remap_roughness{true};
  // Conductor: complex index of refraction eta + i k per channel (a preset's
  // values when "metal" names one; copper by default, as pbrt-v4), or, when
  // `schlick`, Schlick's Fresnel term with normal-incidence reflectance
  // `reflectance`. CoatedDiffuse: `reflectance` is the diffuse base's albedo.
  // MetallicRoughness: `reflectance` is glTF's base colour (the metal's F0 and
  // the coated diffuse's albedo), `metallic` the blend in [0, 1].
  TexturedParam<RGB> eta{Sourced<RGB>(RGB(0.3512f, 0.5855f, 1.2923f)), {}};
  TexturedParam<RGB> k{Sourced<RGB>(RGB(4.3225f, 2.6787f, 2.1364f)), {}};
  TexturedParam<RGB> reflectance{Sourced<RGB>(RGB(0.5f)), {}};
  bool schlick = false;
  TexturedParam<float> metallic{Sourced<float>(0.0f), {}};
  // Any type: a tangent-space normal map and a bump map (displacement along
  // the normal, in scene units; docs/path-tracing.md, "Normal and bump maps").
  std::optional<int> normal_map;
  float normal_scale = 1.0f;  // the tangent-space x and y scaled by it (glTF's normalTexture.scale); 1 natively
  std::optional<TexturedParam<float>> displacement;

  // Calls f(texture index) for every texture the material reads.
  template <class F>
  void for_each_texture(F&& f) const {
    for (const std::optional<int>& t : {texture, uroughness.texture, vroughness.texture, eta.texture, k.texture,
                                        reflectance.texture, metallic.texture, normal_map, emission_texture})
      if (t) f(*t);
    if (displacement && displacement->texture) f(*displacement->texture);
    if (alpha_texture) f(*alpha_texture);
  }
};

// ---------------------------------------------------------------- lights
struct PointLightDesc {
  SourceLocation where;
  Sourced<Vec3f> position;
  Sourced<RGB> intensity;           // I: radiance I cos / r^2 on a white Lambertian (radiant intensity pi I)
  Sourced<RGB> specular_intensity;  // used by the specular lobe of the classic integrator
  // true: irradiance I cos / r^2 (physical; native and Path of Light). false: I cos,
  // no distance falloff (the CGR course's point lights).
  Sourced<bool> inverse_square{true};
};

// A light infinitely far away: parallel rays travelling along `direction`,
// delivering `irradiance` (W/m^2) to a surface perpendicular to them.
struct DirectionalLightDesc {
  SourceLocation where;
  Sourced<Vec3f> direction{Vec3f(0, -1, 0)};  // the direction the light travels; any length
  Sourced<RGB> irradiance;
};

// A spot light (docs/scene-format.md): a point light whose intensity is
// confined to a cone about `direction` (given, or towards `look_at`): full
// within cone_angle - cone_delta of the axis, none beyond cone_angle, and a
// falloff between that each integrator reads its own way (docs/path-tracing.md).
struct SpotLightDesc {
  SourceLocation where;
  Sourced<Vec3f> position;
  Sourced<Vec3f> direction{Vec3f(0, 0, 1)};  // the axis; any length (look_at - position when that is given)
  Sourced<RGB> intensity;                    // as a point light's I, on the axis
  Sourced<RGB> specular_intensity;           // used by the specular lobe of the classic integrator
  Sourced<float> cone_angle{30.0f};          // degrees from the axis to the cone's edge (pbrt-v4's coneangle)
  Sourced<float> cone_delta{5.0f};           // degrees of the falloff band inside the edge (pbrt-v4's conedelta)
};

// The classic integrators' ambient light (seeds 002 and 003): a constant term
// ka Cd `intensity` added to every surface's local shading, unshadowed. Not
// physical: the path integrator leaves it out with a warning; its equivalent
// there is a uniform environment (render.background), docs/path-tracing.md.
struct AmbientLightDesc {
  SourceLocation where;
  Sourced<RGB> intensity;
};

using LightDesc = std::variant<PointLightDesc, DirectionalLightDesc, SpotLightDesc, AmbientLightDesc>;

// ---------------------------------------------------------------- environment
// A latitude-longitude (equirectangular) radiance map around the scene, seen by
// rays that leave it. See docs/path-tracing.md for the orientation.
struct EnvironmentDesc {
  SourceLocation where;
  Sourced<std::string> file;             // as written in the scene file
  std::string resolved;                  // the file that exists on disk
  Sourced<float> rotation_deg{0.0f};     // about `up`, counter-clockwise seen from above
  Sourced<float> intensity{1.0f};        // scale on the map's values
  Sourced<Vec3f> up{Vec3f(0, 1, 0)};     // the map's zenith; any length
};

// ---------------------------------------------------------------- shapes
// The place in the file of one of a shape's fields, under the name the shape's
// validation rule (check() in geometry/shapes/*.h) reports problems on.
struct FieldLocation {
  std::string field;
  SourceLocation where;
};

// One shape: its geometry (geometry/shapes.h; a file's "triangle" is a
// one-triangle mesh, a sphere's pole is unit length) and where it was written.
struct ShapeDesc {
  SourceLocation where;
  std::string name;   // optional label ("id" in Path of Light files); Cryptomatte's object name
  std::string type;   // the file's type name ("sphere", "triangle", ...); empty if built in code
  std::string file;   // the mesh file as written; empty for inline data and other shapes
  Shape geometry;
  std::vector<FieldLocation> fields;  // filled by the importers
  int material = 0;   // index into SceneDescription::materials
  // Object to world ("transform"); absent for the identity, which costs nothing.
  std::optional<Sourced<Transform>> transform;

  // Records where `field` was written and returns its value.
  template <class T>
  const T& field(std::string name_in_rule, const Sourced<T>& v) {
    fields.push_back({std::move(name_in_rule), v.where});
    return v.value;
  }
  // Where `field` was written; the shape's own location for "" or a field not recorded.
  const SourceLocation& at(const std::string& field_name) const {
    for (const FieldLocation& f : fields) {
      if (f.field == field_name && f.where.valid()) return f.where;
    }
    return where;
  }
};

// ---------------------------------------------------------------- instancing
// A named object ("objects"): shapes defined once, in object space, placed
// only by instances.
struct ObjectDesc {
  SourceLocation where;
  std::string name;
  std::vector<ShapeDesc> shapes;
};

// One placement of an object (a shape of type "instance").
struct InstanceDesc {
  SourceLocation where;
  std::string name;                              // optional; Cryptomatte's object name (default: the object's)
  int object = 0;                                // index into SceneDescription::objects
  std::optional<Sourced<Transform>> transform;   // object to world; absent: identity
  std::optional<int> material;                   // replaces the object's materials
};

// ---------------------------------------------------------------- imported model files
// What one {"type": "import"} (or a model file given as the scene) brought
// in and what it left out, as (what, count) pairs: printed by the command
// line, kept in the run record (docs/importing.md).
struct ImportSummary {
  std::string file;    // as written
  std::string format;  // "OBJ", "glTF", "glTF binary", "COLLADA"
  double seconds = 0;  // reading and converting the file (in mesh_load_seconds too)
  std::vector<std::pair<std::string, uint64_t>> imported, skipped;
  std::vector<std::string> files_read;  // ImportedAsset::files_read: inputs no output may overwrite
};

// ---------------------------------------------------------------- the scene
enum class SceneFormat { Native, PathOfLight, Cgr };

struct SceneDescription {
  std::string source_path;
  SceneFormat format = SceneFormat::Native;
  CameraDesc camera;
  FilmDesc film;
  RenderDesc render;
  std::vector<MaterialDesc> materials;
  std::vector<TextureDesc> textures;  // each file once; referenced by index
  std::vector<LightDesc> lights;
  std::vector<ShapeDesc> shapes;
  std::vector<ObjectDesc> objects;      // instancing: what instances place
  std::vector<InstanceDesc> instances;
  std::optional<EnvironmentDesc> environment;  // replaces render.background for rays that leave
  double mesh_load_seconds = 0;  // time the loader spent reading mesh and model files, for run records
  std::vector<ImportSummary> imports;  // one per imported model file, in order
};

}  // namespace pt
