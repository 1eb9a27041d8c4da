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

}  // namespace pt
