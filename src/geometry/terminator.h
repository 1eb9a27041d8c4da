// The shadow terminator (docs/rendering.md, "Shadow terminator"): a mesh
// whose vertex normals are interpolated is shaded as the smooth surface they
// imply, but its rays leave the flat triangles. Near the terminator, where the
// smooth normal still faces a light the triangle already faces away from (or
// barely faces), a ray leaving the flat triangle meets the neighbouring
// triangles, which the smooth surface would not have: faceted dark bands.
// The policy: rays leave from the smooth surface instead, Hanika's offset
// ("Hacking the Shadow Terminator", Ray Tracing Gems II, ch. 4, 2021), applied
// where the direction is near the triangle's tangent plane with Cycles' rule
// (its per-object "Shadow Terminator > Geometry Offset", default 0.1).
#pragma once

#include "core/math.h"
#include "geometry/shape_base.h"

namespace pt {

// Hanika's offset: the displacement from p, a point of the flat triangle with
// corners v and unit vertex normals n (on the side to offset to), to the
// surface the normals imply: p projected onto the tangent plane of each corner
// where it lies below that plane (unmoved where above: the surface curves away
// there), the three projections weighted by the barycentrics w of p. Zero for
// a flat triangle with equal normals; along the bulge for a convex one.
Vec3f terminator_offset(Vec3f p, const Vec3f v[3], const Vec3f n[3], Vec3f w);

// How much of the offset a ray leaving in unit direction wi gets (Cycles 3.4's
// `shadow_ray_offset`): with cos_ns = |ns . wi| and cos_ng = ng . wi, ng taken
// on the side of ns that wi leaves on, all of it where the triangle faces away
// (cos_ng <= 0), none where it faces wi by cos_ng >= cutoff (or >= 2 cutoff
// when cos_ns < cutoff), linear between. 0 for cutoff <= 0.
float terminator_amount(float cos_ns, float cos_ng, float cutoff);

// Hanika's offset at a mesh hit, in world space; `outer`: towards the side the
// vertex normals point to (the side of SurfaceGeometry::ns), else the other.
// Never moves the point to the other side of the triangle's plane.
Vec3f terminator_offset(const SmoothSurface& s, bool outer);

}  // namespace pt
