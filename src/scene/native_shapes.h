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
void read_native_shape(ImportContext& ctx, const JsonValue& v, std::size_t index,
                       std::vector<NativeMaterial>& materials, std::vector<int>& shape_material);

}  // namespace pt
