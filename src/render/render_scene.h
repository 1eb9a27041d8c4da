// RenderScene: the immutable, render-time scene. Built once from a
// SceneDescription (textures decoded, geometry converted, accelerator built);
// integrators only read it.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "accel/accelerator.h"
#include "accel/cutout.h"
#include "core/diagnostics.h"
#include "geometry/shapes.h"
#include "render/camera/camera.h"
#include "render/camera/ray_differential.h"
#include "render/lights/environment.h"
#include "render/lights/light.h"
#include "render/lights/light_set.h"
#include "render/materials/coated_diffuse.h"
#include "render/materials/material.h"
#include "render/textures/footprint.h"
#include "render/textures/texture.h"
#include "render/textures/scratch_folder.h"
#include "render/textures/texture_cache.h"
#include "scene/resolution_limits.h"
#include "scene/scene_description.h"

namespace pt {

class WorkerPool;

// What a camera or bounce ray found.
struct Intersection {
  Hit hit;
  SurfaceGeometry geo;
  const Material* material = nullptr;
};

namespace detail {
// Rays the calling thread has traced through a RenderScene (camera, bounce and
// shadow rays). Per thread, so counting costs an increment of a thread-local
// integer and no synchronisation; the render loop reads it before and after
// each tile to tell its RenderMonitor how many rays the tile traced.
inline thread_local uint64_t t_rays_traced = 0;
}  // namespace detail
inline uint64_t rays_traced_by_this_thread() { return detail::t_rays_traced; }

// The names Cryptomatte gives what a camera ray hits (render/film/cryptomatte.h;
// docs/output.md): an object is a shape placed directly (its `name`), or an
// instance (its `name`, else its object's); a material is a material. Each
// name is listed once; the ids are cryptomatte_id(name).
struct SceneNames {
  std::vector<std::string> objects;        // each once
  std::vector<float> object_ids;           // per entry of `objects`
  std::vector<uint32_t> shape_object;      // per shape: its entry in `objects` when placed directly
  std::vector<uint32_t> instance_object;   // per instance: its entry in `objects`
  std::vector<std::string> materials;      // per material (RenderScene::materials), each once
  std::vector<float> material_ids;         // per material

  // The id of what a hit on `shape` through `instance` (kNoInstance: placed directly) belongs to.
  float object_id(uint32_t shape, uint32_t instance) const {
    return object_ids[instance != kNoInstance ? instance_object[instance] : shape_object[shape]];
  }
};

struct RenderScene {
  int width = 0, height = 0;
  Camera camera;
  RGB background;
  RGB ambient;  // the sum of the ambient lights: the classic integrators' constant term (whitted.cpp)
  SceneGeometry geometry;
  std::vector<int> shape_material;   // per shape, index into materials
  std::vector<int> instance_material;  // per instance: index into materials, or -1 for its shapes' own
  std::vector<Material> materials;
  SceneNames names;  // Cryptomatte's
  // Embedded images written out for the texture cache; declared before the
  // cache, so destroyed (its files removed) after it.
  ScratchFolder embedded_images;
  // The image textures' cache (OpenImageIO's TextureSystem), if the scene has any.
  std::unique_ptr<TextureCache> texture_cache;
  std::vector<std::unique_ptr<Texture>> textures;  // stable addresses (materials point in)
  std::vector<std::unique_ptr<CoatingTable>> coatings;  // coated diffuse albedo tables, one per index
  std::unique_ptr<Texture> background_image;       // render.background_image, if any
  // Owns the environment map (its sampling distribution included) when the
  // scene has one; it is reached through `lights` (an EnvironmentLight).
  std::unique_ptr<EnvironmentMap> environment_map;
  // Every light, each stored once (built after the accelerator: infinite
  // lights' power estimates need the scene bounds).
  LightSet lights;
  // Alpha cutouts (docs/textures.md): per material, its constant alpha or
  // its alpha texture; the test the accelerator calls for the shapes whose
  // material has one (none: the accelerator gets no test and runs none).
  // A blended one (stochastic) is there for a ray with probability alpha (times
  // the texture's), decided by a hash of the ray and the candidate hit.
  struct Cutout {
    float alpha = 1.0f;
    const Texture* texture = nullptr;
    float cutoff = kAlphaCutoff;  // the surface is there where alpha >= cutoff
    bool stochastic = false;      // alpha an opacity (MaterialDesc::alpha_blend)
    bool active() const { return texture != nullptr || !(alpha >= (stochastic ? 1.0f : cutoff)); }
  };
  static constexpr float kAlphaCutoff = 0.5f;  // the native format's cutoff (importers set others)
  std::vector<Cutout> cutouts;
  CutoutTest cutout_test;
  // Whether intersect() computes texture footprints (geo.duvdx, ...): some
  // texture filters over one or reads the object-space position. From camera
  // ray differentials at first hits, else from the camera's spread.
  bool footprints = false;
  CameraSpread camera_spread;
  // render.shadow_terminator_geometry_offset (0: off): rays leaving a mesh
  // with vertex normals near its terminator leave from the smooth surface the
  // normals imply (geometry/terminator.h; docs/rendering.md, "Shadow terminator").
  float shadow_terminator_offset = kDefaultShadowTerminatorOffset;
  std::unique_ptr<Accelerator> accel;  // after what its cutout test reads
  double texture_load_seconds = 0;  // decoding the textures and the environment map; 0 if there are none

