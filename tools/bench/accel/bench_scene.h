// The scenes the acceleration benchmark and cross-check run on: a scene file
// (native, Path of Light or CGR, through the renderer's own loader), a bare
// OBJ or PLY mesh framed by a default camera, or a procedural tessellated
// sphere.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "geometry/shapes.h"
#include "render/camera/camera.h"

namespace pt::bench {

struct BenchScene {
  std::string name;         // "bunny", "sponza", "sphere", "path-of-light", or the file name
  std::string source;       // file path, or a description of the procedure
  SceneGeometry geometry;
  Camera camera;
  int width = 0, height = 0;  // camera resolution (one camera ray per pixel)
  std::vector<Vec3f> lights;  // shadow-ray targets: the scene's point lights, or one above the scene
  std::size_t triangles = 0;
  std::size_t primitives = 0;  // triangles + analytic shapes
};

struct SceneRequest {
  std::string what;           // a built-in name (see builtin_scene_names) or a path
  int width = 640, height = 480;
  std::size_t sphere_triangles = 1'000'000;
};

// "bunny", "sponza", "sphere", "path-of-light": the benchmark's scenes
// (bunny, Sponza and the Path of Light example from ../shared/assets and
// ../shared/seed-scenes).
std::vector<std::string> builtin_scene_names();

// Loads what `request` names. Returns false with `error` on failure; a built-in
// scene whose shared asset is absent gives `missing` = true and an error that
// says where it was looked for.
bool load_bench_scene(const SceneRequest& request, BenchScene& out, bool& missing, std::string& error);

}  // namespace pt::bench
