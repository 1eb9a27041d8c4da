// The import entry's keys; an imported file's lights and camera; the camera
// framed on a scene's bounds; a model file given as the scene
// (docs/importing.md).
#include <cmath>
#include <filesystem>

#include "scene/asset_reader.h"
#include "scene/import_asset_internal.h"
#include "scene/import_transform.h"
#include "scene/suggest.h"

namespace fs = std::filesystem;

namespace pt {
namespace {

Affine to_affine(const Transform& t) {
  Affine a;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 4; ++j) a.m[i][j] = t.m[i][j];
  }
  return a;
}

// "camera": true, false or the name of one of the file's cameras.
bool read_camera_choice(ImportContext& ctx, ObjectReader& r, ImportRequest& req) {
  const JsonValue* v = r.get("camera");
  if (!v) return true;
  req.camera_where = ctx.read.at(*v);
  if (v->is_bool()) {
    req.use_camera = v->as_bool();
  } else if (v->is_string()) {
    req.camera_name = v->as_string();
  } else {
    ctx.diag().error(req.camera_where, std::string("expected true, false or the name of a camera for 'camera', got ") +
                                           json_type_name(v->type()));
    return false;
  }
  return true;
}

std::string supported_extensions() { return ".obj, .gltf, .glb and .dae (PLY meshes: {\"type\": \"mesh\"})"; }

LightDesc to_light_desc(const AssetLight& l, const Transform& t, const SourceLocation& where) {
  switch (l.type) {
    case AssetLight::Type::Directional: {
      DirectionalLightDesc d;
      d.where = where;
      d.direction = Sourced<Vec3f>(t.vector(l.direction), where);
      d.irradiance = Sourced<RGB>(l.intensity, where);
      return d;
    }
    case AssetLight::Type::Spot: {
      SpotLightDesc s;
      s.where = where;
      s.position = Sourced<Vec3f>(t.point(l.position), where);
      s.direction = Sourced<Vec3f>(t.vector(l.direction), where);
      s.intensity = s.specular_intensity = Sourced<RGB>(l.intensity, where);
      s.cone_angle = Sourced<float>(std::clamp(l.cone_angle_deg, 0.01f, 180.0f), where);
      s.cone_delta = Sourced<float>(std::clamp(l.cone_delta_deg, 0.0f, s.cone_angle.value), where);
      return s;
    }
    case AssetLight::Type::Point: break;
  }
  PointLightDesc p;
  p.where = where;
  p.position = Sourced<Vec3f>(t.point(l.position), where);
  p.intensity = p.specular_intensity = Sourced<RGB>(l.intensity, where);
  p.inverse_square = Sourced<bool>(l.inverse_square, where);
  return p;
}

bool usable_light(const AssetLight& l) {
  const bool directed = l.type != AssetLight::Type::Point;
  return l.intensity.is_finite() && std::isfinite(length(l.position)) &&
         (!directed || (std::isfinite(length(l.direction)) && length(l.direction) > 0.0f));
}

}  // namespace

bool read_import_request(ImportContext& ctx, const JsonValue& v, std::vector<NativeMaterial>& materials,
                         ImportRequest& req) {
  ObjectReader r(ctx.read, v, "import");
  r.get("type");
  req.where = r.where();
  r.read_required("file", req.file);
  r.allow({"name"});
  const int material = resolve_material(ctx, r, materials);
  if (material == -2) r.fail();
  req.material = material;
  std::optional<Sourced<Transform>> transform;
  if (const JsonValue* t = r.get("transform"); t && !read_transform(ctx.read, *t, transform)) r.fail();
  if (transform) req.transform = to_affine(transform->value);
  if (!read_camera_choice(ctx, r, req)) r.fail();
  Sourced<bool> lights{true};
  r.read("lights", lights);
  req.use_lights = lights.value;
  r.finish();
  if (!r.ok() || !req.file.where.valid()) return false;
  const std::optional<std::string> resolved = find_scene_file(ctx, req.file, "model file");
  if (!resolved) return false;
  req.resolved = *resolved;
  if (!asset_format_of(*resolved)) {
    const std::string ext = fs::path(*resolved).extension().string();
    ctx.diag().error(req.file.where, "unsupported mesh format '" + ext + "' (supported: " + supported_extensions() + ")");
    return false;
  }
  return true;
}

void place_camera_and_lights(ImportContext& ctx, const ImportedAsset& asset, const ImportRequest& req,
                             ImportCounts& counts) {
  const Transform t(req.transform);
  for (const AssetLight& l : asset.lights) {
    if (!req.use_lights) {
      counts.skipped_n("lights (\"lights\": false)", 1);
    } else if (!usable_light(l)) {
      counts.skipped_n("lights with non-finite or zero values", 1);
    } else {
      ctx.scene.lights.push_back(to_light_desc(l, t, req.where));
    }
  }
  if (asset.cameras.empty()) return;
  const AssetCamera* chosen = &asset.cameras.front();
  if (!req.camera_name.empty()) {
    std::vector<std::string> names;
    chosen = nullptr;
    for (const AssetCamera& c : asset.cameras) {
      if (c.name == req.camera_name) chosen = &c;
      names.push_back(c.name);
    }
    if (!chosen) {
      ctx.diag().error(req.camera_where, "'" + req.file.value + "' has no camera named '" + req.camera_name + "'" +
                                             did_you_mean(req.camera_name, names, "; its cameras: " + quoted_list(names, "and")));
      return;
    }
  }
  const uint64_t others = asset.cameras.size() - 1;
  counts.skipped_n("cameras (not chosen)", others);
  if (!req.use_camera || ctx.scene.camera.where.valid() || ctx.imported_camera) {
    counts.skipped_n(!req.use_camera ? "cameras (\"camera\": false)"
                                     : (ctx.imported_camera ? "cameras (an earlier import's is used)"
                                                            : "cameras (the scene has its own)"), 1);
    return;
  }
  ImportedCamera cam;
  CameraDesc& d = cam.camera;
  d.where = req.where;
  d.type = chosen->orthographic ? CameraType::Orthographic : CameraType::Pinhole;
  d.position = Sourced<Vec3f>(t.point(chosen->position), req.where);
  d.look_at = Sourced<Vec3f>(t.point(chosen->look_at), req.where);
  d.up = Sourced<Vec3f>(t.vector(chosen->up), req.where);
  d.fov_y_deg = Sourced<float>(chosen->fov_y_deg, req.where);
  d.view_height = Sourced<float>(chosen->view_height, req.where);
  cam.aspect = chosen->aspect;
  cam.file = req.file.value;
  cam.name = chosen->name;
  ctx.imported_camera = cam;
}

}  // namespace pt
