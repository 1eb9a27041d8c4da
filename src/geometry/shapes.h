// The list of shapes. Each shape is defined once, in its own header under
// geometry/shapes/, by its struct and the routines every other part of the
// renderer finds by name (overloads on the shape type):
//   Bounds3f bounds(const S&)                      conservative, never invalid (but empty
//                                                  for the unbounded InfinitePlane)
//   uint32_t primitive_count(const S&)             1, or one per triangle of a mesh (0 for
//                                                  the InfinitePlane: accel/unbounded.h tests it)
//   bool intersect(const S&, const Ray&, PrimHit&) (or, with several primitives,
//        intersect(s, prim, ray, hit) and bounds(s, prim))
//   SurfaceGeometry surface(const S&, const Ray&, const PrimHit&)   (or with prim)
//   UvDerivatives uv_derivatives(const S&, const SurfaceGeometry&)  (or with prim): dp/du, dp/dv
//                                                  at a point surface() returned (normal and bump maps)
//   void check(const S&, ShapeChecker&)            the validation rule
//   make_area_sampler(const S&)                    sampling by area, for area lights
// Both acceleration backends, the area lights and scene validation work over
// the Shape variant below; adding a shape is "Adding a shape" in docs/architecture.md.
//
// Contract for every intersect():
//  - returns true and fills `hit` only for the nearest hit with
//    ray.tmin < t < ray.tmax (strict on both ends); `ray.dir` need not be unit;
//  - never returns true for NaN t; degenerate shapes (zero radius, zero-area
//    triangle/quad) never report hits; NaN/inf rays never hit;
//  - `hit.uv` holds what surface() needs beyond ray.at(t) (see PrimHit).
//  - no allocation, no virtual calls: this is the inner loop of both backends.
// Parameterisations, normal conventions and the self-intersection policy are
// documented in docs/geometry.md.
#pragma once

#include <cstdint>
#include <variant>
#include <vector>

#include "core/math.h"
#include "core/transform.h"
#include "geometry/shape_base.h"
#include "geometry/shapes/cone.h"
#include "geometry/shapes/cylinder.h"
#include "geometry/shapes/disc.h"
#include "geometry/shapes/mesh.h"
#include "geometry/shapes/plane.h"
#include "geometry/shapes/polygon.h"
#include "geometry/shapes/quad.h"
#include "geometry/shapes/sphere.h"

