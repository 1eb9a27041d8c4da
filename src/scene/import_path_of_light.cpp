// The "Path of Light" course format (see /work/shared/seed-scenes/CONVENTIONS.md
// and docs/scene-format.md): Z-up, "lookat" is a direction, point lights give
// "id"/"is" with a 1/(4 pi r^2) falloff, "plane" is a quad with named corners,
// linear display (value * 255).
#include <cmath>
#include <string>

#include "scene/importers.h"
#include "scene/legacy_common.h"

namespace pt {
namespace {

constexpr float kInv4Pi = 1.0f / (4.0f * kPi);

// The view direction "lookat", or (after reporting a zero one) a stand-in
// that lets validation go on without blaming the camera twice.
void read_view_direction(ImportContext& ctx, ObjectReader& r, CameraDesc& cam) {
  Sourced<Vec3f> direction;
  if (!r.read_required("lookat", direction)) return;
  if (length(direction.value) == 0.0f) {
    ctx.diag().error(direction.where, "'lookat' is the camera's view direction in Path of Light files and must "
                                      "not be zero");
    const Vec3f any = std::fabs(cam.up.value.x) < 0.9f * length(cam.up.value) ? Vec3f(1, 0, 0) : Vec3f(0, 1, 0);
    cam.look_at = Sourced<Vec3f>(cam.position.value + any);
    return;
  }
  cam.look_at = Sourced<Vec3f>(cam.position.value + direction.value, direction.where);  // target = position + lookat
}

void read_camera(ImportContext& ctx, const JsonValue& v) {
  if (!expect_object(ctx.read, v, "camera")) return;
  ObjectReader r(ctx.read, v, "camera");
  CameraDesc& cam = ctx.scene.camera;
  cam.where = r.where();
  cam.type = read_camera_type(r);
  r.read_required("width", ctx.scene.film.width);
  r.read_required("height", ctx.scene.film.height);
  r.read_required("fov", cam.fov_y_deg);  // full angle; the course's images are square
  r.read_required("position", cam.position);
  r.read_required("up", cam.up);
  read_view_direction(ctx, r, cam);
  cam.left_handed = false;  // image right = forward x up
  if (cam.type == CameraType::ThinLens) read_lens(ctx, r, cam);  // no official keys: docs/scene-format.md
  r.finish();
}

void read_light(ImportContext& ctx, const JsonValue& v, std::size_t index) {
  if (!expect_object(ctx.read, v, "lightsources[" + std::to_string(index) + "]")) return;
  ObjectReader r(ctx.read, v, "light source");
  const int type = read_light_type(r, {"pointlight", "arealight"});
  if (type == 1) return read_area_light(ctx, r);
  if (type != 0) return;
  r.set_what("point light");
  PointLightDesc light;
  light.where = r.where();
  r.read_required("position", light.position);
  Sourced<RGB> diffuse, specular;
  // The course shades kd Cd id cos / (4 pi r^2); a native point light of intensity I
  // shades kd Cd I cos / r^2 in the classic integrator, so I = id / (4 pi).
  // "intensity" (the CGR spelling, seen in third-party files) stands for both.
  if (r.get("intensity") && !r.get("id") && !r.get("is")) {
    if (r.read("intensity", diffuse)) specular = diffuse;
  } else if (r.get("intensity")) {
    ctx.diag().error(ctx.read.at(*r.get("intensity")), "'intensity' stands for both 'id' and 'is'; give either it "
                                                       "or them");
    r.fail();
  } else {
    r.read_required("id", diffuse);
    r.read_required("is", specular);
  }
  if (diffuse.where.valid()) light.intensity = Sourced<RGB>(diffuse.value * kInv4Pi, diffuse.where);
  if (specular.where.valid()) light.specular_intensity = Sourced<RGB>(specular.value * kInv4Pi, specular.where);
  r.finish();
  if (r.ok()) ctx.scene.lights.emplace_back(std::move(light));
}

// "kt" (transmission) with the index of refraction under "eta", "ior" or
// "refractiveIndex": the smooth dielectric, whose Fresnel term decides how much
// is reflected and transmitted (a kt strictly between 0 and 1 cannot be honoured).
void read_transmission(ImportContext& ctx, ObjectReader& r, MaterialDesc& m) {
  Sourced<float> kt{0.0f};
  r.read("kt", kt);
  const char* ior_key = find_aliased(r, {"eta", "ior", "refractiveIndex", "refractiveindex"});
  if (ior_key) r.read(ior_key, m.ior);
  if (!(kt.value > 0.0f)) {
    if (ior_key && m.ior.where.valid())
      ctx.diag().warning(m.ior.where, std::string("'") + ior_key + "' has no effect without 'kt' > 0");
    return;
  }
  m.refractive = Sourced<bool>(true, kt.where);
  if (kt.value < 1.0f)
    ctx.diag().warning(kt.where, "kt " + format_number(kt.value) + " taken as a fully transparent dielectric: "
                                 "the share reflected and refracted follows Fresnel's equations");
  if (!ior_key) {
    m.ior = Sourced<float>(1.5f, kt.where);
    ctx.diag().warning(kt.where, "no index of refraction ('eta', 'ior' or 'refractiveIndex'): glass's 1.5 is used");
  }
}

// A textured surface as the course's reference render shows it (docs/rendering.md,
// "The course reference images"): the texels, read as they are (no sRGB decoding),
// take the place of "diffusecolor", and the surface has no specular highlight.
// The course samples its textures at points (one bilinear lookup at the hit,
// one sample per pixel); so do we, rather than filter them over a footprint.
void use_course_texture(ImportContext& ctx, MaterialDesc& m) {
  TextureDesc& t = ctx.scene.textures[static_cast<std::size_t>(*m.texture)];
  t.filter = Sourced<TextureFilter>(TextureFilter::Bilinear, t.where);
  m.diffuse = Sourced<RGB>(RGB(1.0f), m.diffuse.where);
  m.ks = Sourced<float>(0.0f, m.ks.where);
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
  read_transmission(ctx, r, m);
  Sourced<std::string> texture;
  if (r.get("tPath") && r.read("tPath", texture)) m.texture = add_texture(ctx, texture, /*raw=*/true);
  if (m.texture) use_course_texture(ctx, m);
  r.allow({"tWidth", "tHeight"});  // the course's claimed image size; the real size is used
  r.finish();
  if (!r.ok()) return -1;
  m.name = "material " + std::to_string(ctx.scene.materials.size());
  ctx.scene.materials.push_back(std::move(m));
  return static_cast<int>(ctx.scene.materials.size() - 1);
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
    if (read_corners(r, 4, c)) {
      shape.geometry = Quad{{c[0], c[1], c[2], c[3]}};
      order_quad_corners(ctx, c, std::get<Quad>(shape.geometry));
    }
  } else if (type == "triangle") {
    Sourced<Vec3f> c[3];
    read_corners(r, 3, c);
    shape.geometry = make_triangle(c[0], c[1], c[2]);
  } else if (type == "trimesh" || type == "mesh") {
    read_legacy_mesh(ctx, r, v, shape);
  } else {
    report_unknown_type(r, "shape", type, {"sphere", "plane", "triangle", "trimesh", "mesh"});
    return;
  }
  Sourced<std::string> id;
  r.read("id", id);
  shape.name = id.value;
  finish_legacy_shape(ctx, r, v, std::move(shape), read_material);
}

}  // namespace

void import_path_of_light(ImportContext& ctx) {
  SceneDescription& scene = ctx.scene;
  scene.film.display = DisplayTransform::Linear;  // the course writes value * 255, no gamma
  scene.render.integrator = std::string("whitted");
  ObjectReader top(ctx.read, ctx.doc().root(), "the scene file");
  top.read("nbounces", scene.render.max_depth);
  read_sampling(ctx, top);
  if (const JsonValue* v = top.require("camera")) read_camera(ctx, *v);
  if (const JsonValue* v = top.require("scene")) read_legacy_scene(ctx, *v, read_light, read_shape);
  top.finish();
  warn_if_unlit(ctx);
}

}  // namespace pt
