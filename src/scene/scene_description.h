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
//  - A point light of intensity I gives irradiance I * cos(theta) / r^2.
//  - Angles are in degrees in the description.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "core/color.h"
#include "core/diagnostics.h"
#include "core/math.h"

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
enum class CameraType { Pinhole, ThinLens };

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
};

// ---------------------------------------------------------------- film / output
// How linear radiance becomes 8-bit values in PNG/PPM (EXR is always linear).
enum class DisplayTransform {
  Srgb,       // exposure scale, clamp, sRGB OETF (native default)
  Linear,     // exposure scale, clamp, value*255 (the Path of Light course's PPM)
  CgrCourse,  // the CGR course's mapping, see docs/scene-format.md
};

struct FilmDesc {
  Sourced<int> width{640};
  Sourced<int> height{480};
  Sourced<DisplayTransform> display{DisplayTransform::Srgb};
  Sourced<float> exposure{0.0f};  // stops; display images are scaled by 2^exposure
};

// ---------------------------------------------------------------- render settings
struct RenderDesc {
  Sourced<std::string> integrator{std::string("whitted")};  // registry name, see render/integrators
  Sourced<int> max_depth{5};     // recursion limit (nbounces in the course files)
  Sourced<int> spp{1};           // samples per pixel
  Sourced<RGB> background{RGB(0, 0, 0)};
};

// ---------------------------------------------------------------- textures
// A reference to an image file used as a texture. `path` is resolved (absolute or
// relative to the working directory) by the loader; `written` is the text in the file.
struct TextureDesc {
  SourceLocation where;
  std::string written;   // the path as written in the scene file
  std::string resolved;  // the file that exists on disk
};

// ---------------------------------------------------------------- materials
// The course material model. The classic (Whitted) integrator reads it as
// Blinn-Phong + mirror + Fresnel refraction.
struct MaterialDesc {
  SourceLocation where;
  std::string name;
  Sourced<float> kd{1.0f};
  Sourced<float> ks{0.0f};
  Sourced<RGB> diffuse{RGB(0.8f, 0.8f, 0.8f)};
  Sourced<RGB> specular{RGB(1, 1, 1)};
  Sourced<float> exponent{1.0f};       // Blinn-Phong exponent
  Sourced<float> reflectivity{0.0f};   // mirror weight in [0,1] (kr)
  Sourced<bool> refractive{false};
  Sourced<float> ior{1.0f};
  Sourced<RGB> emission{RGB(0, 0, 0)};
  std::optional<int> texture;           // index into SceneDescription::textures; modulates diffuse
};

// ---------------------------------------------------------------- lights
struct PointLightDesc {
  SourceLocation where;
  Sourced<Vec3f> position;
  Sourced<RGB> intensity;           // radiant intensity; irradiance = I cos / r^2
  Sourced<RGB> specular_intensity;  // used by the specular lobe of the classic integrator
  // true: irradiance I cos / r^2 (physical; native and Path of Light). false: I cos,
  // no distance falloff (the CGR course's point lights).
  Sourced<bool> inverse_square{true};
};

using LightDesc = std::variant<PointLightDesc>;

// ---------------------------------------------------------------- shapes
// Texture mapping: longitude/latitude about `pole` (the world up axis of the
// file's family: +Z for Path of Light, +Y for CGR and by default).
struct SphereDesc {
  Sourced<Vec3f> center;
  Sourced<float> radius{1.0f};
  Sourced<Vec3f> pole{Vec3f(0, 1, 0)};
};

// A planar convex quad with corners in perimeter order. Texture: the image's
// top-left pixel at v0, u along v0->v1, image rows along v0->v3.
struct QuadDesc {
  Sourced<Vec3f> v[4];
};

struct TriangleDesc {
  Sourced<Vec3f> v[3];
};

// A capped cylinder between the centres of its two caps.
struct CylinderDesc {
  Sourced<Vec3f> p0, p1;
  Sourced<float> radius{1.0f};
};

// A triangle mesh, from inline lists or from a PLY file (loaded by the parser,
// so the description always holds the data).
struct MeshDesc {
  Sourced<std::string> file;           // empty for inline meshes
  std::vector<Vec3f> positions;
  std::vector<uint32_t> indices;       // 3 per triangle
  std::vector<Vec3f> normals;          // empty or one per vertex
  std::vector<Vec2f> uvs;              // empty or one per vertex
};

using ShapeGeometry = std::variant<SphereDesc, QuadDesc, TriangleDesc, CylinderDesc, MeshDesc>;

struct ShapeDesc {
  SourceLocation where;
  std::string name;   // optional label ("id" in Path of Light files)
  ShapeGeometry geometry;
  int material = 0;   // index into SceneDescription::materials
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
};

}  // namespace pt
