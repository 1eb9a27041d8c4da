// Native-format shapes: sphere, quad, triangle, cylinder, mesh, disc, polygon, cone, plane.
#include <string>

#include "scene/import_asset.h"
#include "scene/import_transform.h"
#include "scene/json_lists.h"
#include "scene/native_shapes.h"
#include "scene/suggest.h"

namespace pt {
namespace {

// An infinite plane is no primitive of either backend (geometry/shapes/plane.h),
// so it cannot be an instance: its transform is applied to it here (point as a
// point, normal by the inverse transpose, tangent as a vector; uv_scale kept).
void bake_plane_transform(ShapeDesc& shape) {
  auto* plane = std::get_if<InfinitePlane>(&shape.geometry);
  if (plane == nullptr || !shape.transform) return;
  const Transform& t = shape.transform->value;
  shape.geometry = make_plane(t.point(plane->point), t.normal(plane->normal), t.vector(plane->tangent), plane->uv_scale);
  shape.transform.reset();
}


// "vertices": exactly n points, or (at_least) n or more.
bool read_vertices(ObjectReader& r, std::size_t n, std::vector<Sourced<Vec3f>>& out, bool at_least = false) {
  const JsonValue* v = r.require("vertices");
  if (!v) return false;
  ReadContext& ctx = r.context();
  const std::string expected = "an array of " + std::string(at_least ? "at least " : "") + std::to_string(n) +
                               " points [x, y, z]";
  const std::size_t size = v->is_array() ? v->as_array().size() : 0;
  if (!v->is_array() || size < n || (size > n && !at_least)) {
    ctx.diag.error(ctx.at(*v), "expected " + expected + " for 'vertices' of a " + r.what());
    r.fail();
    return false;
  }
  bool ok = true;
  out.resize(size);
  for (std::size_t i = 0; i < size; ++i) {
    const std::string label = "vertices[" + std::to_string(i) + "]";
    ok = read_value(ctx, v->as_array()[i], label, out[i]) && ok;
  }
  if (!ok) r.fail();
  return ok;
}

// Each reader fills shape.geometry, and shape.fields with the locations of the
// fields the shape's check() names.
void read_sphere(ObjectReader& r, ShapeDesc& shape) {
  Sourced<Vec3f> center;
  Sourced<float> radius{1.0f};
  Sourced<Vec3f> pole{Vec3f(0, 1, 0)};
  r.read_required("center", center);
  r.read_required("radius", radius);
  r.read("pole", pole);
  shape.geometry = make_sphere(center, shape.field("radius", radius), shape.field("pole", pole));
}

void read_quad(ObjectReader& r, ShapeDesc& shape) {
  std::vector<Sourced<Vec3f>> v(4);
  read_vertices(r, 4, v);
  shape.geometry = Quad{{v[0], v[1], v[2], v[3]}};
}

void read_triangle(ObjectReader& r, ShapeDesc& shape) {
  std::vector<Sourced<Vec3f>> v(3);
  read_vertices(r, 3, v);
  shape.geometry = make_triangle(v[0], v[1], v[2]);
}

void read_cylinder(ObjectReader& r, ShapeDesc& shape) {
  Sourced<Vec3f> p0, p1;
  Sourced<float> radius{1.0f};
  r.read_required("p0", p0);
  r.read_required("p1", p1);
  r.read_required("radius", radius);
  shape.geometry = Cylinder{p0, p1, shape.field("radius", radius)};
}

void read_disc(ObjectReader& r, ShapeDesc& shape) {
  Sourced<Vec3f> center, normal{Vec3f(0, 1, 0)};
  Sourced<float> radius{1.0f}, inner_radius{0.0f};
  r.read_required("center", center);
  r.read_required("normal", normal);
  r.read_required("radius", radius);
  r.read("inner_radius", inner_radius);
  shape.geometry = make_disc(center, shape.field("normal", normal), shape.field("radius", radius),
                             shape.field("inner_radius", inner_radius));
}

// Each corner's location is recorded as "vertices[i]", where check() reports
// a corner off the plane or a reflex one.
void read_polygon(ObjectReader& r, ShapeDesc& shape) {
  std::vector<Sourced<Vec3f>> v;
  if (!read_vertices(r, 3, v, /*at_least=*/true)) return;
  std::vector<Vec3f> corners;
  for (std::size_t i = 0; i < v.size(); ++i) corners.push_back(shape.field("vertices[" + std::to_string(i) + "]", v[i]));
  shape.geometry = make_polygon(std::move(corners));
}

void read_cone(ObjectReader& r, ShapeDesc& shape) {
  Sourced<Vec3f> p0, p1;
  Sourced<float> radius{1.0f}, top_radius{0.0f};
  r.read_required("p0", p0);
  r.read_required("p1", p1);
  r.read_required("radius", radius);
  r.read("top_radius", top_radius);
  shape.geometry = Cone{p0, p1, shape.field("radius", radius), shape.field("top_radius", top_radius)};
}

void read_plane(ObjectReader& r, ShapeDesc& shape) {
  Sourced<Vec3f> point, normal{Vec3f(0, 1, 0)}, tangent{Vec3f(0.0f)};
  Sourced<float> uv_scale{1.0f};
  r.read_required("point", point);
  r.read_required("normal", normal);
  r.read("tangent", tangent);
  r.read("uv_scale", uv_scale);
  shape.geometry = make_plane(point, shape.field("normal", normal), shape.field("tangent", tangent),
                              shape.field("uv_scale", uv_scale));
}

void read_mesh(ImportContext& ctx, ObjectReader& r, ShapeDesc& shape) {
  TriangleMesh& m = shape.geometry.emplace<TriangleMesh>();
  const JsonValue* file = r.get("file");
  const JsonValue* positions = r.get("positions");
  const JsonValue* indices = r.get("indices");
  const JsonValue* normals = r.get("normals");
  const JsonValue* uvs = r.get("uvs");
  if (file && (positions || indices || normals || uvs)) {
    ctx.diag().error(r.where(), "a mesh has either 'file' or inline 'positions' and 'indices', not both");
    r.fail();
    return;
  }
  if (file) {
    Sourced<std::string> path;
    if (!read_value(ctx.read, *file, "file", path) || !load_mesh_file(ctx, path, shape)) r.fail();
    return;
  }
  if (!positions || !indices) {
    ctx.diag().error(r.where(), "a mesh needs 'file' (a PLY file) or inline 'positions' and 'indices'");
    r.fail();
    return;
  }
  bool ok = read_vec3_list(ctx.read, *positions, "positions", m.positions);
  ok = ok && read_index_list(ctx.read, *indices, "indices", m.positions.size(), /*allow_flat=*/false, m.indices);
  if (normals && read_vec3_list(ctx.read, *normals, "normals", m.normals) && m.normals.size() != m.positions.size()) {
    ctx.diag().error(ctx.read.at(*normals), "'normals' has " + std::to_string(m.normals.size()) +
                                                " entries, but 'positions' has " + std::to_string(m.positions.size()));
    ok = false;
  }
  if (uvs && read_vec2_list(ctx.read, *uvs, "uvs", m.uvs) && m.uvs.size() != m.positions.size()) {
    ctx.diag().error(ctx.read.at(*uvs), "'uvs' has " + std::to_string(m.uvs.size()) + " entries, but 'positions' has " +
                                            std::to_string(m.positions.size()));
    ok = false;
  }
  if (!ok) r.fail();
}

}  // namespace

int resolve_material(ImportContext& ctx, ObjectReader& r, std::vector<NativeMaterial>& materials) {
  Sourced<std::string> name;
  const JsonValue* v = r.get("material");
  if (!v) return -1;
  if (!read_value(ctx.read, *v, "material", name)) return -2;
  std::vector<std::string> names;
  for (std::size_t i = 0; i < materials.size(); ++i) {
    if (materials[i].desc.name == name.value) {
      materials[i].used = true;
      return static_cast<int>(i);
    }
    names.push_back(materials[i].desc.name);
  }
  std::string message = "unknown material '" + name.value + "'";
  message += did_you_mean(name.value, names,
                          names.empty() ? "; the scene defines no materials"
                                        : "; the scene defines " + quoted_list(names, "and"));
  ctx.diag().error(name.where, std::move(message));
  return -2;
}

void read_native_shape(ImportContext& ctx, const JsonValue& v, std::size_t index,
                       std::vector<NativeMaterial>& materials, std::vector<int>& shape_material,
                       std::vector<std::vector<int>>* object_material) {
  if (!expect_object(ctx.read, v, "shapes[" + std::to_string(index) + "]")) return;
  if (is_instance(v)) return read_native_instance(ctx, v, materials);
  if (is_import(v)) {
    if (object_material) return read_native_import(ctx, v, materials, shape_material, *object_material);
    ctx.diag().error(ctx.read.at(v), "an object cannot import a model file (the import places its own instances); "
                                     "import it under \"shapes\"");
    return;
  }
  ObjectReader r(ctx.read, v, "shape");
  // "instance" and "import" are read above; listed for the "did you mean" of a misspelt type.
  static const std::vector<std::string> kTypes = {"sphere", "quad",    "triangle", "cylinder", "mesh", "disc",
                                                  "polygon", "cone", "plane",    "instance", "import"};
  const int type = read_choice(r, "type", kTypes);
  if (type == -1) r.require("type");
  if (type < 0) return;
  r.set_what(kTypes[static_cast<std::size_t>(type)]);

  ShapeDesc shape;
  shape.where = r.where();
  Sourced<std::string> name;
  r.read("name", name);
  shape.name = name.value;
  const int material = resolve_material(ctx, r, materials);
  shape.type = kTypes[static_cast<std::size_t>(type)];
  switch (type) {
    case 0: read_sphere(r, shape); break;
    case 1: read_quad(r, shape); break;
    case 2: read_triangle(r, shape); break;
    case 3: read_cylinder(r, shape); break;
    case 4: read_mesh(ctx, r, shape); break;
    case 5: read_disc(r, shape); break;
    case 6: read_polygon(r, shape); break;
    case 7: read_cone(r, shape); break;
    default: read_plane(r, shape); break;
  }
  if (const JsonValue* t = r.get("transform"); t && !read_transform(ctx.read, *t, shape.transform)) r.fail();
  bake_plane_transform(shape);
  r.finish();
  if (!r.ok()) return;
  // An unknown material is already an error; the shape is kept (with the
  // default material) so that validation still reports its other problems
  // in the same run.
  ctx.scene.shapes.push_back(std::move(shape));
  shape_material.push_back(material == -2 ? -1 : material);
}

}  // namespace pt
