#include "scene/import_context.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <system_error>

#include "core/stopwatch.h"
#include "scene/mesh_obj.h"
#include "scene/ply.h"

namespace fs = std::filesystem;

namespace pt {

std::string describe_search(const std::string& scene_path, const std::string& written) {
  const fs::path w(written);
  std::error_code ec;
  if (w.is_absolute())
    return fs::is_directory(w, ec) ? "the path is a directory, not a file"
                                   : "the path is absolute and no file exists there";
  fs::path dir = fs::path(scene_path).parent_path();
  if (dir.empty()) dir = ".";
  const fs::path in_scene = fs::absolute(dir, ec) / w;
  const fs::path in_cwd = fs::current_path(ec) / w;
  for (const fs::path& candidate : {in_scene, in_cwd})
    if (fs::is_directory(candidate, ec)) {
      // Appended rather than "'" + ... : GCC 12 warns (-Wrestrict) on that
      // temporary's concatenation, wrongly.
      std::string message = "'";
      message += candidate.lexically_normal().string();
      message += "' is a directory, not a file";
      return message;
    }
  return "looked in the scene's directory ('" + in_scene.lexically_normal().string() +
         "') and the working directory ('" + in_cwd.lexically_normal().string() + "')";
}

std::optional<std::string> find_scene_file(ImportContext& ctx, const Sourced<std::string>& written,
                                           const std::string& what) {
  std::optional<std::string> resolved = resolve_scene_path(ctx.scene.source_path, written.value);
  if (!resolved) {
    ctx.diag().error(written.where, what + " '" + written.value + "' not found; " +
                                        describe_search(ctx.scene.source_path, written.value));
  }
  return resolved;
}

std::optional<int> add_texture(ImportContext& ctx, const Sourced<std::string>& written, bool raw) {
  const std::optional<std::string> resolved = find_scene_file(ctx, written, "texture file");
  if (!resolved) return std::nullopt;
  std::error_code ec;
  fs::path canonical = fs::weakly_canonical(*resolved, ec);
  const std::string key = (ec ? *resolved : canonical.string()) + (raw ? std::string(1, '\0') + "raw" : "");
  if (const auto it = ctx.texture_ids.find(key); it != ctx.texture_ids.end()) return it->second;
  const int id = static_cast<int>(ctx.scene.textures.size());
  ctx.scene.textures.push_back(TextureDesc{written.where, written.value, *resolved, raw});
  ctx.texture_ids.emplace(key, id);
  return id;
}

bool load_mesh_file(ImportContext& ctx, const Sourced<std::string>& written, ShapeDesc& shape) {
  shape.file = shape.field("file", written);
  const std::optional<std::string> resolved = find_scene_file(ctx, written, "mesh file");
  if (!resolved) return false;
  // The reader by extension (any case): .ply or .obj. Model files with a
  // scene of their own (glTF, COLLADA) are placed by {"type": "import"}.
  std::string extension = fs::path(*resolved).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (extension != ".ply" && extension != ".obj") {
    const bool model = extension == ".gltf" || extension == ".glb" || extension == ".dae";
    ctx.diag().error(written.where, model ? "a mesh reads a PLY or OBJ file; place a '" + extension +
                                                "' file with {\"type\": \"import\", \"file\": ...} (docs/importing.md)"
                                          : "unsupported mesh format '" + extension +
                                                "' (supported: .ply, .obj; .gltf, .glb and .dae through "
                                                "{\"type\": \"import\"})");
    return false;
  }
  TriangleMesh mesh;
  const auto start = Clock::now();
  std::string error;
  bool loaded = false;
  ObjInfo obj;
  if (extension == ".obj") {
    loaded = load_obj(*resolved, mesh, error, &obj, &ctx.diag());
  } else if (PlyError ply_error; !(loaded = load_ply(*resolved, mesh, ply_error))) {
    error = ply_error.message;
    if (ply_error.line > 0) error += " (header line " + std::to_string(ply_error.line) + ")";
  }
  ctx.scene.mesh_load_seconds += seconds_since(start);
  if (!loaded) {
    ctx.diag().error(written.where, "cannot read mesh '" + written.value + "': " + error);
    return false;
  }
  if (obj.materials > 0)
    ctx.diag().warning(written.where, "'" + written.value + "' names " + std::to_string(obj.materials) +
                                          " material(s) (MTL); a mesh has one material, so they are not used: place "
                                          "the file with {\"type\": \"import\"} to use them (docs/importing.md)");
  shape.geometry = std::move(mesh);
  return true;
}

int default_material(ImportContext& ctx) {
  if (!ctx.default_material) {
    MaterialDesc m;  // the defaults documented in scene_description.h
    m.name = "default";
    ctx.default_material = static_cast<int>(ctx.scene.materials.size());
    ctx.scene.materials.push_back(std::move(m));
  }
  return *ctx.default_material;
}

}  // namespace pt
