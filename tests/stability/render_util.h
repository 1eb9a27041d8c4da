// Test-only: the render-level catalogue entries (docs/numerical-stability.md,
// sections 8 and 9) render small scenes built in code with the path integrator,
// once per acceleration backend.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "../render/path_test_util.h"
#include "backends.h"

namespace pt::test {

inline MaterialDesc glass_material(float ior) {
  MaterialDesc m;
  m.type = MaterialType::Glass;
  m.ior = ior;
  return m;
}

inline MaterialDesc lambert_material(RGB albedo) {
  MaterialDesc m;
  m.type = MaterialType::Lambert;
  m.diffuse = albedo;
  return m;
}

// An axis-aligned box as a closed triangle mesh, outward-facing.
inline TriangleMesh box_mesh(Vec3f lo, Vec3f hi) {
  TriangleMesh m;
  for (int i = 0; i < 8; ++i)
    m.positions.emplace_back((i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z);
  // Two triangles per face, counter-clockwise seen from outside.
  const uint32_t faces[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  for (const auto& f : faces) {
    for (uint32_t i : {f[0], f[1], f[2], f[0], f[2], f[3]}) m.indices.push_back(i);
  }
  return m;
}

// A UV sphere as a closed triangle mesh.
inline TriangleMesh sphere_mesh(Vec3f centre, float radius, int rings, int segments) {
  TriangleMesh m;
  for (int i = 0; i <= rings; ++i) {
    const float theta = kPi * static_cast<float>(i) / static_cast<float>(rings);
    for (int j = 0; j < segments; ++j) {
      const float phi = 2.0f * kPi * static_cast<float>(j) / static_cast<float>(segments);
      m.positions.push_back(centre + radius * Vec3f(std::sin(theta) * std::cos(phi), std::cos(theta),
                                                    std::sin(theta) * std::sin(phi)));
    }
  }
  auto at = [&](int i, int j) { return static_cast<uint32_t>(i * segments + (j % segments)); };
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      for (uint32_t k : {at(i, j), at(i, j + 1), at(i + 1, j + 1), at(i, j), at(i + 1, j + 1), at(i + 1, j)})
        m.indices.push_back(k);
    }
  return m;
}

// Renders `d` with the path integrator and the backend named by the test
// parameter: the image and the film's non-finite report.
inline Rendered render_film_on(AccelKind kind, const SceneDescription& d, const IntegratorSettings& settings) {
  BuildOptions options;
  options.accel = kind;
  return render_film(d, "path", settings, 2, options);
}

inline Image render_on(AccelKind kind, const SceneDescription& d, const IntegratorSettings& settings) {
  return render_film_on(kind, d, settings).image;
}

inline bool all_finite(const Image& img) {
  for (const RGB& p : img.pixels)
    if (!p.is_finite()) return false;
  return true;
}

}  // namespace pt::test
