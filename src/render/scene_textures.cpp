#include "render/scene_textures.h"

#include <bit>
#include <utility>
#include <variant>
#include <vector>

#include "core/rng.h"

#include "core/stopwatch.h"
#include "render/materials/normal_map.h"
#include "scene/material_kinds.h"

namespace pt {

namespace {

bool valid_index(int t, const SceneDescription& desc) {
  return t >= 0 && static_cast<std::size_t>(t) < desc.textures.size();
}

// The textures the materials refer to; false after reporting an index out of range.
bool used_textures(const SceneDescription& desc, std::vector<bool>& used, Diagnostics& diag) {
  used.assign(desc.textures.size(), false);
  for (const MaterialDesc& m : desc.materials) {
    bool in_range = true;
    m.for_each_texture([&](int t) {
      if (!in_range) return;
      if (!valid_index(t, desc)) {
        diag.error(m.where, "material" + (m.name.empty() ? std::string() : " '" + m.name + "'") +
                                " refers to texture " + std::to_string(t) + ", but the scene has " +
                                std::to_string(desc.textures.size()));
        in_range = false;
        return;
      }
      used[static_cast<std::size_t>(t)] = true;
    });
    if (!in_range) return false;
  }
  return true;
}

TextureMapping mapping_of(const TextureDesc& t) {
  TextureMapping m;
  m.object = t.object_mapping;
  m.scale = t.scale;
  if (t.transform) m.transform = t.transform->value;
  return m;
}

// Whether lookups of `t` read the footprint or the object-space position
// (which intersect() then computes at every hit).
bool needs_footprint(const TextureDesc& t) {
  if (t.object_mapping.value || t.type != TextureType::Image) return true;
  return t.filter.value == TextureFilter::Trilinear || t.filter.value == TextureFilter::Anisotropic;
}

// An image embedded in a model file (glTF): written once to the scene's
// scratch folder, then read through the texture cache as every image file is.
std::string embedded_file(const TextureDesc& t, RenderScene& scene, Diagnostics& diag) {
  std::string error;
  const std::string ext = t.embedded_format.empty() ? std::string("png") : t.embedded_format;
  const std::string path = scene.embedded_images.write(*t.embedded, ext, error);
  if (path.empty()) diag.error(t.where, "cannot read texture '" + t.written + "': " + error);
  return path;
}

// One texture: an image through the cache, or a procedural one.
std::unique_ptr<Texture> make_texture(const TextureDesc& t, RenderScene& scene, const BuildOptions& options,
                                      Diagnostics& diag) {
  switch (t.type) {
    case TextureType::Checker:
      return std::make_unique<Texture>(CheckerTexture{t.color0, t.color1, t.object_mapping.value}, mapping_of(t));
    case TextureType::Noise:
      return std::make_unique<Texture>(NoiseTexture{t.color0, t.color1, t.octaves, t.roughness}, mapping_of(t));
    case TextureType::Image: break;
  }
  const auto start = Clock::now();
  const std::string file = t.embedded ? embedded_file(t, scene, diag) : t.resolved;
  if (file.empty()) return nullptr;
  if (!scene.texture_cache) scene.texture_cache = std::make_unique<TextureCache>(options.texture_cache_bytes);
  OpenedImage opened;
  std::string error;
  const bool ok = scene.texture_cache->open(file, t.raw, t.filter, t.wrap, options.textures, opened, error);
  scene.texture_load_seconds += seconds_since(start);
  if (!ok) {
    diag.error(t.where, "cannot read texture '" + t.written + "': " + error);
    return nullptr;
  }
  if (!opened.warning.empty()) diag.warning(t.where, "texture '" + t.written + "': " + opened.warning);
  return std::make_unique<Texture>(std::move(opened.image), mapping_of(t));
}

// The background image, decoded into memory (it is stretched over the frame).
bool load_background(const TextureDesc& t, const TextureLimits& limits, RenderScene& scene, Diagnostics& diag) {
  auto image = std::make_unique<Texture>();
  std::string error;
  const auto start = Clock::now();
  const bool loaded = Texture::load(t.resolved, *image, error, limits, t.raw);
  scene.texture_load_seconds += seconds_since(start);
  if (!loaded) {
    diag.error(t.where, "cannot read background image '" + t.written + "': " + error);
    return false;
  }
  scene.background_image = std::move(image);
  return true;
}

const Texture* texture_at(const std::optional<int>& t, const RenderScene& scene) {
  return t ? scene.textures[static_cast<std::size_t>(*t)].get() : nullptr;
}

}  // namespace

bool load_textures(const SceneDescription& desc, const BuildOptions& options, RenderScene& scene, Diagnostics& diag) {
  std::vector<bool> used;
  if (!used_textures(desc, used, diag)) return false;
  bool ok = true;
  scene.textures.resize(desc.textures.size());
  for (std::size_t i = 0; i < desc.textures.size(); ++i) {
    if (!used[i]) continue;
    scene.textures[i] = make_texture(desc.textures[i], scene, options, diag);
    ok = ok && scene.textures[i] != nullptr;
    scene.footprints = scene.footprints || needs_footprint(desc.textures[i]);
  }
  if (desc.render.background_image) ok = load_background(*desc.render.background_image, options.textures, scene, diag) && ok;
  return ok;
}

void add_materials(const SceneDescription& desc, RenderScene& scene) {
  std::vector<const Texture*> textures;
  for (const std::unique_ptr<Texture>& t : scene.textures) textures.push_back(t.get());
  scene.materials.reserve(desc.materials.size());
  for (const MaterialDesc& d : desc.materials) {
    const CoatingTable* coating = nullptr;
    if (has_coated_diffuse(d.type)) {
      for (const std::unique_ptr<CoatingTable>& c : scene.coatings)
        if (c->ior() == d.ior.value) coating = c.get();
      if (!coating) coating = scene.coatings.emplace_back(std::make_unique<CoatingTable>(d.ior)).get();
    }
    scene.materials.push_back(make_material(d, textures, coating));
  }
}

const CutoutTest* prepare_cutouts(const SceneDescription& desc, RenderScene& scene) {
  scene.cutouts.assign(scene.materials.size(), RenderScene::Cutout{});
  bool any = false;
  for (std::size_t i = 0; i < desc.materials.size() && i < scene.cutouts.size(); ++i) {
    RenderScene::Cutout& c = scene.cutouts[i];
    c.alpha = desc.materials[i].alpha;
    c.texture = texture_at(desc.materials[i].alpha_texture, scene);
    c.cutoff = desc.materials[i].alpha_cutoff;
    c.stochastic = desc.materials[i].alpha_blend.value;
    any = any || c.active();
  }
  if (!any) return nullptr;
  CutoutTest& test = scene.cutout_test;
  const SceneGeometry& g = scene.geometry;
  test.shape.resize(g.shapes.size());
  for (std::size_t s = 0; s < g.shapes.size(); ++s)
    test.shape[s] = scene.cutouts[static_cast<std::size_t>(scene.shape_material[s])].active() ? 1 : 0;
  test.instance.resize(g.instances.size());
  for (std::size_t i = 0; i < g.instances.size(); ++i) {
    const int m = scene.instance_material[i];
    test.instance[i] = m < 0 ? int8_t{-1} : (scene.cutouts[static_cast<std::size_t>(m)].active() ? 1 : 0);
  }
  test.context = &scene;
  test.keeps = [](const void* context, const Ray& ray, uint32_t object, uint32_t prim, const PrimHit& hit,
                  uint32_t inst) { return static_cast<const RenderScene*>(context)->keeps(ray, object, prim, hit, inst); };
  return &test;
}

bool RenderScene::keeps(const Ray& ray, uint32_t object, uint32_t prim, const PrimHit& hit, uint32_t inst) const {
  const Cutout& c = cutouts[static_cast<std::size_t>(material_of(object, inst))];
  if (c.stochastic) return opacity_keeps(c, ray, object, prim, hit, inst);
  if (c.texture == nullptr) return c.alpha >= c.cutoff;
  // A point lookup at the hit, in the shape's own space (ray and hit are there).
  const SurfaceGeometry g = surface(geometry.shapes[object], prim, ray, hit);
  return c.texture->alpha(TexCoord(g.uv, {}, {}, g.p)) >= c.cutoff;
}

// Stochastic opacity (as pbrt-v4's alpha): the surface is there for this ray
// with probability alpha. The uniform number is a hash of the ray, the object,
// its placement, the primitive and (for shapes a ray may meet twice: all but
// meshes, whose triangles it meets once) the hit's distance, so it is the same
// however often a backend tests one candidate, independent between surfaces
// and rays, and a pure function of the ray (renders stay deterministic).
bool RenderScene::opacity_keeps(const Cutout& c, const Ray& ray, uint32_t object, uint32_t prim, const PrimHit& hit,
                                uint32_t inst) const {
  float a = c.alpha;
  const Shape& shape = geometry.shapes[object];
  if (c.texture != nullptr) {
    const SurfaceGeometry g = surface(shape, prim, ray, hit);
    a *= c.texture->alpha(TexCoord(g.uv, {}, {}, g.p));
  }
  if (a >= 1.0f) return true;
  if (!(a > 0.0f)) return false;
  const auto bits = [](float x) { return static_cast<uint64_t>(std::bit_cast<uint32_t>(x)); };
  uint64_t h = hash_keys(bits(ray.origin.x) | bits(ray.origin.y) << 32, bits(ray.origin.z) | bits(ray.dir.x) << 32,
                         bits(ray.dir.y) | bits(ray.dir.z) << 32);
  const float t = std::holds_alternative<TriangleMesh>(shape) ? 0.0f : hit.t;
  h = hash_keys(h, uint64_t{object} | uint64_t{prim} << 32, uint64_t{inst} | bits(t) << 32);
  return static_cast<float>(h >> 40) * 0x1.0p-24f < a;
}

void RenderScene::texture_frame(const RayDifferential* differential, Intersection& out) const {
  SurfaceGeometry& g = out.geo;
  const Transform* t = out.hit.instance != kNoInstance ? &geometry.instances[out.hit.instance].transform : nullptr;
  // The partials where the shape is (its own space), then in world space.
  SurfaceGeometry local = g;
  if (t != nullptr) local.p = t->inverse_point(g.p);
  if (t != nullptr) local.ng = normalize(t->transpose_vector(g.ng));  // the object-space normal (caps read it)
  UvDerivatives d = uv_derivatives(geometry.shapes[out.hit.shape], out.hit.prim, local);
  if (t != nullptr) d = {t->vector(d.dpdu), t->vector(d.dpdv)};
  if (footprints) {
    Vec3f dpdx, dpdy;
    if (differential == nullptr || !footprint_from_differential(*differential, g.p, g.ng, dpdx, dpdy))
      footprint_from_camera(camera_spread, g.p, g.ng, dpdx, dpdy);
    uv_footprint(d.dpdu, d.dpdv, dpdx, dpdy, g.duvdx, g.duvdy);
    g.p_object = local.p;
    g.dpdx = t != nullptr ? t->inverse_vector(dpdx) : dpdx;
    g.dpdy = t != nullptr ? t->inverse_vector(dpdy) : dpdy;
  }
  // After the footprint: normal and bump maps are filtered lookups too.
  if (out.material->perturbs_normal()) perturb_shading_normal(*out.material, d, g);
}

}  // namespace pt
