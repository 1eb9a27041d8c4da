// Scene loading: reads a JSON scene file, detects its family (native, Path of
// Light, CGR), and produces a validated SceneDescription. Meshes (PLY) are read
// here; textures are only checked to exist (decoded once, later, by the
// render-scene builder, and only if a material uses them).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/diagnostics.h"
#include "scene/resolution_limits.h"
#include "scene/scene_description.h"

namespace pt {

struct LoadOptions {
  // Legacy formats: unknown keys become errors instead of warnings.
  bool strict = false;
  // Largest accepted film (width, height, width x height).
  ResolutionLimits limits;
  // `--set key=value` overrides applied to the file's text before it is
  // imported (scene/overrides.h), in order.
  std::vector<std::string> overrides;
};

// Returns the description, or std::nullopt if any error was reported. All
// problems of the file are reported to `diag` (not only the first), each with
// file:line:col. Never throws for bad input, never exits.
std::optional<SceneDescription> load_scene(const std::string& path, const LoadOptions& options,
                                           Diagnostics& diag);

// Same, from text already in memory (`path` is used for messages and for
// resolving relative paths).
std::optional<SceneDescription> load_scene_from_string(const std::string& path, std::string text,
                                                       const LoadOptions& options, Diagnostics& diag);

// Resolves a relative path written in a scene file: first against the scene
// file's directory, then against the working directory. Returns the existing
// file's path, or std::nullopt if neither exists. Anything but a directory
// counts (a FIFO, a device, a symbolic link loop): its reader then says what
// it is (core/file_access.h) instead of "not found". Absolute paths are returned
// as they are if they exist.
std::optional<std::string> resolve_scene_path(const std::string& scene_path, const std::string& written);

}  // namespace pt