  // The material of a shape hit through `instance` (or placed directly, kNoInstance).
  int material_of(uint32_t shape, uint32_t instance) const {
    if (instance != kNoInstance && instance_material[instance] >= 0) return instance_material[instance];
    return shape_material[shape];
  }
  // Both count the ray in the calling thread's rays_traced_by_this_thread().
  // `differential`: a camera ray's, for the footprint of its first hit (null
  // for any other ray).
  bool intersect(const Ray& ray, Intersection& out, const RayDifferential* differential = nullptr) const;
  bool occluded(const Ray& ray) const {
    ++detail::t_rays_traced;
    return accel->occluded(ray);
  }
  // The rest of intersect() for a hit through an instance.
  [[gnu::noinline]] void instanced_surface(const Ray& ray, const PrimHit& prim_hit, Intersection& out) const;
  // A hit's tangent frame at work (scene_textures.cpp): its texture footprint
  // (scenes with `footprints`) and its shading normal perturbed by the
  // material's normal or bump map. One uv_derivatives() serves both.
  [[gnu::noinline]] void texture_frame(const RayDifferential* differential, Intersection& out) const;
  // Whether the surface is there at a candidate hit (the cutout test; ray in the shape's space).
  bool keeps(const Ray& ray, uint32_t object, uint32_t prim, const PrimHit& hit, uint32_t instance) const;
  // The same for a blended material (stochastic opacity).
  bool opacity_keeps(const Cutout& c, const Ray& ray, uint32_t object, uint32_t prim, const PrimHit& hit,
                     uint32_t instance) const;
  // The first texture read that failed during rendering (a file changed or
  // broken since the scene was built), empty if none did: the render is not to be trusted.
  std::string texture_failure() const { return texture_cache ? texture_cache->failure() : std::string(); }
  // Radiance seen by a ray that leaves the scene in direction `dir`: the
  // environment light's (the map, or the background colour), or else the
  // background colour (black).
  RGB escaped_radiance(Vec3f dir) const { return lights.escaped_radiance(dir, background); }
  // Radiance seen by a camera ray (one `camera` generated) that leaves the
  // scene: the background image at the ray's film position if the scene has
  // one, else escaped_radiance. Only integrators' depth-0 misses ask this.
  RGB camera_ray_escaped(const Ray& camera_ray) const {
    return background_image ? background_image_at(camera.film_position(camera_ray))
                            : escaped_radiance(camera_ray.dir);
  }
  // The background image (render.background_image) stretched over the full
  // frame, bilinear, its edge texels extended: film pixel (x, y) shows image
  // uv (x / width, y / height), whatever the crop.
  RGB background_image_at(Vec2f film_px) const;
};


struct BuildOptions {
  AccelKind accel = AccelKind::Bvh;  // as the command line's default
  int width_override = 0;   // > 0 replaces the description's resolution
  int height_override = 0;
  ResolutionLimits limits;           // the image after the overrides, as LoadOptions
  TextureLimits textures;            // every texture and environment map, checked before decoding
  uint64_t texture_cache_bytes = TextureCache::kDefaultBytes;  // --texture-cache
  LightSamplerType light_sampler = LightSamplerType::Bvh;  // render.light_sampler (LightSet)
  float shadow_terminator_offset = kDefaultShadowTerminatorOffset;  // render.shadow_terminator_geometry_offset
};

// The image size build_render_scene gives `film` under `options` (an override
// of one side keeps the description's aspect ratio).
void resolve_resolution(const FilmDesc& film, const BuildOptions& options, int& width, int& height);

// Builds the render scene, or returns nullptr after reporting to `diag`
// (texture that fails to decode, accelerator failure, ...).
std::unique_ptr<RenderScene> build_render_scene(const SceneDescription& desc, const BuildOptions& options,
                                                WorkerPool& pool, Diagnostics& diag);
// As build_render_scene, but each shape's geometry (a mesh's vertex, index,
// normal and uv arrays) is moved into the render scene instead of copied:
// `desc` keeps everything else, its shapes are left without geometry. For a
// caller that does not need the description's geometry afterwards (the
// pathtracer): a large mesh is then held once, not twice (tools/bench/scale).
std::unique_ptr<RenderScene> build_render_scene_taking_geometry(SceneDescription& desc, const BuildOptions& options,
                                                                WorkerPool& pool, Diagnostics& diag);

}  // namespace pt
