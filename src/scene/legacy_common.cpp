#include "scene/legacy_common.h"

#include <algorithm>
#include <cctype>
#include <cmath>
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

void report_unknown_type(ObjectReader& r, std::string_view kind, const std::string& type,
                         std::initializer_list<std::string_view> supported) {
  const std::vector<std::string> names(supported.begin(), supported.end());
  const std::string suggestion = closest_match(type, names);
  const JsonValue* v = r.get("type");
  const SourceLocation at = v ? r.context().at(*v) : r.where();
  if (!suggestion.empty() && edit_distance(type, suggestion) <= 2) {
    r.context().diag.error(at, "unknown " + std::string(kind) + " type '" + type + "'; did you mean '" +
                                   suggestion + "'?");
    r.fail();
    return;
  }
  r.context().diag.warning(at, "unsupported " + std::string(kind) + " type '" + type +
                                   "' (ignored); supported: " + quoted_list(names, "and"));
}

const char* find_aliased(ObjectReader& r, std::initializer_list<const char*> keys) {
  const char* found = nullptr;
  for (const char* key : keys) {
    if (!r.get(key)) continue;
    if (found) {
      r.context().diag.error(r.context().at(*r.get(key)),
                             std::string("'") + key + "' and '" + found + "' say the same thing; give one of them");
      r.fail();
      return nullptr;
    }
    found = key;
  }
  return found;
}

int read_light_type(ObjectReader& r, std::initializer_list<std::string_view> supported) {
  const std::string type = read_legacy_type(r);
  if (type.empty()) return -1;
  int index = 0;
  for (std::string_view name : supported) {
    if (name == type) return index;
    ++index;
  }
  report_unknown_type(r, "light", type, supported);
  return -1;
}

