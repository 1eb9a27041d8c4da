#include "render/render_scene.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <type_traits>
#include <unordered_map>
#include <utility>

#include "core/stopwatch.h"
#include "render/film/cryptomatte.h"
#include "render/scene_textures.h"
#include "scene/validate.h"

namespace pt {

bool RenderScene::intersect(const Ray& ray, Intersection& out, const RayDifferential* differential) const {
  ++detail::t_rays_traced;
  if (!accel->intersect(ray, out.hit)) return false;
  const Shape& shape = geometry.shapes[out.hit.shape];
  PrimHit prim_hit;
  prim_hit.t = out.hit.t;
  prim_hit.uv = out.hit.uv;
  if (out.hit.instance != kNoInstance) {
    instanced_surface(ray, prim_hit, out);
  } else {
    out.geo = surface(shape, out.hit.prim, ray, prim_hit);
    out.material = &materials[static_cast<std::size_t>(shape_material[out.hit.shape])];
  }
  if (shadow_terminator_offset > 0.0f) {
    // A mesh with vertex normals: its rays leave from the smooth surface (geometry/terminator.h).
    const auto* mesh = std::get_if<TriangleMesh>(&shape);
    if (mesh != nullptr && !mesh->normals.empty()) {
      const Transform* t = out.hit.instance != kNoInstance ? &geometry.instances[out.hit.instance].transform : nullptr;
      out.geo.smooth = SmoothSurface{mesh, t, out.hit.prim, out.hit.uv, shadow_terminator_offset};
    }
  }
  if (footprints || out.material->perturbs_normal()) [[unlikely]]
    texture_frame(differential, out);
  return true;
}

// Found in the instance's object space (same t): the surface there, carried to
// world space, and the instance's material. Out of line: scenes without
// instances never come here.
void RenderScene::instanced_surface(const Ray& ray, const PrimHit& prim_hit, Intersection& out) const {
  const Transform& t = geometry.instances[out.hit.instance].transform;
  const Shape& shape = geometry.shapes[out.hit.shape];
  const SurfaceGeometry object = surface(shape, out.hit.prim, t.to_object(ray), prim_hit);
  out.geo = to_world(object, t);
  out.material = &materials[static_cast<std::size_t>(material_of(out.hit.shape, out.hit.instance))];
}

// ---------------------------------------------------------------- resolution
// An override replaces the description's size; if only one of width/height is
// overridden, the other follows the description's aspect ratio.
void resolve_resolution(const FilmDesc& film, const BuildOptions& options, int& width, int& height) {
  width = film.width;
  height = film.height;
  const double aspect = static_cast<double>(film.width.value) / static_cast<double>(film.height.value);
  if (options.width_override > 0 && options.height_override > 0) {
    width = options.width_override;
    height = options.height_override;
  } else if (options.width_override > 0) {
    width = options.width_override;
    height = std::max(1, static_cast<int>(std::lround(width / aspect)));
  } else if (options.height_override > 0) {
    height = options.height_override;
    width = std::max(1, static_cast<int>(std::lround(height * aspect)));
  }
}

namespace {

// ---------------------------------------------------------------- shapes
// ---------------------------------------------------------------- lights
// One overload per LightDesc alternative: the light it becomes (if any).
void add_light(std::vector<Light>& lights, const PointLightDesc& d) {
  lights.emplace_back(PointLight{d.position, d.intensity, d.specular_intensity, d.inverse_square});
}

void add_light(std::vector<Light>& lights, const DirectionalLightDesc& d) {
  // The loader refuses a zero direction; a description built in code might not.
  // Scaled before normalising, so a tiny direction does not flush to zero.
  const float m = max_component(abs(d.direction.value));
  if (!(m > 0.0f) || !std::isfinite(m)) return;
  lights.emplace_back(DirectionalLight{normalize(d.direction.value / m), d.irradiance});
}

void add_light(std::vector<Light>& lights, const SpotLightDesc& d) {
  const float m = max_component(abs(d.direction.value));  // as a directional light's direction
  if (!(m > 0.0f) || !std::isfinite(m)) return;
  const float cone = std::clamp(d.cone_angle.value, 0.0f, 180.0f);
  const float start = std::clamp(cone - d.cone_delta.value, 0.0f, cone);
  lights.emplace_back(SpotLight{d.position, normalize(d.direction.value / m), d.intensity, d.specular_intensity,
                                std::cos(cone * kPi / 180.0f), std::cos(start * kPi / 180.0f)});
}

// Not a light of the set: the classic integrators' constant term (RenderScene::ambient).
void add_light(std::vector<Light>&, const AmbientLightDesc&) {}

// Every light: the description's, every emissive shape, and the environment
// (the map, or the background colour if it is not black).
LightSet build_light_set(const SceneDescription& desc, const RenderScene& scene, LightSamplerType sampler) {
  std::vector<Light> lights;
  for (const LightDesc& l : desc.lights) std::visit([&](const auto& light) { add_light(lights, light); }, l);
  const SceneGeometry& g = scene.geometry;
  const std::vector<bool> direct = placed_directly(g);
  for (std::size_t i = 0; i < g.shapes.size(); ++i) {
    const Material& m = scene.materials[static_cast<std::size_t>(scene.shape_material[i])];
    if (direct[i] && m.emits()) lights.emplace_back(ShapeLight(g.shapes[i], static_cast<uint32_t>(i), m));
  }
  // Each emissive shape of each instance: a light of its own, sampling the
  // shape through the one sampler its placements share (built at first use).
  std::vector<std::shared_ptr<const ShapeAreaSampler>> samplers(g.shapes.size());
  for (std::size_t i = 0; i < g.instances.size(); ++i) {
    const Instance& inst = g.instances[i];
    for (uint32_t s : g.prototypes[inst.prototype]) {
      const Material& m = scene.materials[static_cast<std::size_t>(scene.material_of(s, static_cast<uint32_t>(i)))];
      if (!m.emits()) continue;
      if (!samplers[s]) samplers[s] = std::make_shared<const ShapeAreaSampler>(make_area_sampler(g.shapes[s]));
      lights.emplace_back(ShapeLight(g.shapes[s], s, m, inst.transform, static_cast<uint32_t>(i), samplers[s]));
    }
  }
  if (scene.environment_map) {
    lights.emplace_back(EnvironmentLight{scene.environment_map.get()});
  } else if (!scene.background.is_black()) {
    lights.emplace_back(UniformEnvironment{scene.background});
  }
  const Bounds3f b = scene.accel->bounds();
  float radius = b.empty() ? 1.0f : 0.5f * length(b.extent());
  if (!(radius > 0.0f) || !std::isfinite(radius)) radius = 1.0f;
  return LightSet(std::move(lights), scene.geometry.shapes.size(), radius, sampler);
}

// ---------------------------------------------------------------- geometry
// The shape's material index, or -1 after reporting one out of range.
int shape_material_index(const SceneDescription& desc, const ShapeDesc& s, bool need_default, Diagnostics& diag) {
  if (need_default) return 0;
  if (s.material < 0 || static_cast<std::size_t>(s.material) >= desc.materials.size()) {
    diag.error(s.where, "shape refers to material " + std::to_string(s.material) + ", but the scene has " +
                            std::to_string(desc.materials.size()));
    return -1;
  }
  return s.material;
}

// Cryptomatte's names (SceneNames), each listed once.
class NameList {
 public:
  explicit NameList(std::vector<std::string>& names) : names_(names) {}
  uint32_t index(const std::string& name) {
    const auto [it, added] = index_.emplace(name, static_cast<uint32_t>(names_.size()));
    if (added) names_.push_back(name);
    return it->second;
  }

