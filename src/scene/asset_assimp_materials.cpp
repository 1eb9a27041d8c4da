// Assimp's materials of a glTF or COLLADA file -> AssetMaterial (asset.h).
// Only reading: what becomes of each value is import_materials.cpp's business.
#include <assimp/GltfMaterial.h>
#include <assimp/material.h>
#include <assimp/scene.h>

#include <cstring>
#include <string>

#include "scene/asset_internal.h"

namespace pt {
namespace {

bool gltf_format(AssetFormat f) { return f == AssetFormat::Gltf || f == AssetFormat::Glb; }

RGB colour(const aiMaterial& m, const char* key, unsigned type, unsigned index, RGB fallback, float* alpha = nullptr) {
  aiColor4D c;
  if (m.Get(key, type, index, c) != AI_SUCCESS) return fallback;
  if (alpha) *alpha = c.a;
  return RGB(c.r, c.g, c.b);
}

float number(const aiMaterial& m, const char* key, unsigned type, unsigned index, float fallback) {
  float v = 0;
  return m.Get(key, type, index, v) == AI_SUCCESS ? v : fallback;
}

// The embedded image a texture path names ("*N", or the name of an embedded
// image), as encoded bytes; null if it names a file.
std::shared_ptr<const std::vector<unsigned char>> embedded_bytes(const aiScene& scene, const char* path,
                                                                 std::string& hint, std::string& name) {
  const aiTexture* t = scene.GetEmbeddedTexture(path);
  if (t == nullptr) return nullptr;
  name = t->mFilename.length > 0 ? t->mFilename.C_Str() : path;
  if (t->mHeight == 0) {  // compressed: mWidth bytes of a PNG, JPEG, ...
    hint = t->achFormatHint;
    const auto* bytes = reinterpret_cast<const unsigned char*>(t->pcData);
    return std::make_shared<const std::vector<unsigned char>>(bytes, bytes + t->mWidth);
  }
  // Raw BGRA texels: written out as a binary PPM (P6), which the image
  // reader decodes like any other file (alpha dropped).
  const std::string header = "P6\n" + std::to_string(t->mWidth) + " " + std::to_string(t->mHeight) + "\n255\n";
  auto out = std::make_shared<std::vector<unsigned char>>(header.begin(), header.end());
  const std::size_t n = static_cast<std::size_t>(t->mWidth) * t->mHeight;
  out->reserve(out->size() + 3 * n);
  for (std::size_t i = 0; i < n; ++i) {
    out->push_back(t->pcData[i].r);
    out->push_back(t->pcData[i].g);
    out->push_back(t->pcData[i].b);
  }
  hint = "ppm";
  return out;
}

// The material's first texture of `type`: a file or an embedded image.
AssetTextureRef texture(const aiScene& scene, const aiMaterial& m, aiTextureType type, AssetTextureTable& table,
                        const SourceLocation& where) {
  AssetTextureRef ref;
  aiString path;
  unsigned uv = 0;
  if (m.GetTextureCount(type) == 0 || m.GetTexture(type, 0, &path, nullptr, &uv) != AI_SUCCESS) return ref;
  ref.uv_set = static_cast<int>(uv);
  ref.where = where;
  aiUVTransform transform;
  if (m.Get(AI_MATKEY_UVTRANSFORM(type, 0), transform) == AI_SUCCESS)
    ref.transformed = transform.mTranslation != aiVector2D(0, 0) || transform.mScaling != aiVector2D(1, 1) ||
                      transform.mRotation != 0.0f;
  std::string hint, name;
  if (auto bytes = embedded_bytes(scene, path.C_Str(), hint, name)) {
    ref.texture = table.embedded(path.C_Str(), name, std::move(bytes), hint, where);
  } else {
    ref.texture = table.file(path.C_Str(), where);
  }
  return ref;
}

// glTF's metallic-roughness material as Assimp 5.2 reads it.
void read_metallic_roughness(const aiScene& scene, const aiMaterial& m, AssetMaterial& out, AssetTextureTable& table) {
  out.model = AssetMaterial::Model::MetallicRoughness;
  out.base_color = colour(m, AI_MATKEY_BASE_COLOR, RGB(1.0f), &out.opacity);
  out.base_color_map = texture(scene, m, aiTextureType_BASE_COLOR, table, out.where);
  if (!out.base_color_map) out.base_color_map = texture(scene, m, aiTextureType_DIFFUSE, table, out.where);
  out.metallic = number(m, AI_MATKEY_METALLIC_FACTOR, 1.0f);
  out.roughness = number(m, AI_MATKEY_ROUGHNESS_FACTOR, 1.0f);
  out.metallic_roughness_map = texture(scene, m, aiTextureType_UNKNOWN, table, out.where);
  out.transmission = number(m, AI_MATKEY_TRANSMISSION_FACTOR, 0.0f);
  out.occlusion_map = texture(scene, m, aiTextureType_LIGHTMAP, table, out.where);
  aiString mode;
  if (m.Get(AI_MATKEY_GLTF_ALPHAMODE, mode) == AI_SUCCESS) {
    if (std::strcmp(mode.C_Str(), "MASK") == 0) out.alpha_mode = AlphaMode::Mask;
    if (std::strcmp(mode.C_Str(), "BLEND") == 0) out.alpha_mode = AlphaMode::Blend;
  }
  out.alpha_cutoff = number(m, AI_MATKEY_GLTF_ALPHACUTOFF, 0.5f);
  int shading = 0;
  out.unlit = m.Get(AI_MATKEY_SHADING_MODEL, shading) == AI_SUCCESS && shading == aiShadingMode_Unlit;
}

// COLLADA's <lambert>, <phong>, <blinn> and <constant> as Assimp reads them.
void read_phong(const aiScene& scene, const aiMaterial& m, AssetMaterial& out, AssetTextureTable& table) {
  out.model = AssetMaterial::Model::Phong;
  out.diffuse = colour(m, AI_MATKEY_COLOR_DIFFUSE, RGB(0.8f));
  out.diffuse_map = texture(scene, m, aiTextureType_DIFFUSE, table, out.where);
  out.specular = colour(m, AI_MATKEY_COLOR_SPECULAR, RGB(0.0f));
  out.specular_map = texture(scene, m, aiTextureType_SPECULAR, table, out.where);
  out.shininess = number(m, AI_MATKEY_SHININESS, 0.0f);
  out.reflectivity = number(m, AI_MATKEY_REFLECTIVITY, 0.0f) * colour(m, AI_MATKEY_COLOR_REFLECTIVE, RGB(0.0f)).max_component();
  out.opacity = number(m, AI_MATKEY_OPACITY, 1.0f);
  out.opacity_map = texture(scene, m, aiTextureType_OPACITY, table, out.where);
  const float ior = number(m, AI_MATKEY_REFRACTI, 1.0f);
  if (ior != 1.0f) out.ior = ior;
  out.normal_map = texture(scene, m, aiTextureType_NORMALS, table, out.where);
  out.bump_map = texture(scene, m, aiTextureType_HEIGHT, table, out.where);
  int shading = 0;
  if (m.Get(AI_MATKEY_SHADING_MODEL, shading) == AI_SUCCESS)
    out.lambert_only = shading == aiShadingMode_Gouraud || shading == aiShadingMode_NoShading || shading == aiShadingMode_Flat;
}

}  // namespace

std::vector<std::string> material_names(const aiScene& scene) {
  std::vector<std::string> names;
  for (unsigned i = 0; i < scene.mNumMaterials; ++i) {
    aiString name;
    names.emplace_back(scene.mMaterials[i]->Get(AI_MATKEY_NAME, name) == AI_SUCCESS ? name.C_Str() : "");
  }
  return names;
}

std::vector<int> diffuse_uv_sets(const aiScene& scene) {
  std::vector<int> sets(scene.mNumMaterials, 0);
  for (unsigned i = 0; i < scene.mNumMaterials; ++i) {
    const aiMaterial& m = *scene.mMaterials[i];
    for (aiTextureType type : {aiTextureType_BASE_COLOR, aiTextureType_DIFFUSE}) {
      aiString path;
      unsigned uv = 0;
      if (m.GetTextureCount(type) > 0 && m.GetTexture(type, 0, &path, nullptr, &uv) == AI_SUCCESS) {
        sets[i] = static_cast<int>(uv);
        break;
      }
    }
  }
  return sets;
}

void convert_materials(const aiScene& scene, ImportedAsset& out, AssetTextureTable& table) {
  const std::vector<std::string> names = material_names(scene);
  const SourceLocation file = file_location(out.path);
  out.materials.resize(scene.mNumMaterials);
  for (unsigned i = 0; i < scene.mNumMaterials; ++i) {
    const aiMaterial& m = *scene.mMaterials[i];
    AssetMaterial& mat = out.materials[i];
    mat.name = names[i];
    mat.where = file;
    if (gltf_format(out.format)) {
      read_metallic_roughness(scene, m, mat, table);
    } else {
      read_phong(scene, m, mat, table);
    }
    mat.emission = colour(m, AI_MATKEY_COLOR_EMISSIVE, RGB(0.0f)) * number(m, AI_MATKEY_EMISSIVE_INTENSITY, 1.0f);
    mat.emission_map = texture(scene, m, aiTextureType_EMISSIVE, table, mat.where);
    if (!mat.normal_map) mat.normal_map = texture(scene, m, aiTextureType_NORMALS, table, mat.where);
    int two_sided = 0;
    mat.double_sided = m.Get(AI_MATKEY_TWOSIDED, two_sided) == AI_SUCCESS && two_sided != 0;
  }
}

}  // namespace pt
