// The one place where a model file's materials (AssetMaterial, asset.h:
// MTL, COLLADA's Phong family, glTF's metallic-roughness) become ours
// (MaterialDesc): Lambert, the normalised Blinn-Phong of "phong", conductor,
// dielectric, coated diffuse and glTF's metallic-roughness, with textured colours and roughness, alpha
// cutouts, normal and bump maps (docs/importing.md has the tables). What the
// result does not show as the file means it is returned as a note, which the
// importer turns into one warning per kind and file.
#pragma once

#include <string>
#include <vector>

#include "scene/asset.h"
#include "scene/scene_description.h"

namespace pt {

// One thing about a material that the mapped one does not show as the file
// means it. Notes of the same `kind` are reported together.
struct MaterialNote {
  std::string kind;     // what was approximated or left out, also the message: "alpha (map_d, alphaMode) is not supported yet: ..."
  SourceLocation where;  // the statement or material that asks for it
  bool warning = true;   // false: a remark (what a path tracer has no use for)
};

// Where a mapped material reads a texture of the file.
enum class TextureSlot { Diffuse, Reflectance, Roughness, Metallic, Emission, Alpha, NormalMap, Displacement };

struct TextureUse {
  TextureSlot slot;
  int texture;  // index into ImportedAsset::textures (found or embedded)
  bool data;    // read as stored (roughness, masks, normal and bump maps), else sRGB-decoded colour
};

struct MappedMaterial {
  MaterialDesc desc;  // its texture indices are set by the caller from `textures`
  std::vector<TextureUse> textures;
  std::vector<MaterialNote> notes;
};

// `length_scale`: scene units per unit of the model file (the import's
// transform's scale), for bump heights (MTL -bm is in the file's units).
MappedMaterial map_asset_material(const AssetMaterial& m, const std::vector<AssetTexture>& textures,
                                  float length_scale = 1.0f);

// Sets the texture `index` (into SceneDescription::textures) at `slot` of `d`.
void set_texture(MaterialDesc& d, TextureSlot slot, int index);

// GGX alpha for a Blinn-Phong exponent (Walter et al. 2007: the lobes of
// exponent e and alpha sqrt(2 / (e + 2)) have the same width), in (0, 1].
float alpha_for_exponent(float exponent);

}  // namespace pt