 private:
  std::vector<std::string>& names_;
  std::unordered_map<std::string, uint32_t> index_;
};

// A shape's Cryptomatte name: its own, else its place in the file ("shapes[3]").
std::string shape_name(const ShapeDesc& s, std::size_t index) {
  return s.name.empty() ? "shapes[" + std::to_string(index) + "]" : s.name;
}

// The shapes (object id = index in desc.shapes, then the objects' shapes in
// order); a transformed shape becomes the one instance of a one-shape
// prototype, each object a prototype, each instance an Instance. Desc is a
// const SceneDescription (each shape's geometry is copied) or a mutable one
// (moved: a mesh's arrays change hands, no copy; build_render_scene_taking_geometry).
template <class Desc>
bool add_geometry(Desc& desc, bool need_default, RenderScene& scene, Diagnostics& diag) {
  SceneGeometry& g = scene.geometry;
  NameList names(scene.names.objects);
  bool ok = true;
  auto add_shape = [&](auto& s, const std::string& name) {
    const int material = shape_material_index(desc, s, need_default, diag);
    ok = ok && material >= 0;
    g.shapes.push_back(std::move(s.geometry));  // a copy when s is const
    scene.shape_material.push_back(std::max(material, 0));
    scene.names.shape_object.push_back(names.index(name));
    return static_cast<uint32_t>(g.shapes.size() - 1);
  };
  auto add_instance = [&](uint32_t prototype, const std::optional<Sourced<Transform>>& t, int material,
                          const std::string& name) {
    g.instances.push_back(Instance{prototype, t ? t->value : Transform()});
    scene.instance_material.push_back(material);
    scene.names.instance_object.push_back(names.index(name));
  };
  g.shapes.reserve(desc.shapes.size());
  scene.shape_material.reserve(desc.shapes.size());
  for (std::size_t i = 0; i < desc.shapes.size(); ++i) {
    auto& s = desc.shapes[i];
    const uint32_t id = add_shape(s, shape_name(s, i));
    if (!s.transform) continue;
    g.prototypes.push_back({id});
    add_instance(static_cast<uint32_t>(g.prototypes.size() - 1), s.transform, -1, shape_name(s, i));
  }
  const auto first_object = static_cast<uint32_t>(g.prototypes.size());
  for (auto& o : desc.objects) {
    std::vector<uint32_t> ids;
    for (auto& s : o.shapes) ids.push_back(add_shape(s, o.name));  // seen through instances only
    g.prototypes.push_back(std::move(ids));
  }
  for (const InstanceDesc& inst : desc.instances) {
    if (inst.object < 0 || static_cast<std::size_t>(inst.object) >= desc.objects.size()) {
      diag.error(inst.where, "instance refers to object " + std::to_string(inst.object) + ", but the scene has " +
                                 std::to_string(desc.objects.size()));
      ok = false;
      continue;
    }
    int material = -1;
    if (inst.material && !need_default) {
      material = *inst.material;
      if (material < 0 || static_cast<std::size_t>(material) >= desc.materials.size()) {
        diag.error(inst.where, "instance refers to material " + std::to_string(material));
        ok = false;
        material = -1;
      }
    }
    add_instance(first_object + static_cast<uint32_t>(inst.object), inst.transform, material,
                 inst.name.empty() ? desc.objects[static_cast<std::size_t>(inst.object)].name : inst.name);
  }
  for (const std::string& name : scene.names.objects) scene.names.object_ids.push_back(cryptomatte_id(name));
  return ok;
}

// Cryptomatte's material names: the materials' own ("default" for the one a
// scene without materials gets).
void add_material_names(const SceneDescription& desc, RenderScene& scene) {
  SceneNames& n = scene.names;
  for (std::size_t i = 0; i < scene.materials.size(); ++i) {
    const std::string& own = i < desc.materials.size() ? desc.materials[i].name : std::string();
    n.materials.push_back(!own.empty()                  ? own
                          : i < desc.materials.size() ? "materials[" + std::to_string(i) + "]"
                                                      : std::string("default"));
    n.material_ids.push_back(cryptomatte_id(n.materials.back()));
  }
}

}  // namespace

RGB RenderScene::background_image_at(Vec2f film_px) const {
  const Texture& image = *background_image;
  // Clamped to the outermost texel centres, where the bilinear lookup has no
  // weight on the wrapped-around texel: the edge texels extend outwards.
  const float hx = 0.5f / static_cast<float>(image.width()), hy = 0.5f / static_cast<float>(image.height());
  const float u = std::clamp(film_px.x / static_cast<float>(width), hx, 1.0f - hx);
  const float v = std::clamp(film_px.y / static_cast<float>(height), hy, 1.0f - hy);
  return image.lookup(Vec2f(u, v));
}

namespace {

// build_render_scene for a const description (its geometry copied) or a
// mutable one (its geometry moved; see add_geometry).
template <class Desc>
std::unique_ptr<RenderScene> build(Desc& desc, const BuildOptions& options, WorkerPool& pool, Diagnostics& diag) {
  if (desc.film.width.value <= 0 || desc.film.height.value <= 0) {
    diag.error(desc.film.width.where, "film resolution must be positive, got " +
                                          std::to_string(desc.film.width.value) + "x" +
                                          std::to_string(desc.film.height.value));
    return nullptr;
  }
  auto scene = std::make_unique<RenderScene>();
  resolve_resolution(desc.film, options, scene->width, scene->height);
  // The loader bounds the file's resolution; overrides (and the aspect ratio
  // that fills in a missing one) are bounded here, before any buffer exists.
  const long long pixels = static_cast<long long>(scene->width) * scene->height;
  if (!options.limits.admits(scene->width, scene->height)) {
    diag.error(SourceLocation{}, "the image would be " + std::to_string(scene->width) + "x" +
                                     std::to_string(scene->height) + " = " + std::to_string(pixels) +
                                     " pixels; at most " + std::to_string(options.limits.max_resolution) +
                                     " per side and " + std::to_string(options.limits.max_pixels) + " in all");
    return nullptr;
  }
  scene->camera = Camera(desc.camera, scene->width, scene->height);
  scene->background = desc.render.background;

  bool ok = load_textures(desc, options, *scene, diag);
  if (ok) {
    add_materials(desc, *scene);
  }
  scene->camera_spread = CameraSpread::of(scene->camera, scene->width, scene->height);
  // Shapes without a valid material get a default one, so a description built
  // in code with no materials still renders (reported as an error otherwise).
  const bool need_default = desc.materials.empty();
  if (need_default) scene->materials.emplace_back();

  // Loaded scenes were validated; one built in code is checked here for what
  // the accelerators and lights rely on.
  if (!check_shapes_usable(desc, diag)) ok = false;
  if (!add_geometry(desc, need_default, *scene, diag)) ok = false;
  add_material_names(desc, *scene);

  if (desc.environment) {
    const auto environment_start = Clock::now();
    std::string error, warning;
    scene->environment_map = EnvironmentMap::load(*desc.environment, error, options.textures, &warning);
    scene->texture_load_seconds += seconds_since(environment_start);
    if (!scene->environment_map) {
      diag.error(desc.environment->file.where,
                 "cannot read environment map '" + desc.environment->file.value + "': " + error);
      ok = false;
    } else if (!warning.empty()) {
      diag.warning(desc.environment->file.where, "environment map '" + desc.environment->file.value + "': " + warning);
    }
  }

  if (!ok) return nullptr;
  const CutoutTest* cutouts = prepare_cutouts(desc, *scene);
  scene->accel = build_accelerator(options.accel, scene->geometry, pool, diag, cutouts);
  if (!scene->accel) return nullptr;
  scene->shadow_terminator_offset = options.shadow_terminator_offset;
  scene->lights = build_light_set(desc, *scene, options.light_sampler);
  for (const LightDesc& l : desc.lights)
    if (const auto* ambient = std::get_if<AmbientLightDesc>(&l)) scene->ambient += ambient->intensity.value;
  return scene;
}

}  // namespace

std::unique_ptr<RenderScene> build_render_scene(const SceneDescription& desc, const BuildOptions& options,
                                                WorkerPool& pool, Diagnostics& diag) {
  return build(desc, options, pool, diag);
}

std::unique_ptr<RenderScene> build_render_scene_taking_geometry(SceneDescription& desc, const BuildOptions& options,
                                                                WorkerPool& pool, Diagnostics& diag) {
  return build(desc, options, pool, diag);
}

}  // namespace pt