namespace {

// A camera type without case and separators: "thinLens", "Thin_Lens" and
// "finite aperture" are the names "thinlens" and "finiteaperture".
std::string plain_name(const std::string& s) {
  std::string out;
  for (char c : s)
    if (c != '-' && c != '_' && c != ' ') out += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

}  // namespace

CameraType read_camera_type(ObjectReader& r) {
  Sourced<std::string> type;
  if (!r.get("type") || !r.read("type", type)) return CameraType::Pinhole;  // absent: a pinhole, as before
  if (type.value == "pinhole") return CameraType::Pinhole;
  if (type.value == "thinlens" || type.value == "finite-aperture") return CameraType::ThinLens;
  const std::string plain = plain_name(type.value);
  if (plain == "pinhole" || plain == "thinlens" || plain == "finiteaperture") {
    const bool lens = plain != "pinhole";
    r.context().diag.warning(type.where, "camera type '" + type.value + "' read as '" +
                                             (lens ? "thinlens" : "pinhole") + "'");
    return lens ? CameraType::ThinLens : CameraType::Pinhole;
  }
  const std::vector<std::string> names = {"pinhole", "thinlens", "finite-aperture"};
  const std::string suggestion = closest_match(type.value, names);
  if (!suggestion.empty() && edit_distance(type.value, suggestion) <= 2) {
    r.context().diag.error(type.where, "unknown camera type '" + type.value + "'; did you mean '" + suggestion + "'?");
    r.fail();
  } else {
    r.context().diag.warning(type.where, "unknown camera type '" + type.value + "'; rendered with a pinhole camera "
                                         "(supported: " + quoted_list(names, "and") + ")");
  }
  return CameraType::Pinhole;
}

namespace {

// Reads the one of `keys` present into out (error if none or two).
const char* read_one_of(ObjectReader& r, std::initializer_list<const char*> keys, std::string_view what,
                        Sourced<float>& out) {
  if (std::none_of(keys.begin(), keys.end(), [&](const char* k) { return r.get(k) != nullptr; })) {
    r.context().diag.error(r.where(), "a thin-lens camera needs its " + std::string(what) + ": one of " +
                                          quoted_list(std::vector<std::string>(keys.begin(), keys.end())));
    r.fail();
    return nullptr;
  }
  const char* key = find_aliased(r, keys);
  return key && r.read(key, out) ? key : nullptr;
}

}  // namespace

void read_lens(ImportContext& ctx, ObjectReader& r, CameraDesc& cam) {
  // Ours first, then the spellings of third-party files; "aperture" is the
  // lens diameter, as in Shirley's "Ray Tracing in One Weekend".
  const char* radius_key = read_one_of(r, {"lensradius", "lensRadius", "lens_radius", "apertureradius",
                                           "apertureRadius", "aperture_radius", "aperture"},
                                       "lens radius", cam.lens_radius);
  if (radius_key && std::string_view(radius_key) == "aperture") {
    cam.lens_radius.value *= 0.5f;
    ctx.diag().warning(cam.lens_radius.where, "'aperture' taken as the lens diameter: lens radius " +
                                                  format_number(cam.lens_radius.value));
  }
  const char* focus_key = read_one_of(r, {"focusdistance", "focusDistance", "focaldistance", "focalDistance",
                                          "focus_distance", "focal_distance", "focal_length", "focalLength", "focal"},
                                      "distance in focus", cam.focus_distance);
  const std::string_view focus(focus_key ? focus_key : "");
  if (focus == "focal_length" || focus == "focalLength" || focus == "focal") {
    std::string message = "'";
    message.append(focus).append("' taken as the distance from the lens to the plane in focus");
    ctx.diag().warning(cam.focus_distance.where, message);
  }
  if (const JsonValue* d = r.get("d")) {
    ctx.diag().warning(ctx.read.at(*d), "'d' (the image plane's distance) is not used: the field of view fixes "
                                        "the image, the focus distance what is sharp");
  }
}

void read_sampling(ImportContext& ctx, ObjectReader& top) {
  if (const char* key = find_aliased(top, {"spp", "samples"})) top.read(key, ctx.scene.render.spp);
  const JsonValue* block = top.get("sampling");
  if (!block || !expect_object(ctx.read, *block, "sampling")) return;
  ObjectReader r(ctx.read, *block, "sampling");
  if (const char* key = find_aliased(r, {"spp", "samples"})) {
    if (top.get("spp") || top.get("samples"))
      ctx.diag().error(ctx.read.at(*r.get(key)), "samples per pixel are given twice (here and at the top level)");
    else
      r.read(key, ctx.scene.render.spp);
  }
  if (const char* key = find_aliased(r, {"method", "type", "strategy"})) {
    ctx.diag().warning(ctx.read.at(*r.get(key)), std::string("sampling '") + key + "' is not read from scene files; "
                                                 "choose the sampler with --sampler random|jittered|sobol");
  }
  r.finish();
}

namespace {

// True if a, b, c, d go round a rectangle (right angles, the diagonals bisecting each other).
bool is_rectangle(Vec3f a, Vec3f b, Vec3f c, Vec3f d) {
  const Vec3f p[4] = {a, b, c, d};
  float size = 0.0f;
  for (int i = 0; i < 4; ++i) size = std::max(size, length(p[(i + 1) % 4] - p[i]));
  if (!(size > 0.0f)) return false;
  const float tolerance = 1e-3f * size;
  if (length((a + c) - (b + d)) > tolerance) return false;
  for (int i = 0; i < 4; ++i) {
    const Vec3f e1 = p[(i + 1) % 4] - p[i], e2 = p[(i + 3) % 4] - p[i];
    if (!(length(e1) > 0.0f) || !(length(e2) > 0.0f)) return false;
    if (std::fabs(dot(e1, e2)) > 1e-3f * length(e1) * length(e2)) return false;
  }
  return true;
}

}  // namespace

void order_quad_corners(ImportContext& ctx, const Sourced<Vec3f>* c, Quad& quad) {
  const Vec3f v0 = c[0].value, v1 = c[1].value, v2 = c[2].value, v3 = c[3].value;
  if (is_rectangle(v0, v1, v2, v3)) return;
  int moved = -1;
  if (is_rectangle(v0, v1, v3, v2)) {
    quad = Quad{{v0, v1, v3, v2}};
    moved = 2;
  } else if (is_rectangle(v0, v2, v1, v3)) {
    quad = Quad{{v0, v2, v1, v3}};
    moved = 1;
  } else {
    return;
  }
  ctx.diag().warning(c[moved].where, moved == 2 ? "the corners are in zig-zag order: taken as v0, v1, v3, v2 "
                                                  "(the order that goes round the rectangle)"
                                                : "the corners are in zig-zag order: taken as v0, v2, v1, v3 "
                                                  "(the order that goes round the rectangle)");
}

void warn_if_unlit(ImportContext& ctx) {
  const SceneDescription& scene = ctx.scene;
  if (!scene.lights.empty() || scene.shapes.empty() || scene.render.integrator.value == "binary" ||
      ctx.diag().has_errors())
    return;
  for (const ShapeDesc& shape : scene.shapes) {
    const RGB e = scene.materials[static_cast<std::size_t>(shape.material)].emission.value;
    if (e.r > 0.0f || e.g > 0.0f || e.b > 0.0f) return;
  }
  const RGB bg = scene.render.background.value;
  const bool path = scene.render.integrator.value == "path";
  const bool lit_by_background = path && (bg.r > 0.0f || bg.g > 0.0f || bg.b > 0.0f);
  if (lit_by_background) return;
  ctx.diag().warning(ctx.doc().location(ctx.doc().root()),
                     "the scene has no light source (none given, or every one was skipped): the shapes will be "
                     "black and the image will show the background only");
}

void read_legacy_scene(ImportContext& ctx, const JsonValue& v, const LegacyItemReader& read_light,
                       const LegacyItemReader& read_shape) {
  if (!expect_object(ctx.read, v, "scene")) return;
  ObjectReader r(ctx.read, v, "scene");
  r.read("backgroundcolor", ctx.scene.render.background);
  if (const JsonValue* shapes = r.require("shapes"); shapes && expect_array(ctx.read, *shapes, "shapes")) {
    for (std::size_t i = 0; i < shapes->as_array().size(); ++i) read_shape(ctx, shapes->as_array()[i], i);
  }
  if (const JsonValue* lights = r.get("lightsources"); lights && expect_array(ctx.read, *lights, "lightsources")) {
    for (std::size_t i = 0; i < lights->as_array().size(); ++i) read_light(ctx, lights->as_array()[i], i);
  }
  r.finish();
}

namespace {

// Material keys of both families, misplaced on the shape itself.
void report_material_keys(ImportContext& ctx, ObjectReader& r, const JsonValue& object) {
  static const char* const kMaterialKeys[] = {
      "ks", "kd", "kr", "kt", "eta", "ior", "specularexponent", "diffusecolor", "specularcolor", "tPath", "tWidth",
      "tHeight", "isreflective", "reflectivity", "isrefractive", "refractiveindex", "refractiveIndex"};
  for (const JsonMember& m : object.as_object()) {
    if (m.duplicate || std::find(std::begin(kMaterialKeys), std::end(kMaterialKeys), m.key) == std::end(kMaterialKeys))
      continue;
    r.allow({m.key});
    ctx.diag().warning(ctx.doc().location(m.key_offset), "'" + m.key + "' is a material key (ignored here); put "
                                                         "it in the shape's \"material\" object");
  }
}

}  // namespace

void finish_legacy_shape(ImportContext& ctx, ObjectReader& r, const JsonValue& object, ShapeDesc shape,
                         LegacyMaterialReader read_material) {
  report_material_keys(ctx, r, object);
  int material = -1;
  const JsonValue* mv = r.get("material");
  if (mv) material = read_material(ctx, *mv);
  r.finish();
  if (!r.ok() || (mv && material < 0)) return;
  shape.material = mv ? material : default_material(ctx);
  ctx.scene.shapes.push_back(std::move(shape));
}

}  // namespace pt