namespace pt {

// One renderable object. Its index in SceneGeometry::shapes is its object id
// (Embree geomID == object id; prim id is the triangle index for meshes, 0 otherwise).
using Shape = std::variant<Sphere, Quad, Cylinder, TriangleMesh, Disc, ConvexPolygon, Cone, InfinitePlane>;

// No instance: a shape placed directly in world space.
inline constexpr uint32_t kNoInstance = UINT32_MAX;

// One placement of a prototype (a group of shapes defined in object space).
struct Instance {
  uint32_t prototype = 0;  // index into SceneGeometry::prototypes
  Transform transform;     // object to world
};

// Every shape, and how it is placed. A shape listed in a prototype is in that
// prototype's object space and appears in the world only through instances;
// every other shape is in world space and placed directly (a scene without
// instances is exactly that, with no cost for the instancing).
struct SceneGeometry {
  std::vector<Shape> shapes;
  std::vector<std::vector<uint32_t>> prototypes;  // each: the object ids of its shapes
  std::vector<Instance> instances;
};

// Per shape: whether it is placed directly (listed in no prototype).
std::vector<bool> placed_directly(const SceneGeometry& g);
// World bounds of everything in the scene: direct shapes and every instance.
Bounds3f world_bounds(const SceneGeometry& g);
// A surface point found in object space, carried to world space by `t`:
// position (its error bound grown by the transform's rounding), normals by the
// inverse transpose (renormalised; the outward side survives a mirroring map).
SurfaceGeometry to_world(const SurfaceGeometry& s, const Transform& t);

// ---------------------------------------------------------------- generic over shapes
// A shape intersected as a whole (one primitive), as opposed to one made of
// primitives addressed by index (a mesh's triangles).
template <class S>
concept WholeShape = requires(const S& s, const Ray& r, PrimHit& h) { intersect(s, r, h); };

// Primitive `prim` of a shape (prim is 0 for a whole shape).
template <class S>
Bounds3f primitive_bounds(const S& s, uint32_t prim) {
  if constexpr (WholeShape<S>) return bounds(s);
  else return bounds(s, prim);
}

template <class S>
bool intersect_primitive(const S& s, uint32_t prim, const Ray& ray, PrimHit& hit) {
  if constexpr (WholeShape<S>) return intersect(s, ray, hit);
  else return intersect(s, prim, ray, hit);
}

template <class S>
SurfaceGeometry surface_of_primitive(const S& s, uint32_t prim, const Ray& ray, const PrimHit& hit) {
  if constexpr (WholeShape<S>) return surface(s, ray, hit);
  else return surface(s, prim, ray, hit);
}

template <class S>
UvDerivatives uv_derivatives_of_primitive(const S& s, uint32_t prim, const SurfaceGeometry& sg) {
  if constexpr (requires { uv_derivatives(s, sg); }) return uv_derivatives(s, sg);
  else return uv_derivatives(s, prim, sg);
}

// A typed reference to one shape of a SceneGeometry (one pointer per
// alternative of Shape, generated from its list).
template <class V>
struct RefVariant;
template <class... S>
struct RefVariant<std::variant<S...>> {
  using type = std::variant<const S*...>;
};
using ShapeRef = RefVariant<Shape>::type;

// The by-area sampler of each alternative of Shape (duplicates allowed:
// quads and meshes share TriangleAreaSampler; construct by index).
template <class V>
struct AreaSamplerVariant;
template <class... S>
struct AreaSamplerVariant<std::variant<S...>> {
  using type = std::variant<decltype(make_area_sampler(std::declval<const S&>()))...>;
};
using ShapeAreaSampler = AreaSamplerVariant<Shape>::type;
ShapeAreaSampler make_area_sampler(const Shape& s);

// Dispatch on the variant (prim is ignored for whole shapes).
Bounds3f bounds(const Shape& s);
uint32_t primitive_count(const Shape& s);
SurfaceGeometry surface(const Shape& s, uint32_t prim, const Ray& ray, const PrimHit& hit);
UvDerivatives uv_derivatives(const Shape& s, uint32_t prim, const SurfaceGeometry& sg);
void check(const Shape& s, ShapeChecker& c);

// ---------------------------------------------------------------- self-intersection
// Shadow rays built by spawn_ray_to() end at t = 1 - kShadowEpsilon (target at t = 1).
inline constexpr float kShadowEpsilon = 1e-4f;

// Offsets a ray origin leaving surface point p (with geometric normal ng) to the
// side given by `dir`, far enough that the new ray cannot re-hit the surface it
// leaves, yet close enough for contact shadows: pbrt-v4 style, the offset along
// ng is the error bound `p_error` projected on ng, and the result is rounded
// away from the surface. See docs/geometry.md for the policy.
Vec3f offset_ray_origin(Vec3f p, Vec3f p_error, Vec3f ng, Vec3f dir);
// As above with an error bound estimated from the magnitude of p alone, for
// callers without a SurfaceGeometry (e.g. a sampled light point). Prefer the
// four-argument form: a point near the origin on a large shape needs more.
Vec3f offset_ray_origin(Vec3f p, Vec3f ng, Vec3f dir);

// A ray leaving a surface point towards `dir`, origin offset as above, tmin = 0.
// At a point of a smooth-shaded mesh with sg.smooth set (the shadow-terminator
// offset on), the origin is first moved towards the smooth surface the vertex
// normals imply, for directions near the triangle's plane, and is offset to
// the side of the plane the shading normal is on for `dir` (geometry/terminator.h).
Ray spawn_ray(const SurfaceGeometry& sg, Vec3f dir);
// A shadow ray from a surface point to a point `target` (e.g. a light), which
// stops just short of the target: dir = target - origin, tmin = 0,
// tmax = 1 - kShadowEpsilon. For a target on a surface (an area light sample)
// pass a target offset from that surface with offset_ray_origin().
Ray spawn_ray_to(const SurfaceGeometry& sg, Vec3f target);

}  // namespace pt
