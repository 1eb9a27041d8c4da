// The one place where a model file's materials (AssetMaterial, asset.h:
// MTL, COLLADA's Phong family, glTF's metallic-roughness) become ours
// (MaterialDesc). Today's materials are Lambert, the normalised Blinn-Phong
// of "phong", mirror and glass with one diffuse texture and emission, so
// most file materials are approximated; each approximation is returned as a
// note, which the importer turns into one warning per kind and file. When
// rough conductors and dielectrics, textured parameters, alpha and normal
// maps exist, they plug in here (docs/importing.md has the tables).
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

struct MappedMaterial {
  MaterialDesc desc;      // desc.texture is left empty: the caller registers `texture`
  int texture = -1;       // the asset texture (index into ImportedAsset::textures) the result reads, or -1
  std::vector<MaterialNote> notes;
};

MappedMaterial map_asset_material(const AssetMaterial& m, const std::vector<AssetTexture>& textures);

// The normalised Blinn-Phong exponent whose lobe is closest to a microfacet
// lobe of roughness `roughness` (alpha = roughness^2): 2 / alpha^2 - 2,
// clamped to [1, 10000].
float blinn_exponent_for_roughness(float roughness);

}  // namespace pt
