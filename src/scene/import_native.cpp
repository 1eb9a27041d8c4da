// The native format (docs/scene-format.md): top level, camera, film, render
// settings and lights. Materials are in import_native_materials.cpp, shapes
// in import_native_shapes.cpp.
#include <algorithm>
#include <iterator>
#include <optional>
#include <string>
#include <vector>

#include "scene/detect.h"
#include "scene/import_asset.h"
#include "scene/importers.h"
#include "scene/import_transform.h"
#include "scene/native_shapes.h"
#include "scene/native_textures.h"

namespace pt {
namespace {

// The camera types' names (docs/scene-format.md): Mitsuba's "perspective" and
// "thinlens" are accepted beside ours.
struct CameraTypeName {
  const char* name;
  CameraType type;
};
constexpr CameraTypeName kCameraTypes[] = {{"pinhole", CameraType::Pinhole},        {"perspective", CameraType::Pinhole},
                                           {"thin_lens", CameraType::ThinLens},     {"thinlens", CameraType::ThinLens},
                                           {"orthographic", CameraType::Orthographic}, {"spherical", CameraType::Spherical}};

// The keys only some camera types read; one the type does not read is an error.
std::vector<std::string> camera_type_keys(CameraType type) {
  switch (type) {
    case CameraType::ThinLens: return {"fov", "lens_radius", "focus_distance"};
    case CameraType::Orthographic: return {"view_height", "view_width"};
    case CameraType::Spherical: return {};
    case CameraType::Pinhole: break;
  }
  return {"fov"};
}

void refuse_camera_keys(ImportContext& ctx, ObjectReader& r, CameraType type, const std::string& type_name) {
  const std::vector<std::string> allowed = camera_type_keys(type);
  for (const char* key : {"fov", "lens_radius", "focus_distance", "view_height", "view_width"}) {
    if (std::find(allowed.begin(), allowed.end(), key) != allowed.end()) continue;
    if (const JsonValue* v = r.get(key)) {
      std::string message = "'";
      message += key;
      message += std::string("' does not apply to ") + (type_name[0] == 'o' ? "an " : "a ") + type_name + " camera";
      for (std::size_t i = 0; i < allowed.size(); ++i) message += (i == 0 ? " (it reads: " : ", ") + allowed[i];
      if (!allowed.empty()) message += ')';
      ctx.diag().error(ctx.read.at(*v), message);
      r.fail();
    }
  }
}

// The camera's transform, applied at import as pbrt-v4's camera transform and
// Mitsuba 3's to_world act: it moves the position, target and up; its uniform
// scale scales the camera's lengths (lens radius, focus distance, orthographic
// view), so a scene scaled with its camera looks the same; a mirror flips the
// image's handedness (a reflection of the whole scene and its camera renders
// the same image). A non-uniform scale or shear would stretch the view, which
// no camera here models: refused.
void apply_camera_transform(ImportContext& ctx, ObjectReader& r, const JsonValue& v, CameraDesc& cam) {
  std::optional<Sourced<Transform>> transform;
  if (!read_transform(ctx.read, v, transform) || !transform) return;
  const Transform& t = transform->value;
  if (!t.similarity) {
    ctx.diag().error(transform->where, "a camera's transform must keep angles (translate, rotate, a uniform scale "
                                       "or a mirror): a non-uniform scale or a shear would stretch the view");
    r.fail();
    return;
  }
  cam.position.value = t.point(cam.position.value);
  cam.look_at.value = t.point(cam.look_at.value);
  cam.up.value = t.vector(cam.up.value);
  for (Sourced<float>* length : {&cam.lens_radius, &cam.focus_distance, &cam.view_height, &cam.view_width})
    length->value *= t.scale;
  if (t.det < 0.0f) cam.left_handed.value = !cam.left_handed.value;
}

void read_camera(ImportContext& ctx, const JsonValue& v) {
  if (!expect_object(ctx.read, v, "camera")) return;
  ObjectReader r(ctx.read, v, "camera");
  CameraDesc& cam = ctx.scene.camera;
  cam.where = r.where();
  SourceLocation type_at;
  std::vector<std::string> names;
  for (const CameraTypeName& t : kCameraTypes) names.emplace_back(t.name);
  const int type = read_choice(r, "type", names, &type_at);
  if (type >= 0) cam.type = kCameraTypes[type].type;
  refuse_camera_keys(ctx, r, cam.type, type >= 0 ? names[static_cast<std::size_t>(type)] : "pinhole");
  r.read_required("position", cam.position);
  r.read_required("look_at", cam.look_at);
  r.read("up", cam.up);
  SourceLocation handed_at;
  const int handed = read_choice(r, "handedness", {"right", "left"}, &handed_at);
  if (handed >= 0) cam.left_handed = Sourced<bool>(handed == 1, handed_at);
  if (cam.type == CameraType::Pinhole || cam.type == CameraType::ThinLens) r.read("fov", cam.fov_y_deg);
  if (cam.type == CameraType::ThinLens) {
    r.read_required("lens_radius", cam.lens_radius);
    r.read_required("focus_distance", cam.focus_distance);
  }
  if (cam.type == CameraType::Orthographic) {
    r.read("view_height", cam.view_height);
    r.read("view_width", cam.view_width);
    if (cam.view_height.where.valid() && cam.view_width.where.valid()) {
      ctx.diag().error(cam.view_width.where,
                       "give view_height or view_width, not both: the other follows from the image's aspect ratio");
      r.fail();
    }
  }
  if (const JsonValue* t = r.get("transform")) apply_camera_transform(ctx, r, *t, cam);
  r.finish();
}

void read_film(ImportContext& ctx, const JsonValue& v) {
  if (!expect_object(ctx.read, v, "film")) return;
  ObjectReader r(ctx.read, v, "film");
  FilmDesc& film = ctx.scene.film;
  r.read("width", film.width);
  r.read("height", film.height);
  SourceLocation display_at;
  const int display = read_choice(
      r, "display", {std::begin(kDisplayTransformNames), std::end(kDisplayTransformNames)}, &display_at);
  if (display >= 0) film.display = Sourced<DisplayTransform>(static_cast<DisplayTransform>(display), display_at);
  r.read("exposure", film.exposure);
  r.finish();
}

void read_render(ImportContext& ctx, const JsonValue& v) {
  if (!expect_object(ctx.read, v, "render")) return;
  ObjectReader r(ctx.read, v, "render");
  RenderDesc& render = ctx.scene.render;
  r.read("integrator", render.integrator);
  r.read("max_depth", render.max_depth);
  r.read("spp", render.spp);
  r.read("background", render.background);
  SourceLocation filter_at;
  const int filter = read_choice(r, "filter", {std::begin(kPixelFilterNames), std::end(kPixelFilterNames)}, &filter_at);
  if (filter >= 0) render.filter = Sourced<PixelFilterType>(static_cast<PixelFilterType>(filter), filter_at);
  r.read("clamp", render.clamp);
  SourceLocation sampler_at;
  const int sampler =
      read_choice(r, "light_sampler", {std::begin(kLightSamplerNames), std::end(kLightSamplerNames)}, &sampler_at);
  if (sampler >= 0) render.light_sampler = Sourced<LightSamplerType>(static_cast<LightSamplerType>(sampler), sampler_at);
  r.read("shadow_terminator_geometry_offset", render.shadow_terminator_geometry_offset);
  r.read("film_transparent", render.film_transparent);
  r.read("light_guiding", render.light_guiding);
  r.read("path_guiding", render.path_guiding);
  Sourced<std::string> image;
  if (r.read("background_image", image) && image.where.valid()) {
    if (const std::optional<std::string> resolved = find_scene_file(ctx, image, "background image"))
      render.background_image = TextureDesc{image.where, image.value, *resolved};
  }
  r.finish();
}

// The keys point and spot lights share: where, position, intensity, specular_intensity.
template <class Desc>
void read_positioned_light(ObjectReader& r, const char* what, Desc& light) {
  r.set_what(what);
  light.where = r.where();
  r.read_required("position", light.position);
  r.read_required("intensity", light.intensity);
  light.specular_intensity = light.intensity;
  r.read("specular_intensity", light.specular_intensity);
}

// A spot light: its axis as "direction" or as "look_at" (not both).
void read_spot_light(ImportContext& ctx, ObjectReader& r) {
  SpotLightDesc light;
  read_positioned_light(r, "spot light", light);
  r.read("cone_angle", light.cone_angle);
  r.read("cone_delta", light.cone_delta);
  Sourced<Vec3f> look_at;
  const bool has_direction = r.get("direction") != nullptr;
  if (r.get("look_at") && r.read("look_at", look_at) && r.ok()) {
    if (has_direction) {
      ctx.diag().error(look_at.where, "a spot light takes 'direction' or 'look_at', not both");
      r.fail();
    }
    light.direction = Sourced<Vec3f>(look_at.value - light.position.value, look_at.where);
  } else if (!has_direction && !r.get("look_at")) {
    r.require("direction");  // "missing key 'direction'": one of the two is needed
  }
  if (has_direction) r.read("direction", light.direction);
  r.finish();
  if (r.ok()) ctx.scene.lights.emplace_back(std::move(light));
}

void read_light(ImportContext& ctx, const JsonValue& v, std::size_t index) {
  const std::string label = "lights[" + std::to_string(index) + "]";
  if (!expect_object(ctx.read, v, label)) return;
  ObjectReader r(ctx.read, v, "light");
  const int type = read_choice(r, "type", {"point", "directional", "spot", "ambient"});
  if (type == -1) r.require("type");
  if (type < 0) return;  // the error is reported; the rest of this light cannot be checked
  if (type == 2) {
    read_spot_light(ctx, r);
    return;
  }
  if (type == 3) {
    r.set_what("ambient light");
    AmbientLightDesc light;
    light.where = r.where();
    r.read_required("intensity", light.intensity);
    r.finish();
    if (r.ok()) ctx.scene.lights.emplace_back(std::move(light));
    return;
  }
  if (type == 1) {
    r.set_what("directional light");
    DirectionalLightDesc light;
    light.where = r.where();
    r.read_required("direction", light.direction);
    r.read_required("irradiance", light.irradiance);
    r.finish();
    if (r.ok()) ctx.scene.lights.emplace_back(std::move(light));
    return;
  }
  PointLightDesc light;
  read_positioned_light(r, "point light", light);
  SourceLocation falloff_at;
  const int falloff = read_choice(r, "falloff", {"inverse_square", "none"}, &falloff_at);
  if (falloff >= 0) light.inverse_square = Sourced<bool>(falloff == 0, falloff_at);
  r.finish();
  if (r.ok()) ctx.scene.lights.emplace_back(std::move(light));
}

// "environment": a latitude-longitude radiance map (docs/scene-format.md).
void read_environment(ImportContext& ctx, const JsonValue& v) {
  if (!expect_object(ctx.read, v, "environment")) return;
  ObjectReader r(ctx.read, v, "environment");
  EnvironmentDesc env;
  env.where = r.where();
  if (r.read_required("file", env.file)) {
    if (const std::optional<std::string> resolved = find_scene_file(ctx, env.file, "environment map"))
      env.resolved = *resolved;
  }
  r.read("rotation", env.rotation_deg);
  r.read("intensity", env.intensity);
  r.read("up", env.up);
  r.finish();
  // Kept even without its file (already reported), so the rest is validated too.
  if (r.ok()) ctx.scene.environment = std::move(env);
}

// Keeps the materials some shape uses (in declaration order), registers their
// textures, and renumbers the shapes' material indices.
void assemble_materials(ImportContext& ctx, std::vector<NativeMaterial>& materials, NativeTextures& textures,
                        const std::vector<int>& shape_material, const std::vector<std::vector<int>>& object_material) {
  std::vector<int> final_index(materials.size(), -1);
  for (std::size_t i = 0; i < materials.size(); ++i) {
    NativeMaterial& m = materials[i];
    if (!m.used) {
      ctx.diag().warning(m.desc.where, "material '" + m.desc.name + "' is not used by any shape");
      continue;
    }
    resolve_material_textures(ctx, textures, m);
    final_index[i] = static_cast<int>(ctx.scene.materials.size());
    ctx.scene.materials.push_back(std::move(m.desc));
  }
  for (std::size_t s = 0; s < ctx.scene.shapes.size(); ++s) {
    const int m = shape_material[s];
    ctx.scene.shapes[s].material = m >= 0 ? final_index[static_cast<std::size_t>(m)] : default_material(ctx);
  }
  for (std::size_t o = 0; o < ctx.scene.objects.size(); ++o) {
    for (std::size_t s = 0; s < ctx.scene.objects[o].shapes.size(); ++s) {
      const int m = object_material[o][s];
      ctx.scene.objects[o].shapes[s].material =
          m >= 0 ? final_index[static_cast<std::size_t>(m)] : default_material(ctx);
    }
  }
  for (InstanceDesc& inst : ctx.scene.instances) {
    if (inst.material) inst.material = final_index[static_cast<std::size_t>(*inst.material)];
  }
}

// Whether "shapes" holds an import (one that failed counts: its error is reported).
bool has_import(ObjectReader& top) {
  const JsonValue* shapes = top.get("shapes");
  if (!shapes || !shapes->is_array()) return false;
  const JsonValue::Array& list = shapes->as_array();
  return std::any_of(list.begin(), list.end(), [](const JsonValue& s) { return is_import(s); });
}

}  // namespace

void import_native(ImportContext& ctx) {
  const JsonValue& root = ctx.doc().root();
  ObjectReader top(ctx.read, root, "the scene file");
  top.get("format");  // checked by detect_scene_format
  Sourced<int> version;
  if (top.read_required("version", version) && version.value != kNativeFormatVersion) {
    ctx.diag().error(version.where, "unsupported version " + std::to_string(version.value) +
                                        "; this build reads version " + std::to_string(kNativeFormatVersion));
  }
  // Without a "camera", an imported model file's or a framing one (import_asset.h).
  const JsonValue* camera = top.get("camera");
  if (camera) read_camera(ctx, *camera);
  if (const JsonValue* v = top.get("film")) read_film(ctx, *v);
  if (const JsonValue* v = top.get("render")) read_render(ctx, *v);
  if (const JsonValue* v = top.get("environment")) {
    read_environment(ctx, *v);
    if (ctx.scene.render.background.where.valid())
      ctx.diag().error(ctx.scene.render.background.where,
                       "a scene has either render.background or an environment map, not both: the "
                       "environment is what rays that leave the scene see");
  }

  NativeTextures textures;
  if (const JsonValue* v = top.get("textures")) textures = read_native_textures(ctx, *v);
  std::vector<NativeMaterial> materials;
  if (const JsonValue* v = top.get("materials")) materials = read_materials(ctx, *v);

  if (const JsonValue* v = top.get("lights"); v && expect_array(ctx.read, *v, "lights")) {
    const JsonValue::Array& lights = v->as_array();
    for (std::size_t i = 0; i < lights.size(); ++i) read_light(ctx, lights[i], i);
  }

  std::vector<std::vector<int>> object_material;  // as shape_material, per object
  if (const JsonValue* v = top.get("objects")) read_native_objects(ctx, *v, materials, object_material);
  std::vector<int> shape_material;  // per shape: index into `materials`, -1 for the default
  if (const JsonValue* v = top.get("shapes"); v && expect_array(ctx.read, *v, "shapes")) {
    const JsonValue::Array& shapes = v->as_array();
    for (std::size_t i = 0; i < shapes.size(); ++i)
      read_native_shape(ctx, shapes[i], i, materials, shape_material, &object_material);
  }
  if (!camera && !camera_from_imports(ctx, has_import(top))) top.require("camera");
  top.finish();
  warn_unplaced_objects(ctx);
  assemble_materials(ctx, materials, textures, shape_material, object_material);
  warn_unused_textures(ctx, textures);
}

}  // namespace pt
