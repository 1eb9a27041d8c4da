// Render-time shape data and the one place each shape's bounds, intersection
// and surface evaluation are written. Both acceleration backends (Embree user
// geometry and our own BVH) call exactly these routines.
//
// Contract for every intersect_*():
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

namespace pt {

struct PrimHit {
  float t = kInfinity;
  // Shape-specific parameters:
  //  triangle: barycentrics (b1, b2) of p1 and p2;
  //  quad:     (u, v) of the two-triangle parameterisation (u >= v: triangle
  //            v0 v1 v2, else v0 v2 v3; equals the bilinear (u, v) for parallelograms);
  //  cylinder: (part, 0), part 0 = side, 1 = cap at p0, 2 = cap at p1;
  //  sphere:   unused (0, 0); surface() reprojects ray.at(t).
  Vec2f uv;
};

// Local geometry at a hit point.
struct SurfaceGeometry {
  Vec3f p;        // position
  Vec3f ng;       // unit geometric normal (shape's outward side; NOT flipped towards the ray)
  Vec3f ns;       // unit shading normal (interpolated for meshes with normals), same side as ng
  Vec2f uv;       // texture coordinates
  // Conservative per-component bound on the absolute error of `p` (and of the
  // shape's own intersection routine near p); used by spawn_ray().
  Vec3f p_error;
};

struct Sphere {
  Vec3f center;
  float radius = 1;
  Vec3f pole{0, 1, 0};  // unit; texture-mapping axis
};

// Planar convex quad, corners in perimeter order.
struct Quad {
  Vec3f v[4];
};

// Capped cylinder between cap centres p0 and p1.
struct Cylinder {
  Vec3f p0, p1;
  float radius = 1;
};

struct TriangleMesh {
  std::vector<Vec3f> positions;
  std::vector<uint32_t> indices;  // 3 per triangle
  std::vector<Vec3f> normals;     // empty or one per vertex
  std::vector<Vec2f> uvs;         // empty or one per vertex
  std::size_t triangle_count() const { return indices.size() / 3; }
};

// One renderable object. Its index in SceneGeometry::shapes is its object id
// (Embree geomID == object id; prim id is the triangle index for meshes, 0 otherwise).
using Shape = std::variant<Sphere, Quad, Cylinder, TriangleMesh>;

struct SceneGeometry {
  std::vector<Shape> shapes;
};

// ---------------------------------------------------------------- per shape
// Bounds are conservative (padded by a few ulps) and never invalid: a
// degenerate shape gets a point box.
Bounds3f bounds(const Sphere& s);
Bounds3f bounds(const Quad& q);
Bounds3f bounds(const Cylinder& c);
Bounds3f triangle_bounds(const TriangleMesh& m, uint32_t tri);

bool intersect(const Sphere& s, const Ray& ray, PrimHit& hit);
bool intersect(const Quad& q, const Ray& ray, PrimHit& hit);
bool intersect(const Cylinder& c, const Ray& ray, PrimHit& hit);
// Watertight ray/triangle test (Woop, Benthin, Wald 2013). uv = barycentrics of v1, v2.
bool intersect_triangle(Vec3f p0, Vec3f p1, Vec3f p2, const Ray& ray, PrimHit& hit);
bool intersect(const TriangleMesh& m, uint32_t tri, const Ray& ray, PrimHit& hit);

SurfaceGeometry surface(const Sphere& s, const Ray& ray, const PrimHit& hit);
SurfaceGeometry surface(const Quad& q, const Ray& ray, const PrimHit& hit);
SurfaceGeometry surface(const Cylinder& c, const Ray& ray, const PrimHit& hit);
SurfaceGeometry surface(const TriangleMesh& m, uint32_t tri, const Ray& ray, const PrimHit& hit);

// Dispatch on the variant (prim is ignored for non-mesh shapes).
Bounds3f bounds(const Shape& s);
SurfaceGeometry surface(const Shape& s, uint32_t prim, const Ray& ray, const PrimHit& hit);

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
Ray spawn_ray(const SurfaceGeometry& sg, Vec3f dir);
// A shadow ray from a surface point to a point `target` (e.g. a light), which
// stops just short of the target: dir = target - origin, tmin = 0,
// tmax = 1 - kShadowEpsilon. For a target on a surface (an area light sample)
// pass a target offset from that surface with offset_ray_origin().
Ray spawn_ray_to(const SurfaceGeometry& sg, Vec3f target);

}  // namespace pt
