// Triangle meshes of the Path of Light family. The course requires them (as an
// explicit list and as a PLY file) but gives no keys, so students' files spell
// them in several ways (docs/scene-format.md, "Meshes in Path of Light files").
#include <algorithm>
#include <cctype>
#include <string>
#include <vector>

#include "scene/json_lists.h"
#include "scene/legacy_common.h"
#include "scene/suggest.h"

namespace pt {
namespace {

constexpr std::initializer_list<const char*> kFileKeys = {"mPath", "modelpath", "plyPath", "filename", "path"};

// Built by append: `std::string(1, c) + std::to_string(i)` trips a GCC 12
// -Wrestrict false positive.
std::string numbered(char prefix, std::size_t i) {
  std::string name(1, prefix);
  name += std::to_string(i);
  return name;
}

bool names_mesh_file(const JsonValue& v) {
  if (!v.is_string() || v.as_string().size() < 4) return false;
  std::string ext = v.as_string().substr(v.as_string().size() - 4);
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".ply" || ext == ".obj";
}

// "f3": [i, j, k] or a convex polygon [i, j, k, l, ...] (split into a fan).
bool read_numbered_face(ReadContext& ctx, const JsonValue& v, const std::string& key, std::size_t vertex_count,
                        std::vector<uint32_t>& out) {
  if (!v.is_array() || v.as_array().size() < 3) {
    ctx.diag.error(ctx.at(v), "expected a list of at least 3 vertex indices for '" + key + "'");
    return false;
  }
  std::vector<uint32_t> polygon;
  for (const JsonValue& e : v.as_array()) {
    const double d = e.is_number() ? e.as_number() : -1.0;
    if (!e.is_number() || !e.is_integer() || d < 0 || d >= static_cast<double>(vertex_count)) {
      ctx.diag.error(ctx.at(e), "'" + key + "' holds an index that is not a vertex: expected an integer from 0 to " +
                                    std::to_string(vertex_count) + " - 1");
      return false;
    }
    polygon.push_back(static_cast<uint32_t>(d));
  }
  for (std::size_t i = 1; i + 1 < polygon.size(); ++i) out.insert(out.end(), {polygon[0], polygon[i], polygon[i + 1]});
  return true;
}

// "v0", "v1", ... and "f0", "f1", ... (each numbering from 0 without gaps).
bool read_numbered(ObjectReader& r, TriangleMesh& m) {
  bool ok = true;
  for (std::size_t i = 0;; ++i) {
    Sourced<Vec3f> p;
    const std::string key = numbered('v', i);
    if (!r.get(key)) break;
    ok = r.read(key, p) && ok;
    m.positions.push_back(p.value);
  }
  for (std::size_t i = 0;; ++i) {
    const std::string key = numbered('f', i);
    const JsonValue* f = r.get(key);
    if (!f) break;
    ok = read_numbered_face(r.context(), *f, key, m.positions.size(), m.indices) && ok;
  }
  if (ok && m.indices.empty()) {
    r.context().diag.error(r.where(), "a mesh given by 'v0'..'vN' needs its faces 'f0'..'fN'");
    ok = false;
  }
  return ok;
}

// No geometry key: a file under a key of the author's own, or nothing at all.
void report_missing_geometry(ImportContext& ctx, ObjectReader& r, const JsonValue& object) {
  const std::vector<std::string> file_keys(kFileKeys.begin(), kFileKeys.end());
  for (const JsonMember& member : object.as_object()) {
    if (!names_mesh_file(member.value) || r.get(member.key) == nullptr) continue;
    ctx.diag().error(ctx.doc().location(member.key_offset),
                     "'" + member.key + "' is not a key for the mesh's file; use one of " + quoted_list(file_keys));
    r.fail();
    return;
  }
  ctx.diag().error(r.where(), "a mesh needs its triangles: a PLY or OBJ file under " + quoted_list(file_keys) +
                                  ", or 'vertices' and 'faces', or 'v0'..'vN' and 'f0'..'fN'");
  r.fail();
}

void read_geometry(ImportContext& ctx, ObjectReader& r, const JsonValue& object, ShapeDesc& shape) {
  TriangleMesh& m = shape.geometry.emplace<TriangleMesh>();
  if (const char* key = find_aliased(r, kFileKeys)) {
    Sourced<std::string> path;
    if (!r.read(key, path) || !load_mesh_file(ctx, path, shape)) r.fail();
    return;
  }
  if (!r.ok()) return;
  if (r.get("v0")) {
    if (!read_numbered(r, m)) r.fail();
    return;
  }
  const JsonValue* vertices = r.get("vertices");
  const char* faces_key = r.get("faces") ? "faces" : "indices";
  const JsonValue* faces = r.get(faces_key);
  if (!vertices && !faces) return report_missing_geometry(ctx, r, object);
  if (!vertices || !faces) {
    ctx.diag().error(r.where(), vertices ? "a mesh with 'vertices' needs 'faces' (or 'indices')"
                                         : std::string("a mesh with '") + faces_key + "' needs 'vertices'");
    r.fail();
    return;
  }
  if (!read_vec3_list(ctx.read, *vertices, "vertices", m.positions) ||
      !read_index_list(ctx.read, *faces, faces_key, m.positions.size(), /*allow_flat=*/true, m.indices))
    r.fail();
}

// "scale"/"sizeScale" (a number or [x, y, z]) about the model's origin, then
// "pos"/"center" or "locX"/"locY"/"locZ" as a translation: baked into the vertices.
void read_placement(ImportContext& ctx, ObjectReader& r, TriangleMesh& m) {
  Vec3f scale(1.0f), offset(0.0f);
  if (const char* key = find_aliased(r, {"scale", "sizeScale"})) {
    Sourced<float> uniform;
    Sourced<Vec3f> per_axis;
    const JsonValue* v = r.get(key);
    if (v->is_number() ? r.read(key, uniform) : r.read(key, per_axis))
      scale = v->is_number() ? Vec3f(uniform.value) : per_axis.value;
  }
  const char* at = find_aliased(r, {"pos", "center"});
  const bool loc = r.get("locX") || r.get("locY") || r.get("locZ");
  if (at && loc) {
    ctx.diag().error(ctx.read.at(*r.get(at)), std::string("'") + at + "' and 'locX'/'locY'/'locZ' say the same "
                                                                      "thing; give one of them");
    r.fail();
  } else if (at) {
    Sourced<Vec3f> p;
    if (r.read(at, p)) offset = p.value;
  } else if (loc) {
    Sourced<float> x{0.0f}, y{0.0f}, z{0.0f};
    if (r.read("locX", x) & r.read("locY", y) & r.read("locZ", z)) offset = Vec3f(x.value, y.value, z.value);
  }
  if (!r.ok()) return;
  for (Vec3f& p : m.positions) p = p * scale + offset;
  // Normals take the inverse transpose of the scale (a no-op for a uniform one).
  for (Vec3f& n : m.normals) {
    const Vec3f k(n.x / scale.x, n.y / scale.y, n.z / scale.z);
    if (length(k) > 0.0f) n = normalize(k);
  }
}

}  // namespace

void read_legacy_mesh(ImportContext& ctx, ObjectReader& r, const JsonValue& object, ShapeDesc& shape) {
  read_geometry(ctx, r, object, shape);
  if (r.ok()) read_placement(ctx, r, std::get<TriangleMesh>(shape.geometry));
}

}  // namespace pt
