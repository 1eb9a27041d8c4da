// Traces the same rays through two backends and classifies every ray:
//  - agree:      both miss, or both hit the same primitive (of the same
//                instance) at distances within the tolerance (relative to
//                max(t, |origin| / |dir|, 1e-3));
//  - tie:        both hit at distances within the tolerance but different
//                primitives or placements (coincident or touching surfaces,
//                or the two triangles either side of an edge the ray passes through);
//  - hit_miss:   one hits, the other does not;
//  - distance:   both hit, at distances differing beyond the tolerance.
// Shadow rays compare occluded() answers (agree or hit_miss only).
// The backends need not agree ray for ray (Embree's triangle test is not ours,
// docs/geometry.md): every disagreement is given a cause (see Cause), found
// from the geometry in double precision, and the agreeing hits' distances are
// compared bit for bit.
// An image marks the pixels with a disagreement (see disagreement_image).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "accel/accelerator.h"
#include "core/image.h"
#include "ray_sets.h"

namespace pt {
class WorkerPool;
}

namespace pt::bench {

enum class Verdict : uint8_t { Agree, Tie, HitMiss, Distance };

// Why two backends disagree on a ray, from the hit(s) they report, first that
// applies:
//  - vertex / edge: a triangle hit lies within kBoundary (barycentric) of a
//    corner or of an edge: the two triangle tests round differently there
//    (the ray leaks between two triangles in one backend, or grazes one
//    triangle just outside its edge);
//  - grazing: the ray runs within 1e-3 (cosine) of a triangle's plane;
//  - ray start: the hit is nearer the ray's start than 1% of the distance to
//    the triangle's farthest corner (or a relative 1e-4 for other shapes):
//    our routine rejects a t within its error bound (pbrt-v4's) for a triangle
//    reaching behind the origin, and that bound grows with the triangle; Embree
//    keeps such hits, including re-hits of the surface a ray leaves;
//  - ray end: the hit is within a relative 1e-4 of the ray's finite tmax (a
//    shadow ray ending on a surface);
//  - same triangle: both hit the same primitive, at distances differing beyond
//    the tolerance (t accuracy, e.g. needle triangles);
//  - other: none of these (a hit on an analytic shape, which both backends
//    test with the same routine, lands here: a traversal difference).
enum class Cause : uint8_t { Vertex, Edge, Grazing, RayStart, RayEnd, SameTriangle, Other };
inline constexpr int kCauses = 7;
inline constexpr double kBoundary = 1e-5;
const char* cause_name(Cause c);

struct CrossCheckCounts {
  std::size_t rays = 0, agree = 0, tie = 0, hit_miss = 0, distance = 0;
  std::array<std::size_t, kCauses> cause{};  // of the disagreements (hit_miss + distance)
  // Agreeing hits (same primitive, within the tolerance): how many distances
  // differ at all, and the largest relative difference.
  std::size_t hits_compared = 0, t_differs = 0;
  double max_relative_t = 0;
  std::size_t disagreements() const { return hit_miss + distance; }
  double rate() const { return rays ? static_cast<double>(disagreements()) / static_cast<double>(rays) : 0.0; }
};

struct CrossCheck {
  float tolerance = 1e-4f;
  CrossCheckCounts camera, shadow, diffuse;
  // Per pixel, the worst verdict over its rays (HitMiss > Distance > Tie > Agree).
  std::vector<Verdict> pixel;
  int width = 0, height = 0;
  std::size_t rays() const { return camera.rays + shadow.rays + diffuse.rays; }
  std::size_t disagreements() const {
    return camera.disagreements() + shadow.disagreements() + diffuse.disagreements();
  }
  double rate() const { return rays() ? static_cast<double>(disagreements()) / static_cast<double>(rays()) : 0.0; }
  std::size_t cause(Cause c) const {
    const auto i = static_cast<std::size_t>(c);
    return camera.cause[i] + shadow.cause[i] + diffuse.cause[i];
  }
};

CrossCheck cross_check(const Accelerator& a, const Accelerator& b, const SceneGeometry& geometry, const RaySets& rays,
                       WorkerPool& pool, float tolerance = 1e-4f);

// 1234567 as "1,234,567".
std::string thousands(std::size_t n);

// "0.0012% (12 of 1,000,000 rays: 10 vertex, 2 edge)".
std::string describe_rate(const CrossCheck& check);

// The camera view in grey (backend a's camera hits, shaded by the angle to
// the geometric normal) with disagreeing pixels in colour: red = hit versus
// miss, yellow = distance, blue = tie.
Image disagreement_image(const CrossCheck& check, const RaySets& rays, const SceneGeometry& geometry,
                         const Accelerator& a, WorkerPool& pool);

}  // namespace pt::bench
