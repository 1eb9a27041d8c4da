// Helpers shared by the scene tests.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <variant>

#include "scene/loader.h"

namespace pt::test {

inline ::testing::AssertionResult near(Vec3f a, Vec3f b, float eps = 1e-5f) {
  if (std::fabs(a.x - b.x) <= eps && std::fabs(a.y - b.y) <= eps && std::fabs(a.z - b.z) <= eps)
    return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "(" << a.x << ", " << a.y << ", " << a.z << ") != (" << b.x << ", "
                                       << b.y << ", " << b.z << ")";
}

inline ::testing::AssertionResult near(RGB a, RGB b, float eps = 1e-5f) {
  return near(Vec3f(a.r, a.g, a.b), Vec3f(b.r, b.g, b.b), eps);
}

template <class T>
const T& geometry_of(const SceneDescription& scene, std::size_t i) {
  EXPECT_LT(i, scene.shapes.size());
  EXPECT_TRUE(std::holds_alternative<T>(scene.shapes[i].geometry)) << "shape " << i;
  return std::get<T>(scene.shapes[i].geometry);
}

inline const PointLightDesc& point_light(const SceneDescription& scene, std::size_t i) {
  EXPECT_LT(i, scene.lights.size());
  return std::get<PointLightDesc>(scene.lights[i]);
}

// The folder of the shared seed scenes, or "" (the caller skips) if absent.
inline std::string seed_dir() {
  const std::string dir = std::string(PT_SHARED_DIR) + "/seed-scenes";
  std::error_code ec;
  return std::filesystem::is_directory(dir, ec) ? dir : std::string();
}

}  // namespace pt::test
