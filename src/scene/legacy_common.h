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

}  // namespace pt
