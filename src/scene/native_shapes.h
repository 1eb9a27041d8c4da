// Shapes of the native format (import_native_shapes.cpp), and the material
// table they refer to by name (import_native_materials.cpp).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "scene/import_context.h"
#include "scene/native_textures.h"

namespace pt {

// Which of a material's parameters a texture reference is for.
enum class MaterialTexture {
  Diffuse, URoughness, VRoughness, Eta, K, Reflectance, Metallic, Emission, NormalMap, Displacement
};

// A texture reference (native_textures.h: a name, an image file or an inline
// texture) read with its material, resolved once a shape uses the material.
struct PendingTexture {
  const JsonValue* ref;
  const char* key;  // the material key it was given for (messages)
  MaterialTexture slot;
  bool data;        // numbers rather than colour: image files read without sRGB decoding
};

struct NativeMaterial {
  MaterialDesc desc;
  std::vector<PendingTexture> textures;  // resolved only if the material is used
  const JsonValue* alpha = nullptr;      // "alpha": a number or a texture reference
  bool used = false;
  bool ok = true;
};

// The top-level "materials" object, in file order.
std::vector<NativeMaterial> read_materials(ImportContext& ctx, const JsonValue& v);
// Resolves the texture references and the alpha of a material some shape uses
// (resolve_texture_ref) and stores their indices in its description.
void resolve_material_textures(ImportContext& ctx, NativeTextures& textures, NativeMaterial& m);

// Reads shapes[index] and appends it to ctx.scene.shapes, and its material
// (index into `materials`, -1 for the default material) to `shape_material`.
// A shape with errors is reported and skipped.
// Any shape may have a "transform" (import_transform.h); a shape of type
// "instance" goes to ctx.scene.instances instead (read_native_instance); one
// of type "import" places a model file (import_asset.h) and may add objects
// (object_material grows with them; null inside an object, where an import
// is refused).
void read_native_shape(ImportContext& ctx, const JsonValue& v, std::size_t index,
                       std::vector<NativeMaterial>& materials, std::vector<int>& shape_material,
                       std::vector<std::vector<int>>* object_material);

// The material a shape (or instance) names: index into `materials`, -1 for
// none, -2 if unknown (reported with "did you mean").
int resolve_material(ImportContext& ctx, ObjectReader& r, std::vector<NativeMaterial>& materials);

// ---------------------------------------------------------------- instancing (import_native_instances.cpp)
// Whether shapes[i] is {"type": "instance", ...}.
bool is_instance(const JsonValue& v);
// Reads the top-level "objects" into ctx.scene.objects (each shape's material
// index into `materials` in object_material), before the shapes that place them.
void read_native_objects(ImportContext& ctx, const JsonValue& v, std::vector<NativeMaterial>& materials,
                         std::vector<std::vector<int>>& object_material);
// Reads an instance into ctx.scene.instances; its material, if any, is an
// index into `materials` until assemble_materials renumbers it.
void read_native_instance(ImportContext& ctx, const JsonValue& v, std::vector<NativeMaterial>& materials);
// A warning for each object no instance places (it is never drawn), at the object.
void warn_unplaced_objects(ImportContext& ctx);

}  // namespace pt
