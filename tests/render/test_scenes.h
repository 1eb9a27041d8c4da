// Small scenes built in code for the render tests (no scene files involved).
#pragma once

#include <memory>
#include <string>

#include <gtest/gtest.h>

#include "core/diagnostics.h"
#include "core/parallel.h"
#include "render/render_scene.h"
#include "scene/scene_description.h"

namespace pt::test {

inline MaterialDesc diffuse_material(RGB colour, float kd = 1.0f) {
  MaterialDesc m;
  m.kd = kd;
  m.ks = 0.0f;
  m.diffuse = colour;
  return m;
}

inline MaterialDesc emitter_material(RGB emission) {
  MaterialDesc m;
  m.kd = 0.0f;
  m.ks = 0.0f;
  m.emission = emission;
  return m;
}

// A description with a camera, no shapes, no lights and a black background.
inline SceneDescription empty_scene(int width, int height, Vec3f eye, Vec3f target, Vec3f up, float fov = 40.0f) {
  SceneDescription d;
  d.film.width = width;
  d.film.height = height;
  d.camera.position = eye;
  d.camera.look_at = target;
  d.camera.up = up;
  d.camera.fov_y_deg = fov;
  d.render.background = RGB(0, 0, 0);
  return d;
}

inline int add_material(SceneDescription& d, const MaterialDesc& m) {
  d.materials.push_back(m);
  return static_cast<int>(d.materials.size()) - 1;
}

inline void add_shape(SceneDescription& d, Shape g, int material) {
  ShapeDesc s;
  s.geometry = std::move(g);
  s.material = material;
  d.shapes.push_back(std::move(s));
}

inline void add_sphere(SceneDescription& d, Vec3f centre, float radius, int material) {
  Sphere s;
  s.center = centre;
  s.radius = radius;
  add_shape(d, s, material);
}

// Axis-aligned square in the plane z = height, corners counter-clockwise seen from +z.
inline void add_z_square(SceneDescription& d, float height, float half, int material) {
  Quad q;
  q.v[0] = Vec3f(-half, -half, height);
  q.v[1] = Vec3f(half, -half, height);
  q.v[2] = Vec3f(half, half, height);
  q.v[3] = Vec3f(-half, half, height);
  add_shape(d, q, material);
}

inline void add_point_light(SceneDescription& d, Vec3f position, RGB intensity, RGB specular_intensity,
                            bool inverse_square = true) {
  PointLightDesc l;
  l.inverse_square = inverse_square;
  l.position = position;
  l.intensity = intensity;
  l.specular_intensity = specular_intensity;
  d.lights.emplace_back(l);
}

// Builds with Embree; fails the current test (and returns nullptr) on any error.
inline std::unique_ptr<RenderScene> build(const SceneDescription& d, WorkerPool& pool,
                                          const BuildOptions& options = {}) {
  Diagnostics diag;
  auto scene = build_render_scene(d, options, pool, diag);
  EXPECT_TRUE(scene != nullptr) << diag.format();
  EXPECT_FALSE(diag.has_errors()) << diag.format();
  return scene;
}

}  // namespace pt::test
