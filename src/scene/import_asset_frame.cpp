// A scene without a camera that imports a model file: the file's camera, or
// one framed on the scene's bounds. A model file given as the scene: the
// scene text that imports it and its lighting (docs/importing.md).
#include <algorithm>
#include <cmath>
#include <filesystem>

#include "scene/asset_reader.h"
#include "scene/import_asset_internal.h"

namespace fs = std::filesystem;

namespace pt {
namespace {

// Built by append: GCC 12 warns (-Wrestrict) on "(" + string, wrongly.
std::string vec(Vec3f v) {
  std::string s = "(";
  s += format_number(v.x);
  s += ", ";
  s += format_number(v.y);
  s += ", ";
  s += format_number(v.z);
  s += ")";
  return s;
}

// World bounds of the scene's bounded shapes, placed and instanced.
Bounds3f scene_bounds(const SceneDescription& scene) {
  Bounds3f b;
  auto add = [&](const ShapeDesc& s, const std::optional<Sourced<Transform>>& placed) {
    Bounds3f sb = bounds(s.geometry);
    if (sb.empty()) return;
    if (s.transform) sb = s.transform->value.bounds(sb);
    if (placed) sb = placed->value.bounds(sb);
    b.extend(sb.lo);
    b.extend(sb.hi);
  };
  for (const ShapeDesc& s : scene.shapes) add(s, std::nullopt);
  for (const InstanceDesc& inst : scene.instances) {
    if (inst.object < 0 || static_cast<std::size_t>(inst.object) >= scene.objects.size()) continue;
    for (const ShapeDesc& s : scene.objects[static_cast<std::size_t>(inst.object)].shapes) add(s, inst.transform);
  }
  return b;
}

// A pinhole camera that sees the whole bounding sphere: from the front (+z)
// and a little above and to the right, y up, as a model file (y up) is
// usually viewed.
void frame(ImportContext& ctx, const SourceLocation& where) {
  CameraDesc& cam = ctx.scene.camera;
  const Bounds3f b = scene_bounds(ctx.scene);
  const Vec3f centre = b.empty() ? Vec3f(0.0f) : (b.lo + b.hi) * 0.5f;
  float radius = b.empty() ? 1.0f : 0.5f * length(b.hi - b.lo);
  if (!(radius > 0.0f) || !std::isfinite(radius)) radius = 1.0f;
  const float aspect = static_cast<float>(ctx.scene.film.width.value) / static_cast<float>(ctx.scene.film.height.value);
  const double half_y = cam.fov_y_deg.value * 3.14159265358979323846 / 360.0;
  const double half_x = std::atan(std::tan(half_y) * (aspect > 0.0f ? aspect : 1.0f));
  const float distance = 1.05f * radius / static_cast<float>(std::sin(std::min(half_x, half_y)));
  const Vec3f from = normalize(Vec3f(0.3f, 0.35f, 1.0f));
  cam.where = where;
  cam.position = Sourced<Vec3f>(centre + from * distance, where);
  cam.look_at = Sourced<Vec3f>(centre, where);
  cam.up = Sourced<Vec3f>(Vec3f(0, 1, 0), where);
  ctx.diag().note(where, "the scene has no camera and its model files bring none: a camera framed on the scene's "
                         "bounds (centre " + vec(centre) + ", radius " + format_number(radius) + ") looks from " +
                         vec(cam.position.value));
}

}  // namespace

bool camera_from_imports(ImportContext& ctx, bool has_imports) {
  const SourceLocation where = file_location(ctx.scene.source_path);
  if (ctx.imported_camera) {
    ImportedCamera& c = *ctx.imported_camera;
    ctx.scene.camera = c.camera;
    std::string message = "the camera is '" + c.name + "' of '" + c.file + "'";
    FilmDesc& film = ctx.scene.film;
    if (c.aspect > 0.0f && !film.width.where.valid() && !film.height.where.valid()) {
      film.height.value = std::max(1, static_cast<int>(std::lround(film.width.value / c.aspect)));
      message += "; the image is " + std::to_string(film.width.value) + "x" + std::to_string(film.height.value) +
                 " (its aspect ratio)";
    }
    ctx.diag().note(c.camera.where, message);
    return true;
  }
  if (!has_imports) return false;
  frame(ctx, where);
  return true;
}

std::string model_scene_text(const std::string& model_path) {
  std::error_code ec;
  std::string path = fs::absolute(model_path, ec).lexically_normal().string();
  std::string escaped;
  for (char c : path) {
    if (c == '"' || c == '\\') escaped += '\\';
    escaped += c;
  }
  return "{\n  \"format\": \"pathtracer-scene\",\n  \"version\": 1,\n"
         "  \"render\": { \"integrator\": \"path\", \"spp\": 16, \"max_depth\": 8 },\n"
         "  \"shapes\": [ { \"type\": \"import\", \"file\": \"" + escaped + "\" } ]\n}\n";
}

void light_model_scene(SceneDescription& scene, Diagnostics& diag) {
  if (scene.render.background.where.valid() || scene.environment) return;  // --set render.background=...
  bool emits = false;
  for (const MaterialDesc& m : scene.materials) emits = emits || !m.emission.value.is_black();
  const bool lit = emits || std::any_of(scene.lights.begin(), scene.lights.end(), [](const LightDesc& l) {
                     return !std::holds_alternative<AmbientLightDesc>(l);
                   });
  scene.render.background.value = lit ? RGB(0.05f) : RGB(1.0f);
  if (!lit)
    diag.note(file_location(scene.source_path),
              "the model brings no lights: it is lit by a uniform white sky (render.background [1, 1, 1])");
}

}  // namespace pt
