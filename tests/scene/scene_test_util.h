// Helpers shared by the scene tests.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
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

// A fresh folder under the system's temporary directory, removed afterwards.
class TempDir {
 public:
  TempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = std::filesystem::temp_directory_path() /
            ("pt-scene-" + std::to_string(::getpid()) + "-" + info->test_suite_name() + "-" + info->name());
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  std::string write(const std::string& relative, const std::string& text) const {
    const std::filesystem::path p = path_ / relative;
    std::filesystem::create_directories(p.parent_path());
    std::ofstream(p, std::ios::binary) << text;
    return p.string();
  }
  std::string str() const { return path_.string(); }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

// Changes the working directory for the lifetime of the object.
class ScopedCwd {
 public:
  explicit ScopedCwd(const std::filesystem::path& dir) : old_(std::filesystem::current_path()) { std::filesystem::current_path(dir); }
  ~ScopedCwd() { std::filesystem::current_path(old_); }

 private:
  std::filesystem::path old_;
};

}  // namespace pt::test
