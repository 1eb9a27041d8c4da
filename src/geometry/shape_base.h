// What every shape's definition (geometry/shapes/*.h) builds on: the hit
// record its intersect() fills, the surface record its surface() returns, the
// sink its validation rule reports to, and the by-area sampler that quads and
// meshes share.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/diagnostics.h"
#include "core/math.h"
#include "core/sampling.h"

namespace pt {

struct PrimHit {
  float t = kInfinity;
  // Shape-specific parameters:
  //  triangle: barycentrics (b1, b2) of p1 and p2;
  //  quad:     (u, v) of the two-triangle parameterisation (u >= v: triangle
  //            v0 v1 v2, else v0 v2 v3; equals the bilinear (u, v) for parallelograms);
  //  cylinder: (part, 0), part 0 = side, 1 = cap at p0, 2 = cap at p1;
  //  cone:     (part, 0) as the cylinder's (the apex counts as side);
//  sphere, disc, polygon, plane: unused (0, 0); surface() reprojects ray.at(t).
  Vec2f uv;
};

struct TriangleMesh;
struct Transform;

// Where a hit lies on a mesh whose vertex normals imply a smooth surface: what
// the shadow-terminator offset of the rays leaving it needs (geometry/terminator.h,
// docs/rendering.md "Shadow terminator"). `mesh` is null everywhere else.
struct SmoothSurface {
  const TriangleMesh* mesh = nullptr;
  const Transform* to_world = nullptr;  // an instance's transform; null for a mesh placed directly
  uint32_t tri = 0;
  Vec2f b;              // the hit's barycentrics (b1, b2)
  float cutoff = 0.0f;  // render.shadow_terminator_geometry_offset (> 0 where mesh is set)
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
  // Where and over how much textures are looked up (render/textures/tex_coord.h),
  // set by RenderScene::intersect in a scene with textures: the change of uv
  // and of the object-space position across one pixel in x and y of the
  // image, and that position (the shape's own space; p for a shape placed
  // directly). Zero otherwise, and from surface(): a point lookup.
  Vec2f duvdx, duvdy;
  Vec3f p_object, dpdx, dpdy;
  // Set by RenderScene::intersect on meshes with normals when the shadow
  // terminator offset is on; surface() leaves it empty (rays leave p itself).
  SmoothSurface smooth;
};

// The derivatives of position with respect to the texture coordinates at a
// surface point (the tangent frame of normal and bump maps; the shape's
// uv_derivatives routine). Either may be zero where the parameterisation is
// degenerate (a sphere's poles, the constant v of a cap).
struct UvDerivatives {
  Vec3f dpdu, dpdv;
};

// ---------------------------------------------------------------- validation
// Where a shape's validation rule, check(const S&, ShapeChecker&), reports what
// is wrong with its values. `field` names the scene file's key the problem is
// about ("radius"), or is empty for the shape as a whole; src/scene/validate.cpp
// turns it into the key's file:line:col.
// An `unusable` problem (an error) is one the later stages assume away: the
// accelerators, intersection and area sampling rely on its absence (mesh
// indices in range, finite values), so build_render_scene() refuses it even in
// a description built in code (src/scene/validate.h).
struct ShapeProblem {
  std::string field;
  std::string message;
  bool warning = false;
  bool unusable = false;
};

class ShapeChecker {
 public:
  // `type`: the shape's type name in the scene file ("triangle"), if any;
  // `file`: the file the shape's data was read from ("bunny.ply"), if any.
  explicit ShapeChecker(std::string type = {}, std::string file = {})
      : type_(std::move(type)), file_(std::move(file)) {}
  const std::string& type() const { return type_; }
  const std::string& file() const { return file_; }
  void error(std::string field, std::string message) { problems_.push_back({std::move(field), std::move(message), false}); }
  void warning(std::string field, std::string message) { problems_.push_back({std::move(field), std::move(message), true}); }
  void unusable(std::string field, std::string message) {
    problems_.push_back({std::move(field), std::move(message), false, true});
  }
  bool usable() const {
    return std::none_of(problems_.begin(), problems_.end(), [](const ShapeProblem& p) { return p.unusable; });
  }
  const std::vector<ShapeProblem>& problems() const { return problems_; }

 private:
  std::string type_;
  std::string file_;
  std::vector<ShapeProblem> problems_;
};

// ---------------------------------------------------------------- area sampling
// A shape's by-area sampler (make_area_sampler(shape)) has `float area` and
// `void sample(Vec2f u, Vec3f& q, Vec3f& n) const`: a point q uniformly
// distributed by area (density 1 / area) and the unit normal there.

// Picks a part of a shape made of parts (density in proportion to their
// areas) with u.x, and returns u with u.x rescaled to [0, 1) inside the part.
inline Vec2f pick_part(const Distribution1D& parts, Vec2f u, std::size_t& part) {
  float pmf = 0.0f;
  part = 0;
  const float x = parts.sample_continuous(u.x, &pmf, &part);
  // The position of u.x inside its cell, back in [0, 1).
  const float n_parts = static_cast<float>(parts.size());
  return Vec2f(std::min(x * n_parts - static_cast<float>(part), kOneMinusEpsilon), u.y);
}

// Triangles (quads, meshes) sampled by area: a triangle in proportion to its
// area, then a uniform point in it.
struct TriangleAreaSampler {
  // A triangle ready to sample: a corner, its two edges and the unit normal.
  struct Triangle {
    Vec3f p0, e1, e2, n;
  };
  std::vector<Triangle> triangles;
  Distribution1D parts;  // the triangles by area
  float area = 0.0f;

  void sample(Vec2f u, Vec3f& q, Vec3f& n) const { sample(parts, u, q, n); }
  // The same with the triangles picked by another distribution over them (an
  // instance's, by their areas under its transform); `part`, if given, is set
  // to the triangle's index (a mesh's primitive).
  void sample(const Distribution1D& by, Vec2f u, Vec3f& q, Vec3f& n, std::size_t* part_out = nullptr) const {
    std::size_t part = 0;
    const Vec2f v = pick_part(by, u, part);
    if (part_out != nullptr) *part_out = part;
    const Triangle& t = triangles[part];
    const Vec3f b = sample_uniform_triangle(v);
    q = t.p0 + t.e1 * b.y + t.e2 * b.z;
    n = t.n;
  }
};

}  // namespace pt
