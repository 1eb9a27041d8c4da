#include "scene/legacy_common.h"

#include <vector>

#include "scene/suggest.h"

namespace pt {

bool read_corners(ObjectReader& r, int n, Sourced<Vec3f>* out) {
  bool ok = true;
  for (int i = 0; i < n; ++i) {
    const char key[3] = {'v', static_cast<char>('0' + i), '\0'};  // n <= 4
    ok = r.read_required(key, out[i]) && ok;
  }
  return ok;
}

std::string read_legacy_type(ObjectReader& r) {
  Sourced<std::string> type;
  if (!r.read_required("type", type)) return {};
  return type.value;
}

void warn_unsupported_type(ObjectReader& r, std::string_view kind, const std::string& type,
                           std::initializer_list<std::string_view> supported) {
  const std::vector<std::string> names(supported.begin(), supported.end());
  std::string message = "unsupported " + std::string(kind) + " type '" + type + "' (ignored)";
  const std::string suggestion = closest_match(type, names);
  if (!suggestion.empty()) message += "; did you mean '" + suggestion + "'?";
  else message += "; supported: " + quoted_list(names, "and");
  const JsonValue* v = r.get("type");
  r.context().diag.warning(v ? r.context().at(*v) : r.where(), std::move(message));
}

bool accept_point_light(ObjectReader& r) {
  const std::string type = read_legacy_type(r);
  if (type.empty()) return false;
  if (type != "pointlight") {
    warn_unsupported_type(r, "light", type, {"pointlight"});
    return false;
  }
  r.set_what("point light");
  return true;
}

void read_legacy_scene(ImportContext& ctx, const JsonValue& v, LegacyItemReader read_light,
                       LegacyItemReader read_shape) {
  if (!expect_object(ctx.read, v, "scene")) return;
  ObjectReader r(ctx.read, v, "scene");
  r.read("backgroundcolor", ctx.scene.render.background);
  if (const JsonValue* lights = r.get("lightsources"); lights && expect_array(ctx.read, *lights, "lightsources")) {
    for (std::size_t i = 0; i < lights->as_array().size(); ++i) read_light(ctx, lights->as_array()[i], i);
  }
  if (const JsonValue* shapes = r.require("shapes"); shapes && expect_array(ctx.read, *shapes, "shapes")) {
    for (std::size_t i = 0; i < shapes->as_array().size(); ++i) read_shape(ctx, shapes->as_array()[i], i);
  }
  r.finish();
}

void finish_legacy_shape(ImportContext& ctx, ObjectReader& r, ShapeDesc shape,
                         LegacyMaterialReader read_material) {
  int material = -1;
  const JsonValue* mv = r.get("material");
  if (mv) material = read_material(ctx, *mv);
  r.finish();
  if (!r.ok() || (mv && material < 0)) return;
  shape.material = mv ? material : default_material(ctx);
  ctx.scene.shapes.push_back(std::move(shape));
}

}  // namespace pt
