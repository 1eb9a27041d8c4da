// Helpers shared by the two course-format importers (Path of Light and CGR).
#pragma once

#include <functional>
#include <string>
#include <string_view>

#include "scene/import_context.h"

namespace pt {

// Reads the required corner keys "v0", "v1", ... "v{n-1}" into out[0..n).
bool read_corners(ObjectReader& r, int n, Sourced<Vec3f>* out);

// The value of a legacy object's "type" key, or "" after reporting a missing
// or non-string type (an error: nothing can be done with the object then).
std::string read_legacy_type(ObjectReader& r);

// A "type" this renderer does not know in a legacy file. One or two edits from
// a supported one ("spehre"): an error with "did you mean" (the object is
// failed). Otherwise a warning (the file may come from a course variant with
// extra features) and the object is skipped.
void report_unknown_type(ObjectReader& r, std::string_view kind, const std::string& type,
                         std::initializer_list<std::string_view> supported);

// A value that files spell in several ways: the one of `keys` that is present
// (nullptr if none; two present is an error, and r fails).
const char* find_aliased(ObjectReader& r, std::initializer_list<const char*> keys);

// A light source's "type": its index in `supported`, or -1 after reporting a
// missing type (error) or an unknown one (report_unknown_type).
int read_light_type(ObjectReader& r, std::initializer_list<std::string_view> supported);

// The camera's "type" in either family: pinhole, or a thin lens under any of
// its spellings ("thinlens", CGR's "finite-aperture"); an unknown type close to
// one of those is an error, any other unknown type a warning (a pinhole is used).
CameraType read_camera_type(ObjectReader& r);

// The thin-lens keys of both families (docs/scene-format.md): the lens radius
// (or "aperture", its diameter) and the distance in focus, each under several
// spellings; "d" (an image-plane distance) is accepted and ignored.
void read_lens(ImportContext& ctx, ObjectReader& r, CameraDesc& cam);

// Top-level "spp" or "samples", and a "sampling" block, into render.spp.
void read_sampling(ImportContext& ctx, ObjectReader& top);

// Puts a quad whose corners form a rectangle listed in zig-zag order (v0 v1 v3
// v2 or v0 v2 v1 v3 go round it) in perimeter order, with a warning at the
// corner that moved. Any other quad is left for validation to judge.
void order_quad_corners(ImportContext& ctx, const Sourced<Vec3f>* corners, Quad& quad);

// Path of Light "arealight" (legacy_lights.cpp): an emissive quad or triangle,
// or emission on the shape named by "shapeid". Shapes must be read before.
void read_area_light(ImportContext& ctx, ObjectReader& r);

// Path of Light "trimesh" or "mesh" (legacy_mesh.cpp): a mesh file, inline
// "vertices" + "faces", or numbered "v0".."vN" + "f0".."fN", placed by
// "pos"/"center", "locX"/"locY"/"locZ" and "scale"/"sizeScale" (baked in).
// `object` is the shape's JSON object (looked through for a file under a key of the author's own).
void read_legacy_mesh(ImportContext& ctx, ObjectReader& r, const JsonValue& object, ShapeDesc& shape);

// A warning when the imported scene has no light source at all (every light
// skipped, or none given, and no emissive shape): the image will be black or
// show only the background.
void warn_if_unlit(ImportContext& ctx);

// Reads an item of a legacy list (a light or a shape) at `index`.
using LegacyItemReader = std::function<void(ImportContext& ctx, const JsonValue& v, std::size_t index)>;
// Reads a legacy material object; returns its index in the scene, or -1 after an error.
using LegacyMaterialReader = int (*)(ImportContext& ctx, const JsonValue& v);

// Reads the "scene" object both course families share: "backgroundcolor",
// optional "lightsources" and required "shapes", each item by its family's
// reader. Shapes are read first, so that an area light can name one.
void read_legacy_scene(ImportContext& ctx, const JsonValue& v, const LegacyItemReader& read_light,
                       const LegacyItemReader& read_shape);

// Ends a legacy shape whose geometry is read: its optional "material" (the
// default material when absent), the unknown-key check (a material key on the
// shape itself is named as such), and, if nothing was wrong, adds it to the scene.
void finish_legacy_shape(ImportContext& ctx, ObjectReader& r, const JsonValue& object, ShapeDesc shape,
                         LegacyMaterialReader read_material);

}  // namespace pt
