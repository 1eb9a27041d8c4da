// An area light: a shape whose material emits. Every shape type can emit:
//  - spheres are sampled by solid angle (uniformly inside the cone they
//    subtend) from points outside them, and by area from inside;
//  - quads, triangles, meshes and cylinders are sampled uniformly by area
//    (a mesh picks a triangle in proportion to its area, a quad one of its two
//    triangles, a cylinder its side or a cap), so the area density is 1 / A.
// Emission is one-sided (the side of the shape's geometric normal) unless the
// material is two-sided; see Material::emitted.
#pragma once

#include <cstdint>
#include <vector>

#include "core/sampling.h"
#include "geometry/shapes.h"
#include "render/lights/light.h"
#include "render/materials/material.h"

namespace pt {

class ShapeLight {
 public:
  ShapeLight(const Shape& shape, uint32_t shape_id, const Material& material);

  uint32_t shape_id() const { return shape_id_; }
  float area() const { return area_; }
  // Samples a point of the light as seen from p; false if nothing can be sampled.
  bool sample(Vec3f p, Vec2f u, LightSample& s) const;
  // The solid-angle density with which sample(p, ...) produces direction wi
  // reaching the light at point q with geometric normal n.
  float pdf(Vec3f p, Vec3f wi, Vec3f q, Vec3f n) const;
  float power() const;

 private:
  // A point uniformly distributed by area (the density is 1 / area_).
  void sample_area(Vec2f u, Vec3f& q, Vec3f& n) const;
  bool sample_sphere_cone(const Sphere& s, Vec3f p, Vec2f u, LightSample& out) const;

  // A triangle ready to sample: a corner, its two edges and the unit normal.
  struct Triangle {
    Vec3f p0, e1, e2, n;
  };

  const Shape* shape_;
  uint32_t shape_id_;
  const Material* material_;
  float area_ = 0.0f;
  Distribution1D parts_;  // meshes: triangles by area; quads: the two triangles; cylinders: side, caps
  std::vector<Triangle> triangles_;  // meshes and quads
};

}  // namespace pt
