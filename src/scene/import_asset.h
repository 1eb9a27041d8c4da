// Model files in a scene (docs/importing.md): the native format's
// {"type": "import", "file": "model.gltf", ...} shape, and a model file given
// as the scene itself. The file is read into the neutral record
// (asset_reader.h); here it becomes shapes, objects and instances, materials
// (import_materials.h), textures, a camera and lights of the SceneDescription.
#pragma once

#include <string>
#include <vector>

#include "scene/native_shapes.h"

namespace pt {

// Whether `v` is {"type": "import", ...}.
bool is_import(const JsonValue& v);

// Reads an import entry of "shapes" and places the file: meshes placed once
// become shapes (with their node's transform), meshes placed several times an
// object with one instance per placement (one copy of the geometry); its
// materials (unless "material" replaces them) are appended to `materials` and
// used; shape_material and object_material grow with the scene's shapes and
// objects. The file's lights join the scene's ("lights": false leaves them
// out); its camera is kept in ctx.imported_camera for a scene without one.
void read_native_import(ImportContext& ctx, const JsonValue& v, std::vector<NativeMaterial>& materials,
                        std::vector<int>& shape_material, std::vector<std::vector<int>>& object_material);

// For a native scene without a "camera": an imported file's camera, or else
// (when the scene imports a file) a camera framed on the scene's bounds, each
// with a note. Returns false if neither applies (the camera is then missing).
bool camera_from_imports(ImportContext& ctx, bool has_imports);

// A model file given as the scene: the native scene text that imports it
// (a path integrator, its camera or a framing one), and the lighting it gets
// after loading when it brings none (light_model_scene).
std::string model_scene_text(const std::string& model_path);
void light_model_scene(SceneDescription& scene, Diagnostics& diag);

}  // namespace pt
