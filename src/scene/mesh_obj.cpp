#include "scene/mesh_obj.h"

#include "scene/obj_reader.h"

namespace pt {

bool load_obj(const std::string& path, TriangleMesh& out, std::string& error, ObjInfo* info, Diagnostics* diag) {
  ObjReadOptions options;
  options.one_mesh = true;
  options.max_bytes = kMaxObjFileBytes;
  ObjModel model;
  Diagnostics found;
  const bool read = read_obj(path, options, model, found);
  for (const Diagnostic& d : found.all()) {
    if (d.severity == Severity::Error && error.empty()) {
      error = d.message;
      if (d.where.line > 0)
        error += " (line " + std::to_string(d.where.line) + ", column " + std::to_string(d.where.col) + ")";
    }
    if (diag == nullptr) continue;
    if (d.severity == Severity::Error) diag->error(d.where, d.message);
    if (d.severity == Severity::Warning) diag->warning(d.where, d.message);
    if (d.severity == Severity::Note) diag->note(d.where, d.message);
  }
  if (!read) {
    if (error.empty()) error = "the file cannot be read";
    return false;
  }
  out = std::move(model.meshes[0].mesh);
  if (out.indices.empty()) {
    error = "the file holds no triangles or polygons";
    return false;
  }
  if (info) {
    info->materials = 0;
    for (std::size_t m = 1; m < model.materials.size(); ++m)
      info->materials += model.material_used[m] && model.materials[m] != kObjDefaultMaterial ? 1 : 0;
  }
  return true;
}

}  // namespace pt
