// The importer-neutral record of a model file (OBJ + MTL, glTF 2.0, COLLADA):
// what read_asset() (asset_reader.h) makes of a file, before anything is put
// into a SceneDescription (import_asset.cpp) and before its materials are
// mapped onto ours (import_materials.h). Plain data; nothing here or after it
// sees an Assimp type (docs/importing.md).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/color.h"
#include "core/diagnostics.h"
#include "core/transform.h"
#include "geometry/shapes/mesh.h"

namespace pt {

enum class AssetFormat { Obj, Gltf, Glb, Collada };

// The file extensions read_asset() reads, lower case with the dot, and the
// format of each ("OBJ", "glTF", "glTF binary", "COLLADA").
std::optional<AssetFormat> asset_format_of(const std::string& path);
const char* asset_format_name(AssetFormat format);

// An image a material names: a file beside the model (resolved), or the
// encoded bytes of an image embedded in it (glTF's bufferView or data: URI).
struct AssetTexture {
  std::string name;      // as the model file writes it ("textures/a.png"), or the embedded image's name
  std::string resolved;  // the existing file; empty if embedded or not found
  std::shared_ptr<const std::vector<unsigned char>> embedded;  // encoded image (PNG, JPEG, ...)
  std::string format_hint;  // of an embedded image: "png", "jpg", ...
  SourceLocation where;     // where the model file names it (its file if no line is known)
  bool missing = false;     // named, but neither found nor embedded (reported by read_asset)
};

// A material's use of a texture: index into ImportedAsset::textures (-1:
// none) and the texture-coordinate set it reads.
struct AssetTextureRef {
  int texture = -1;
  int uv_set = 0;
  SourceLocation where;  // the statement or key that names it
  bool transformed = false;  // an offset/scale/rotation of its coordinates (MTL -o/-s, KHR_texture_transform)
  float scale = 1.0f;        // MTL -bm (a bump map's multiplier), glTF normalTexture.scale
  explicit operator bool() const { return texture >= 0; }
};

enum class AlphaMode { Opaque, Mask, Blend };

// One material as the file describes it. Two models: the classic Phong one
// (MTL, COLLADA) and glTF's metallic-roughness one; `model` says which
// fields are meaningful. Everything the file says is kept, including what
// our materials cannot show yet (alpha, normal maps, textured parameters):
// import_materials.cpp decides, in one place, what becomes of it.
struct AssetMaterial {
  enum class Model { Phong, MetallicRoughness };
  std::string name;
  SourceLocation where;  // its definition (newmtl line, glTF materials[i]); the file if unknown
  Model model = Model::Phong;

  // Phong (MTL, COLLADA).
  RGB diffuse{0.8f, 0.8f, 0.8f};  // Kd
  AssetTextureRef diffuse_map;    // map_Kd
  RGB specular{0, 0, 0};          // Ks
  AssetTextureRef specular_map;   // map_Ks
  float shininess = 0;            // Ns (Blinn-Phong exponent)
  AssetTextureRef shininess_map;  // map_Ns
  float reflectivity = 0;         // COLLADA <reflectivity> x <reflective>: mirror weight
  RGB transmission_filter{1, 1, 1};  // Tf
  int illum = -1;                 // MTL illumination model; -1: not given
  bool lambert_only = false;      // COLLADA <lambert> (or <constant>): no specular term

  // Metallic-roughness (glTF).
  RGB base_color{1, 1, 1};
  AssetTextureRef base_color_map;
  float metallic = 1, roughness = 1;
  AssetTextureRef metallic_roughness_map;
  float transmission = 0;  // KHR_materials_transmission
  bool unlit = false;      // KHR_materials_unlit

  // Both.
  RGB emission{0, 0, 0};  // Ke, emissiveFactor x KHR_materials_emissive_strength
  AssetTextureRef emission_map;
  std::optional<float> ior;  // Ni, KHR_materials_ior
  float opacity = 1;         // d (1 - Tr), base colour alpha
  SourceLocation opacity_where;
  AssetTextureRef opacity_map;  // map_d
  AlphaMode alpha_mode = AlphaMode::Opaque;
  float alpha_cutoff = 0.5f;
  AssetTextureRef normal_map;  // norm, glTF normalTexture
  AssetTextureRef bump_map;    // map_bump, bump
  AssetTextureRef occlusion_map;
  bool double_sided = false;
  // Features of the file's material that no field above holds (glTF
  // extensions such as "KHR_materials_clearcoat"), each with where it is written.
  std::vector<std::pair<std::string, SourceLocation>> unsupported;
};

// One triangle mesh with one material. `tangents` (xyz and the bitangent
// sign w, as glTF's TANGENT) are read for normal maps, which do not exist
// yet: they do not reach the scene (counted as left out).
struct AssetMesh {
  std::string name;
  TriangleMesh mesh;  // normals and uvs: one per vertex or none; uvs of the set the diffuse texture reads
  std::vector<std::pair<Vec3f, float>> tangents;
  int material = 0;   // index into ImportedAsset::materials
};

// A node of the file's hierarchy that places meshes: the meshes (indices into
// ImportedAsset::meshes) and the node's transform to the file's world space.
// Nodes placing the same list are instances of one object.
struct AssetPlacement {
  std::string node;
  std::vector<int> meshes;
  Affine to_world;
};

struct AssetCamera {
  std::string name;
  bool orthographic = false;
  Vec3f position, look_at, up;  // in the file's world space
  float fov_y_deg = 45;         // perspective: vertical full angle
  float view_height = 2;        // orthographic: the visible height
  float aspect = 0;             // width / height if the file gives it; 0 if not
};

// A light in the file's world space, intensity already in our units
// (docs/importing.md, "Lights").
struct AssetLight {
  enum class Type { Point, Spot, Directional };
  std::string name;
  Type type = Type::Point;
  Vec3f position, direction{0, 0, -1};
  RGB intensity;            // point and spot: our I; directional: irradiance
  bool inverse_square = true;
  float cone_angle_deg = 45, cone_delta_deg = 0;  // spot
  SourceLocation where;
};

// What was read and what was left out, as (what, count) pairs in a fixed
// order: "nothing silently dropped" (printed by the command line and kept in
// the run record).
struct ImportCounts {
  std::vector<std::pair<std::string, uint64_t>> imported, skipped;
  void add(std::vector<std::pair<std::string, uint64_t>>& list, const std::string& what, uint64_t n) {
    if (n == 0) return;
    for (auto& [name, count] : list) {
      if (name == what) {
        count += n;
        return;
      }
    }
    list.emplace_back(what, n);
  }
  void imported_n(const std::string& what, uint64_t n) { add(imported, what, n); }
  void skipped_n(const std::string& what, uint64_t n) { add(skipped, what, n); }
};

struct ImportedAsset {
  std::string path;  // the file read
  AssetFormat format = AssetFormat::Obj;
  std::vector<AssetMesh> meshes;
  std::vector<AssetMaterial> materials;
  std::vector<AssetTexture> textures;
  std::vector<AssetPlacement> placements;
  std::vector<AssetCamera> cameras;
  std::vector<AssetLight> lights;
  ImportCounts counts;
  // Every file the import read or names: the model, its MTL files and
  // buffers, every texture found (used or not). Outputs may not be any of them.
  std::vector<std::string> files_read;
};

}  // namespace pt
