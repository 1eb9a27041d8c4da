// bench_render (tools/bench/render, docs/performance.md) run as a process on a
// small scene: the benchmark must measure what the product renders. `compare`
// at the pathtracer's own seed and spp finds no error at all, with both
// backends; `time-to-error` stops at the first pass whose error is under the
// targets and reports that pass's error; `profile` counts the rays of a
// direct-light render exactly (a camera ray, a shadow ray and a BSDF ray per
// sample of a scene every pixel of which sees a lit surface). Timings are not
// checked beyond being present: no test measures time.
#include <cmath>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tool_test.h"

namespace pt {
namespace {

using json = nlohmann::json;

const std::string kScene = std::string(PT_STUDY_SCENES_DIR) + "/soft-shadow.json";  // 32x32, max_depth 1

class BenchRender : public test::ToolTest {
 protected:
  // The pathtracer's own render of kScene, as the reference.
  void render_reference(int spp, int seed) const {
    const test::ToolResult r = run(PT_PATHTRACER_EXE, "'" + kScene + "' -o ref.exr --quiet --spp " + std::to_string(spp) +
                                                   " --seed " + std::to_string(seed));
    ASSERT_EQ(r.status, 0) << r.err;
  }
  json bench(const std::string& args) const {
    const test::ToolResult r = run(PT_BENCH_RENDER_EXE, args);
    EXPECT_EQ(r.status, 0) << r.err;
    try {
      return json::parse(r.out);
    } catch (const json::exception& e) {
      ADD_FAILURE() << e.what() << "\n" << r.out;
      return json::array();
    }
  }
};

TEST_F(BenchRender, CompareRendersExactlyWhatTheApplicationRenders) {
  render_reference(16, 5);
  const json same = bench("compare '" + kScene + "' --reference ref.exr --accel embree bvh --spp 16 --seed 5");
  ASSERT_EQ(same.size(), 2u);
  for (const json& m : same) {
    EXPECT_EQ(m.at("spp").get<int>(), 16);
    EXPECT_LE(m.at("rmse").get<double>(), 1e-7) << m.at("accel");
    for (const json& ratio : m.at("mean_ratio")) EXPECT_NEAR(ratio.get<double>(), 1.0, 1e-6);
  }
  // Another seed: the same image up to noise, so an error that is small but not zero.
  const json other = bench("compare '" + kScene + "' --reference ref.exr --accel bvh --spp 16 --seed 6");
  ASSERT_EQ(other.size(), 1u);
  EXPECT_GT(other[0].at("rmse").get<double>(), 1e-4);
  EXPECT_LT(other[0].at("rmse").get<double>(), 0.1);
}

TEST_F(BenchRender, TimeToErrorStopsAtTheFirstPassUnderBothTargets) {
  render_reference(256, 9);
  const double target_rmse = 0.01, target_relmse = 0.002;
  const json runs = bench("time-to-error '" + kScene + "' --reference ref.exr --accel bvh --runs 2 --pass-spp 4 --rmse " +
                          std::to_string(target_rmse) + " --relmse " + std::to_string(target_relmse) +
                          " --max-seconds 60");
  ASSERT_EQ(runs.size(), 1u);
  ASSERT_EQ(runs[0].at("runs").size(), 2u);
  for (const json& run : runs[0].at("runs")) {
    const json& trace = run.at("trace_spp_seconds_rmse_relmse");
    ASSERT_FALSE(trace.empty());
    const int spp_rmse = run.at("spp_to_rmse").get<int>(), spp_relmse = run.at("spp_to_relmse").get<int>();
    EXPECT_EQ(spp_rmse % 4, 0);
    EXPECT_EQ(spp_relmse % 4, 0);
    double previous_seconds = 0.0;
    for (const json& row : trace) {
      const int spp = row[0].get<int>();
      const double seconds = row[1].get<double>(), rmse = row[2].get<double>(), relmse = row[3].get<double>();
      EXPECT_GT(seconds, previous_seconds);  // cumulative render time
      previous_seconds = seconds;
      // Above each target before the pass that reached it, under it at that pass.
      if (spp < spp_rmse) {
        EXPECT_GE(rmse, target_rmse) << "spp " << spp;
      } else if (spp == spp_rmse) {
        EXPECT_LT(rmse, target_rmse);
      }
      if (spp < spp_relmse) {
        EXPECT_GE(relmse, target_relmse) << "spp " << spp;
      } else if (spp == spp_relmse) {
        EXPECT_LT(relmse, target_relmse);
      }
    }
  }
}

TEST_F(BenchRender, ProfileCountsTheRaysOfADirectLightRender) {
  const json p = bench("profile '" + kScene + "' --accel embree bvh --spp 4 --runs 1");
  ASSERT_EQ(p.size(), 2u);
  for (const json& m : p) {
    // Every pixel of the soft-shadow scene sees the floor, lit by one area light:
    // per sample a camera ray, one shadow ray (next-event estimation) and one
    // BSDF ray (max_depth 1, looking for the emitter), whatever the backend.
    EXPECT_EQ(m.at("rays").get<int>(), 32 * 32 * 4 * 3) << m.at("accel");
    EXPECT_EQ(m.at("shadow_rays").get<int>(), 32 * 32 * 4);
    // The share is a ratio of two timings: only its presence is checked (no test measures time).
    EXPECT_GT(m.at("median_traversal_share").get<double>(), 0.0);
  }
}

}  // namespace
}  // namespace pt
