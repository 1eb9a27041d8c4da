// The native format's "transform" (docs/scene-format.md, "Transforms"): a list
// of steps, each an object with one key, applied to the object in the order
// listed (the first step acts first, as in Mitsuba 3's <transform>).
#pragma once

#include <optional>

#include "core/transform.h"
#include "scene/json_reader.h"

namespace pt {

// Reads `v` (the value of "transform"). An identity result leaves `out`
// empty (no transform, no cost). On a problem (an unknown step, a wrong
// number count, a singular, non-finite or non-affine matrix) reports it at
// the step and returns false.
bool read_transform(ReadContext& ctx, const JsonValue& v, std::optional<Sourced<Transform>>& out);

}  // namespace pt
