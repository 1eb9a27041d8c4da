// Test-only: runs a test once per acceleration backend (pt::accel_kind_names()).
// A backend that reports that it is not available yet is skipped with its own
// message; one that appears later is covered with no change here.
//
//   TEST_P(MySuite, Case) {
//     std::unique_ptr<Accelerator> accel;
//     build(geometry, pool, accel);
//     if (!accel) return;  // skipped (not available) or failed (reported)
//     ...
//   }
//   INSTANTIATE_TEST_SUITE_P(Backends, MySuite, ::testing::ValuesIn(accel_kind_names()),
//                            test::backend_test_name);
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <memory>
#include <string>

#include "accel/accelerator.h"
#include "core/diagnostics.h"
#include "core/parallel.h"
#include "geometry/shapes.h"

namespace pt::test {

class PerBackend : public ::testing::TestWithParam<std::string> {
 public:
  AccelKind kind() const {
    AccelKind k{};
    EXPECT_TRUE(parse_accel_kind(GetParam(), k)) << GetParam();
    return k;
  }

  // Whether the backend tests triangles with Embree's own (Plücker) test rather
  // than ours (src/geometry/triangle.cpp). Its guarantees are weaker in two
  // cases, stated per backend in docs/numerical-stability.md: rays aimed
  // exactly at a shared vertex can pass between the triangles (case 1), and the
  // t of a needle triangle's hit is approximate, its barycentrics are not (case 4).
  bool embree_triangles() const { return kind() == AccelKind::Embree; }

 protected:
  // Builds the backend named by the test parameter into `out`. Leaves it null
  // after GTEST_SKIP (the backend says it is not available) or a failure.
  void build(const SceneGeometry& geometry, WorkerPool& pool, std::unique_ptr<Accelerator>& out) {
    Diagnostics diag;
    out = build_accelerator(kind(), geometry, pool, diag);
    if (out) {
      EXPECT_FALSE(diag.has_errors()) << diag.format();
      return;
    }
    const std::string report = diag.format();
    if (report.find("not available") != std::string::npos) GTEST_SKIP() << report;
    FAIL() << GetParam() << " failed to build:\n" << report;
  }
};

inline std::string backend_test_name(const ::testing::TestParamInfo<std::string>& info) {
  std::string n = info.param;
  std::replace_if(n.begin(), n.end(), [](char c) { return !std::isalnum(static_cast<unsigned char>(c)); }, '_');
  return n;
}

}  // namespace pt::test
