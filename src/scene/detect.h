// Which family a scene file belongs to (docs/scene-format.md, "Detection"):
//  - native:        top-level "format": "pathtracer-scene" (with "version": 1);
//  - CGR:           a top-level "scene" object, and "rendermode" at the top level
//                   or "lookAt"/"upVector" in "camera";
//  - Path of Light: a top-level "scene" object and "lookat"/"up" in "camera".
// Anything else is reported, naming the formats and what was looked for.
#pragma once

#include <optional>

#include "core/diagnostics.h"
#include "scene/json.h"
#include "scene/scene_description.h"

namespace pt {

std::optional<SceneFormat> detect_scene_format(const JsonDocument& doc, Diagnostics& diag);

// The marker that identifies the native format, and the version this build reads.
inline constexpr const char* kNativeFormatName = "pathtracer-scene";
inline constexpr int kNativeFormatVersion = 1;

}  // namespace pt
