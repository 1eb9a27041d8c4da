// Helpers shared by the two course-format importers (Path of Light and CGR).
#pragma once

#include <string>
#include <string_view>

#include "scene/import_context.h"

namespace pt {

// Reads the required corner keys "v0", "v1", ... "v{n-1}" into out[0..n).
bool read_corners(ObjectReader& r, int n, Sourced<Vec3f>* out);

// The value of a legacy object's "type" key, or "" after reporting a missing
// or non-string type (an error: nothing can be done with the object then).
std::string read_legacy_type(ObjectReader& r);

// A "type" this renderer does not know in a legacy file: a warning (the file
// may come from a course variant with extra features); the object is skipped.
void warn_unsupported_type(ObjectReader& r, std::string_view kind, const std::string& type,
                           std::initializer_list<std::string_view> supported);

// Checks a light source's "type": true for "pointlight" (the only light both
// course families define; the reader then names it "point light"); otherwise
// reports it (an error if missing, a warning if unknown) and returns false.
bool accept_point_light(ObjectReader& r);

// Reads an item of a legacy list (a light or a shape) at `index`.
using LegacyItemReader = void (*)(ImportContext& ctx, const JsonValue& v, std::size_t index);
// Reads a legacy material object; returns its index in the scene, or -1 after an error.
using LegacyMaterialReader = int (*)(ImportContext& ctx, const JsonValue& v);

// Reads the "scene" object both course families share: "backgroundcolor",
// optional "lightsources" and required "shapes", each item by its family's reader.
void read_legacy_scene(ImportContext& ctx, const JsonValue& v, LegacyItemReader read_light,
                       LegacyItemReader read_shape);

// Ends a legacy shape whose geometry is read: its optional "material" (the
// default material when absent), the unknown-key check, and, if nothing was
// wrong, adds it to the scene.
void finish_legacy_shape(ImportContext& ctx, ObjectReader& r, ShapeDesc shape,
                         LegacyMaterialReader read_material);

}  // namespace pt
