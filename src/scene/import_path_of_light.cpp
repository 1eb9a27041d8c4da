// The "Path of Light" course format (see /work/shared/seed-scenes/CONVENTIONS.md
// and docs/scene-format.md): Z-up, "lookat" is a direction, point lights give
// "id"/"is" with a 1/(4 pi r^2) falloff, "plane" is a quad with named corners,
// linear display (value * 255).
#include <string>

#include "scene/importers.h"
#include "scene/json_lists.h"
#include "scene/legacy_common.h"

namespace pt {
namespace {

constexpr float kInv4Pi = 1.0f / (4.0f * kPi);

// A required value that files spell in several ways: exactly one of `keys`
// must be present (the first is the one the messages name).
void read_aliased(ObjectReader& r, std::initializer_list<const char*> keys, Sourced<float>& out) {
  const char* found = nullptr;
  for (const char* key : keys) {
    if (!r.get(key)) continue;
    if (found) {
      r.context().diag.error(r.context().at(*r.get(key)), std::string("'") + key + "' and '" + found +
                                                              "' say the same thing; give one of them");
      r.fail();
      return;
    }
    found = key;
  }
  if (!found) {
    r.require(*keys.begin());
    r.fail();
    return;
  }
  r.read(found, out);
}

void read_camera(ImportContext& ctx, const JsonValue& v) {
  if (!expect_object(ctx.read, v, "camera")) return;
  ObjectReader r(ctx.read, v, "camera");
  CameraDesc& cam = ctx.scene.camera;
  cam.where = r.where();
  SourceLocation type_at;
  const int type = read_choice(r, "type", {"pinhole", "thinlens"}, &type_at);
  if (type == 1) cam.type = CameraType::ThinLens;
  r.read_required("width", ctx.scene.film.width);
  r.read_required("height", ctx.scene.film.height);
  r.read_required("fov", cam.fov_y_deg);  // full angle; the course's images are square
  r.read_required("position", cam.position);
  Sourced<Vec3f> direction;
  if (r.read_required("lookat", direction))  // a direction: the target is position + lookat
    cam.look_at = Sourced<Vec3f>(cam.position.value + direction.value, direction.where);
  r.read_required("up", cam.up);
  cam.left_handed = false;  // image right = forward x up
  if (cam.type == CameraType::ThinLens) {
    // No official keys exist: ours first, then the unambiguous spellings seen in
    // third-party files (pbrt's "focaldistance", snake case). docs/scene-format.md.
    read_aliased(r, {"lensradius", "lens_radius", "apertureradius", "aperture_radius"}, cam.lens_radius);
    read_aliased(r, {"focusdistance", "focaldistance", "focus_distance", "focal_distance"}, cam.focus_distance);
  }
  r.finish();
}

void read_light(ImportContext& ctx, const JsonValue& v, std::size_t index) {
  if (!expect_object(ctx.read, v, "lightsources[" + std::to_string(index) + "]")) return;
  ObjectReader r(ctx.read, v, "light source");
  if (!accept_point_light(r)) return;
  PointLightDesc light;
  light.where = r.where();
  r.read_required("position", light.position);
  Sourced<RGB> diffuse, specular;
  // The course shades kd Cd id cos / (4 pi r^2); a native point light of intensity I
  // shades kd Cd I cos / r^2 in the classic integrator, so I = id / (4 pi).
  if (r.read_required("id", diffuse)) light.intensity = Sourced<RGB>(diffuse.value * kInv4Pi, diffuse.where);
  if (r.read_required("is", specular))
    light.specular_intensity = Sourced<RGB>(specular.value * kInv4Pi, specular.where);
  r.finish();
  if (r.ok()) ctx.scene.lights.emplace_back(std::move(light));
}

// An inline material; returns its index in scene.materials, or -1 if it was bad.
int read_material(ImportContext& ctx, const JsonValue& v) {
  if (!expect_object(ctx.read, v, "material")) return -1;
  ObjectReader r(ctx.read, v, "material");
  MaterialDesc m;
  m.where = r.where();
  r.read("ks", m.ks);
  r.read("kd", m.kd);
  r.read("specularexponent", m.exponent);
  r.read("diffusecolor", m.diffuse);
  r.read("kr", m.reflectivity);
  Sourced<std::string> texture;
  if (r.get("tPath") && r.read("tPath", texture)) m.texture = add_texture(ctx, texture);
  r.allow({"tWidth", "tHeight"});  // the course's claimed image size; the real size is used
  r.finish();
  if (!r.ok()) return -1;
  m.name = "material " + std::to_string(ctx.scene.materials.size());
  ctx.scene.materials.push_back(std::move(m));
  return static_cast<int>(ctx.scene.materials.size() - 1);
}

// "trimesh": inline "vertices" + "faces" (or "indices"), or a PLY path under
// "mPath", "plyPath" or "filename" (keys seen in third-party files).
void read_trimesh(ImportContext& ctx, ObjectReader& r, ShapeDesc& shape) {
  TriangleMesh& m = shape.geometry.emplace<TriangleMesh>();
  for (const char* key : {"mPath", "plyPath", "filename"}) {
    if (const JsonValue* v = r.get(key)) {
      Sourced<std::string> path;
      if (!read_value(ctx.read, *v, key, path) || !load_mesh_file(ctx, path, shape)) r.fail();
      return;
    }
  }
  const JsonValue* vertices = r.require("vertices");
  const JsonValue* faces = r.get("faces");
  const char* faces_key = "faces";
  if (!faces) {
    faces = r.get("indices");
    faces_key = "indices";
  }
  if (!faces) {
    ctx.diag().error(r.where(), "a trimesh needs 'vertices' and 'faces' (or 'indices'), or a PLY file under "
                                "'mPath', 'plyPath' or 'filename'");
    r.fail();
    return;
  }
  if (!vertices || !read_vec3_list(ctx.read, *vertices, "vertices", m.positions) ||
      !read_index_list(ctx.read, *faces, faces_key, m.positions.size(), /*allow_flat=*/true, m.indices))
    r.fail();
}

void read_shape(ImportContext& ctx, const JsonValue& v, std::size_t index) {
  if (!expect_object(ctx.read, v, "shapes[" + std::to_string(index) + "]")) return;
  ObjectReader r(ctx.read, v, "shape");
  const std::string type = read_legacy_type(r);
  if (type.empty()) return;
  r.set_what(type);
  ShapeDesc shape;
  shape.where = r.where();
  shape.type = type;
  if (type == "sphere") {
    Sourced<Vec3f> center;
    Sourced<float> radius{1.0f};
    r.read_required("center", center);
    r.read_required("radius", radius);
    shape.geometry = make_sphere(center, shape.field("radius", radius), Vec3f(0, 0, 1));  // the course's world is Z-up
  } else if (type == "plane") {
    Sourced<Vec3f> c[4];  // a planar quad; corners looked up by name (key order is scrambled)
    read_corners(r, 4, c);
    shape.geometry = Quad{{c[0], c[1], c[2], c[3]}};
  } else if (type == "triangle") {
    Sourced<Vec3f> c[3];
    read_corners(r, 3, c);
    shape.geometry = make_triangle(c[0], c[1], c[2]);
  } else if (type == "trimesh") {
    read_trimesh(ctx, r, shape);
  } else {
    warn_unsupported_type(r, "shape", type, {"sphere", "plane", "triangle", "trimesh"});
    return;
  }
  Sourced<std::string> id;
  r.read("id", id);
  shape.name = id.value;
  finish_legacy_shape(ctx, r, std::move(shape), read_material);
}

}  // namespace

void import_path_of_light(ImportContext& ctx) {
  SceneDescription& scene = ctx.scene;
  scene.film.display = DisplayTransform::Linear;  // the course writes value * 255, no gamma
  scene.render.integrator = std::string("whitted");
  ObjectReader top(ctx.read, ctx.doc().root(), "the scene file");
  top.read("nbounces", scene.render.max_depth);
  if (const JsonValue* v = top.require("camera")) read_camera(ctx, *v);
  if (const JsonValue* v = top.require("scene")) read_legacy_scene(ctx, *v, read_light, read_shape);
  top.finish();
}

}  // namespace pt
