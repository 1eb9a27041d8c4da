// Shapes of the native format (import_native_shapes.cpp), and the material
// table they refer to by name (filled by import_native.cpp).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "scene/import_context.h"

namespace pt {

struct NativeMaterial {
  MaterialDesc desc;
  std::optional<Sourced<std::string>> texture;  // registered only if the material is used
  bool used = false;
  bool ok = true;
};

// Reads shapes[index] and appends it to ctx.scene.shapes, and its material
// (index into `materials`, -1 for the default material) to `shape_material`.
// A shape with errors is reported and skipped.
// Any shape may have a "transform" (import_transform.h); a shape of type
// "instance" goes to ctx.scene.instances instead (read_native_instance).
void read_native_shape(ImportContext& ctx, const JsonValue& v, std::size_t index,
                       std::vector<NativeMaterial>& materials, std::vector<int>& shape_material);

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
