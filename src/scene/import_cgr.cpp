// The "CGR" course format (see /work/shared/seed-scenes/CONVENTIONS.md and
// docs/scene-format.md): Y-up, "lookAt" is a target point, left-handed image
// frame, point lights without distance falloff, cylinder "height" is half the
// length, "rendermode" picks the integrator.
#include <cmath>
#include <string>

#include "scene/cgr_triangle_runs.h"
#include "scene/importers.h"
#include "scene/legacy_common.h"

namespace pt {
namespace {

constexpr int kDefaultBounces = 8;       // "nbounces" may be absent
constexpr float kCourseExposure = 0.1f;  // the value in every course file

void read_camera(ImportContext& ctx, const JsonValue& v) {
  if (!expect_object(ctx.read, v, "camera")) return;
  ObjectReader r(ctx.read, v, "camera");
  CameraDesc& cam = ctx.scene.camera;
  cam.where = r.where();
  cam.type = read_camera_type(r);
  r.read_required("width", ctx.scene.film.width);
  r.read_required("height", ctx.scene.film.height);
  r.read_required("position", cam.position);
  r.read_required("lookAt", cam.look_at);  // a target point
  r.read_required("upVector", cam.up);
  r.read_required("fov", cam.fov_y_deg);   // vertical, degrees
  cam.left_handed = true;                  // image right = up x forward
  cam.film_offset = Vec2f(-1.0f, 0.0f);    // the course's pixel x looks through our x - 1 (docs/rendering.md)
  if (cam.type == CameraType::ThinLens) read_lens(ctx, r, cam);  // "finite-aperture": docs/scene-format.md
  // The course never defines "exposure"; its display mapping (DisplayTransform::CgrCourse)
  // is fitted to reference images that all use 0.1, so the value is not applied.
  Sourced<float> exposure;
  if (r.read("exposure", exposure) && exposure.where.valid() && exposure.value != kCourseExposure) {
    ctx.diag().warning(exposure.where, "exposure " + format_number(exposure.value) +
                                           " has no effect: the CGR display mapping is fixed (fitted to the "
                                           "course's images, which use 0.1)");
  }
  r.finish();
}

void read_light(ImportContext& ctx, const JsonValue& v, std::size_t index) {
  if (!expect_object(ctx.read, v, "lightsources[" + std::to_string(index) + "]")) return;
  ObjectReader r(ctx.read, v, "light source");
  if (read_light_type(r, {"pointlight"}) != 0) return;
  r.set_what("point light");
  PointLightDesc light;
  light.where = r.where();
  r.read_required("position", light.position);
  if (r.read_required("intensity", light.intensity)) light.specular_intensity = light.intensity;
  light.inverse_square = false;  // the course's Phong lights do not fall off with distance
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
  r.read("specularcolor", m.specular);
  // "reflectivity" applies only when "isreflective" is true.
  Sourced<bool> reflective{false};
  Sourced<float> reflectivity{1.0f};
  r.read("isreflective", reflective);
  r.read("reflectivity", reflectivity);
  m.reflectivity = reflective.value ? reflectivity : Sourced<float>(0.0f, reflective.where);
  r.read("isrefractive", m.refractive);
  r.read("refractiveindex", m.ior);
  r.finish();
  if (!r.ok()) return -1;
  m.name = "material " + std::to_string(ctx.scene.materials.size());
  ctx.scene.materials.push_back(std::move(m));
  return static_cast<int>(ctx.scene.materials.size() - 1);
}

// "center", unit "axis", "radius", "height" = HALF the length: the cylinder
// spans center +- height * axis.
void read_cylinder(ImportContext& ctx, ObjectReader& r, ShapeDesc& shape) {
  Sourced<Vec3f> center, axis;
  Sourced<float> radius{1.0f};
  Sourced<float> half_height;
  const bool ok = r.read_required("center", center) & r.read_required("axis", axis) &
                  r.read_required("radius", radius) & r.read_required("height", half_height);
  if (!ok) return;
  if (length(axis.value) == 0.0f) {
    ctx.diag().error(axis.where, "cylinder axis must not be zero");
    r.fail();
    return;
  }
  if (half_height.value <= 0.0f) {
    ctx.diag().error(half_height.where, "cylinder height must be > 0, got " + format_number(half_height.value));
    r.fail();
    return;
  }
  const Vec3f offset = normalize(axis.value) * half_height.value;
  shape.geometry = Cylinder{center.value - offset, center.value + offset, shape.field("radius", radius)};
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
    shape.geometry = make_sphere(center, shape.field("radius", radius), Vec3f(0, 1, 0));  // texture pole +Y
  } else if (type == "cylinder") {
    read_cylinder(ctx, r, shape);
  } else if (type == "triangle") {
    Sourced<Vec3f> c[3];
    read_corners(r, 3, c);
    shape.geometry = make_triangle(c[0], c[1], c[2]);
  } else {
    report_unknown_type(r, "shape", type, {"sphere", "cylinder", "triangle"});
    return;
  }
  finish_legacy_shape(ctx, r, v, std::move(shape), read_material);
}

// The course's Phong renderer lights every surface with an ambient term whose
// light is the background colour: Cd backgroundcolor, without kd (ka = 1),
// inferred from the course's reference images (docs/rendering.md, "The course
// reference images").
// Not for "rendermode": "pathtracer" (the path integrator has no such term; its
// background already lights the scene); the binary mode ignores lights.
void add_course_ambient(SceneDescription& scene) {
  if (scene.render.integrator.value == "path") return;
  AmbientLightDesc ambient;
  ambient.where = scene.render.background.where;
  ambient.intensity = scene.render.background;
  scene.lights.emplace_back(std::move(ambient));
  for (MaterialDesc& m : scene.materials) m.ka = Sourced<float>(1.0f, scene.render.background.where);
}

}  // namespace

void import_cgr(ImportContext& ctx) {
  SceneDescription& scene = ctx.scene;
  scene.film.display = DisplayTransform::CgrCourse;
  scene.render.max_depth = kDefaultBounces;
  ObjectReader top(ctx.read, ctx.doc().root(), "the scene file");
  SourceLocation mode_at;
  const int mode = read_choice(top, "rendermode", {"binary", "phong", "pathtracer"}, &mode_at);
  if (mode >= 0) {
    static const char* const kIntegrators[] = {"binary", "whitted", "path"};
    scene.render.integrator = Sourced<std::string>(kIntegrators[mode], mode_at);
  }
  top.read("nbounces", scene.render.max_depth);
  read_sampling(ctx, top);
  if (const JsonValue* v = top.require("camera")) read_camera(ctx, *v);
  CgrTriangleRuns runs;  // long runs of triangles as one mesh (cgr_triangle_runs.h)
  auto read_shape_in_run = [&runs](ImportContext& c, const JsonValue& v, std::size_t index) {
    const std::size_t before = c.scene.shapes.size();
    read_shape(c, v, index);
    runs.shape_read(c, index, c.scene.shapes.size() > before);
  };
  if (const JsonValue* v = top.require("scene")) read_legacy_scene(ctx, *v, read_light, read_shape_in_run);
  runs.finish(ctx);
  top.finish();
  warn_if_unlit(ctx);
  add_course_ambient(scene);
}

}  // namespace pt
