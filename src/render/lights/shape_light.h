// An area light: a shape whose material emits. Every shape type can emit:
//  - spheres are sampled by solid angle (uniformly inside the cone they
//    subtend) from points outside them, and by area from inside;
//  - quads, triangles, meshes and cylinders are sampled uniformly by area
//    (a mesh picks a triangle in proportion to its area, a quad one of its two
//    triangles, a cylinder its side or a cap), so the area density is 1 / A;
//    a quad or a two-triangle mesh that is a planar parallelogram (the usual
//    rectangular area light) is sampled directly as p0 + u e1 + v e2, the same
//    density at a fraction of the cost, and a stratified (u, v) stays
//    stratified on the light;
//  - a rectangle (a parallelogram with perpendicular edges) is sampled
//    uniformly by solid angle (spherical rectangle sampling) when
//    `solid_angle_rectangles` is on and it subtends at least
//    kMinSphericalRectangle sr (below that, float precision fails; by area).
// A shape placed by an instance (SceneGeometry::instances) is a light of its
// own for each instance, and the placements of one shape share its sampler
// (built once, in object space: an emissive mesh placed 10,000 times is not
// 10,000 copies of its triangles). A sphere under a similarity transform is
// still a sphere (sampled by solid angle, its world centre and radius); a quad
// or two-triangle parallelogram stays a parallelogram (its corners and edges
// transformed); every other shape is sampled by area in object space and
// mapped to world space, its density divided by the area scale at the point,
// |det M| / |M^T n| (n the unit world normal). A similarity scales every
// area alike, so a mesh's triangles are still picked in proportion to their
// world areas, i.e. their emitted power; under any other map an instance of a
// shape made of triangles (mesh, polygon, quad) picks them by their world
// areas from a distribution of its own (8 bytes per triangle), so the density
// is the uniform 1 / A_world again.
// Emission is one-sided (the side of the shape's geometric normal) unless the
// material is two-sided; see Material::emitted. A textured emission (MTL's
// map_Ke, glTF's emissiveTexture) is sampled as an untextured one, by area or
// solid angle, and the texture read at the sampled point (tex_coord_at): the
// density does not follow the texture (power and the light BVH read the
// emission factor), which costs variance on a mostly dark texture, not bias.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "core/sampling.h"
#include "geometry/shapes.h"
#include "render/lights/light.h"
#include "render/lights/light_bounds.h"
#include "render/materials/material.h"

namespace pt {

inline constexpr float kMinSphericalRectangle = 1e-3f;

class ShapeLight {
 public:
  // The light interface's flags (render/lights/light.h).
  static constexpr bool delta = false;
  static constexpr bool infinite = false;

  ShapeLight(const Shape& shape, uint32_t shape_id, const Material& material, bool solid_angle_rectangles = false);
  // The shape placed by `instance` with object-to-world `transform` (which
  // must outlive the light). `sampler`, if given, is make_area_sampler(shape),
  // shared with the shape's other placements.
  ShapeLight(const Shape& shape, uint32_t shape_id, const Material& material, const Transform& transform,
             uint32_t instance, std::shared_ptr<const ShapeAreaSampler> sampler = nullptr);

  uint32_t shape_id() const { return shape_id_; }
  uint32_t instance() const { return instance_; }
  const Material& material() const { return *material_; }
  // In object space for a light sampled there (see above); in world space for a
  // parallelogram or triangles picked by world area.
  float area() const { return area_; }
  // Samples a point of the light as seen from p; false if nothing can be sampled.
  bool sample(Vec3f p, Vec2f u, LightSample& s) const;
  // The solid-angle density with which sample(p, ...) produces direction wi
  // reaching the light at point q with geometric normal n.
  float pdf(Vec3f p, Vec3f wi, Vec3f q, Vec3f n) const;
  float power() const;
  float power(float /*scene_radius*/) const { return power(); }  // the light interface's signature
  // Its world bounds, intensity and normal cone for the light BVH (light_bounds.h);
  // false if it has none (no area, no emission, or unbounded).
  bool bounds(LightBounds& out) const;
  // Whether the shape is a planar parallelogram sampled as one (see above).
  bool sampled_as_parallelogram() const { return parallelogram_; }
  bool sampled_by_solid_angle_as_rectangle() const { return rectangle_; }

 private:
  // A point uniformly distributed by area (the density is 1 / area_), and
  // the primitive it is on (-1: not known, one of a parallelogram's two).
  void sample_area(Vec2f u, Vec3f& q, Vec3f& n, int& prim) const;
  // The texture coordinates of the shape at a sampled point q with normal n
  // (world space), for a textured emission: the shape's own surface where a
  // short ray along -n meets primitive `prim` at q (object space).
  TexCoord tex_coord_at(Vec3f q, Vec3f n, int prim) const;
  // The area of the shape around a point with unit normal n, as the density
  // 1 / that of sample_area() there: area_, scaled for a transformed shape.
  float area_at(Vec3f n) const;
  // The shape's world area (estimated for a transformed curved shape, see power()).
  float world_area() const;
  // A cone holding every emitting normal, in world space (all directions for a curved shape).
  DirectionCone normal_cone() const;
  // The sphere sampled by solid angle, if any (in world space).
  const Sphere* cone_sphere() const;
  bool sample_sphere_cone(const Sphere& s, Vec3f p, Vec2f u, LightSample& out) const;

  // A triangle ready to sample: a corner, its two edges and the unit normal.
  using Triangle = TriangleAreaSampler::Triangle;
  // A parallelogram with the given corners, if a, b, c, d (in order around
  // it) form one and both halves face the same way as `n`.
  static bool make_parallelogram(Vec3f a, Vec3f b, Vec3f c, Vec3f d, Vec3f n, Triangle& out);
  void detect_parallelogram();
  ShapeLight(const Shape& shape, uint32_t shape_id, const Material& material,
             std::shared_ptr<const ShapeAreaSampler> sampler);
  // The by-area sampler's triangles, if the shape is sampled as triangles.
  const TriangleAreaSampler* triangle_sampler() const;
  // Picks the triangles by their areas under `transform` (see above).
  void weigh_triangles_by_world_area(const Transform& transform);

  // The parallelogram (p0, e1, e2, n) if the shape is one (see above).
  bool parallelogram_ = false;
  bool rectangle_ = false;  // and sampled by solid angle
  Triangle para_{};
  // The rectangle as seen from p, if sampled by solid angle from there.
  bool spherical_rectangle(Vec3f p, SphericalRectangle& r) const;

  const Shape* shape_;
  uint32_t shape_id_;
  uint32_t instance_ = kNoInstance;
  const Transform* transform_ = nullptr;  // object to world, for an instance's light
  Distribution1D world_parts_;            // the sampler's triangles by world area, if
  bool world_triangles_ = false;          // weigh_triangles_by_world_area() made it
  Sphere world_sphere_{};                 // a sphere under a similarity transform, in world space
  bool has_world_sphere_ = false;
  const Material* material_;
  float area_ = 0.0f;
  // The shape's own sampling by area (geometry/shapes/*.h), in object space.
  std::shared_ptr<const ShapeAreaSampler> sampler_;
};

}  // namespace pt
