// Checks a SceneDescription's values, reporting each problem at the place in
// the file it came from (the Sourced locations). Run once, after importing,
// whatever the file's family. What is an error and what a warning is listed in
// docs/scene-format.md ("Validation").
#pragma once

#include "core/diagnostics.h"
#include "scene/loader.h"
#include "scene/scene_description.h"

namespace pt {

void validate_scene(const SceneDescription& scene, const LoadOptions& options, Diagnostics& diag);

// The part of the shapes' validation that the later stages rely on, for
// descriptions built in code (a loaded one has passed validate_scene): each
// shape's unusable problems (geometry/shape_base.h; a mesh index out of range,
// a non-finite value), reported as errors "shape i: ..." at the field. Returns
// false if there was any.
bool check_shapes_usable(const SceneDescription& scene, Diagnostics& diag);

}  // namespace pt
