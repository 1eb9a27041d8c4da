// The study's command-line tools run as processes (docs/samplers.md,
// docs/report/README.md): pt-imgerr against hand-computed values, with and
// without --rect, and its exit codes and messages; pt-converge's checkpoints
// (a progressive prefix is the render at that spp; jittered restarts), its
// region handling and its refusal of bad input without leaving a CSV.
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "io/display.h"
#include "io/image_io.h"
#include "tool_test.h"

namespace pt {
namespace {

namespace fs = std::filesystem;

using Result = test::ToolResult;

class StudyTools : public test::ToolTest {
 protected:
  void write_exr(const std::string& name, const Image& image) const {
    std::string error;
    ASSERT_TRUE(write_image(path(name), image, DisplaySettings{}, error)) << error;
  }
  Result imgerr(const std::string& args) const { return run(PT_IMGERR_EXE, args); }
  Result converge(const std::string& args) const { return run(PT_CONVERGE_EXE, args); }
};

// Reference: every channel 0.5. Test: (0,0) red +0.25, (1,0) green -0.25,
// (0,1) equal, (1,1) red 2.0 (clamped to 1 for MSE, not for relMSE).
// Squared differences summed per pixel: 0.0625, 0.0625, 0, 0.25 (clamped; 2.25 unclamped).
void make_pair(Image& test, Image& reference) {
  reference = Image(2, 2);
  for (RGB& p : reference.pixels) p = RGB(0.5f);
  test = reference;
  test.at(0, 0) = RGB(0.75f, 0.5f, 0.5f);
  test.at(1, 0) = RGB(0.5f, 0.25f, 0.5f);
  test.at(1, 1) = RGB(2.0f, 0.5f, 0.5f);
}

double field(const std::string& text, const std::string& name) {
  std::istringstream in(text);
  std::string key;
  double value = 0;
  while (in >> key >> value)
    if (key == name) return value;
  ADD_FAILURE() << "no " << name << " in: " << text;
  return NAN;
}

TEST_F(StudyTools, ImgerrPrintsHandComputedErrors) {
  Image test, reference;
  make_pair(test, reference);
  write_exr("test.exr", test);
  write_exr("ref.exr", reference);
  // Whole frame: MSE = (0.0625 + 0.0625 + 0 + 0.25) / 4; relMSE = sum (t-r)^2 / (0.25 + 0.01) / 3 / 4.
  Result r = imgerr("test.exr ref.exr");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NEAR(field(r.out, "mse"), 0.09375, 1e-9);
  EXPECT_NEAR(field(r.out, "rmse"), std::sqrt(0.09375), 1e-9);
  EXPECT_NEAR(field(r.out, "rel_mse"), (0.0625 + 0.0625 + 2.25) / 0.26 / 3 / 4, 1e-7);
  EXPECT_EQ(field(r.out, "pixels"), 4);
  // The top row only, and the bottom-right pixel only (in JSON).
  r = imgerr("test.exr ref.exr --rect 0,0,2,1");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NEAR(field(r.out, "mse"), 0.0625, 1e-9);
  EXPECT_EQ(field(r.out, "pixels"), 2);
  r = imgerr("test.exr ref.exr --rect 1,1,1,1 --json");
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_NEAR(j["mse"].get<double>(), 0.25, 1e-9);
  EXPECT_NEAR(j["rel_mse"].get<double>(), 2.25 / 0.26 / 3, 1e-7);
  EXPECT_EQ(j["pixels"].get<int>(), 1);
  EXPECT_EQ(j["rect"], nlohmann::json({1, 1, 1, 1}));
  // Symmetric in MSE, not in relMSE (relative to the reference).
  r = imgerr("ref.exr test.exr");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NEAR(field(r.out, "mse"), 0.09375, 1e-9);
  EXPECT_GT(std::abs(field(r.out, "rel_mse") - (0.0625 + 0.0625 + 2.25) / 0.26 / 12), 0.01);
}

TEST_F(StudyTools, ImgerrRefusesBadInputWithAMessage) {
  Image test, reference;
  make_pair(test, reference);
  write_exr("test.exr", test);
  write_exr("ref.exr", reference);
  write_exr("big.exr", Image(3, 2));
  std::ofstream(path("garbage.exr")) << "not an image";
  // Bad arguments: exit 2.
  Result r = imgerr("test.exr");
  EXPECT_EQ(r.status, 2);
  r = imgerr("test.exr ref.exr --rect 1,2,3");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("--rect 1,2,3"), std::string::npos) << r.err;
  r = imgerr("test.exr ref.exr --rect 0,0,0,1");
  EXPECT_EQ(r.status, 2);
  // Bad input: exit 1, the file named.
  r = imgerr("missing.exr ref.exr");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("missing.exr"), std::string::npos) << r.err;
  r = imgerr("test.exr garbage.exr");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("garbage.exr"), std::string::npos) << r.err;
  r = imgerr("big.exr ref.exr");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("big.exr"), std::string::npos) << r.err;
  r = imgerr("test.exr ref.exr --rect 1,1,2,1");  // not inside the 2x2 image
  EXPECT_EQ(r.status, 1);
  EXPECT_FALSE(r.err.empty());
  EXPECT_TRUE(r.out.empty()) << r.out;
}

// CSV rows as (spp -> mse) for one seed.
std::vector<std::pair<int, double>> csv_rows(const std::string& text) {
  std::vector<std::pair<int, double>> rows;
  std::istringstream in(text);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "scene,accel,sampler,seed,spp,seconds,mse,rel_mse,rmse");
  while (std::getline(in, line)) {
    std::vector<std::string> f;
    std::stringstream ss(line);
    for (std::string item; std::getline(ss, item, ',');) f.push_back(item);
    EXPECT_EQ(f.size(), 9u) << line;
    if (f.size() != 9) continue;
    rows.push_back({std::stoi(f[4]), std::stod(f[6])});
    EXPECT_GE(std::stod(f[5]), 0.0) << line;
    EXPECT_NEAR(std::stod(f[8]), std::sqrt(std::stod(f[6])), 1e-6 * std::sqrt(std::stod(f[6])) + 1e-12);
  }
  return rows;
}

const std::string kScene = std::string(PT_STUDY_SCENES_DIR) + "/aa-edges.json";

// A black 32x32 reference: the error is the image's own mean squared value.
TEST_F(StudyTools, ConvergeCheckpointsArePrefixesOrRestarts) {
  write_exr("black.exr", Image(32, 32));
  for (const char* sampler : {"random", "sobol", "jittered"}) {
    const std::string common = "'" + kScene + "' --reference black.exr --threads 2 --seeds 3 --sampler " + sampler;
    Result r = converge(common + " --checkpoints 2,5,8 --csv steps.csv");
    ASSERT_EQ(r.status, 0) << r.err;
    r = converge(common + " --checkpoints 8 --csv once.csv");
    ASSERT_EQ(r.status, 0) << r.err;
    const auto steps = csv_rows(slurp(path("steps.csv")));
    const auto once = csv_rows(slurp(path("once.csv")));
    ASSERT_EQ(steps.size(), 3u);
    ASSERT_EQ(once.size(), 1u);
    EXPECT_EQ(steps[0].first, 2);
    EXPECT_EQ(steps[2].first, 8);
    // Samples [0, 8) rendered in passes (or, for jittered, a render of its own)
    // are the 8-spp render: only the summation order of a pixel can differ.
    EXPECT_NEAR(steps[2].second, once[0].second, 1e-6 * once[0].second) << sampler;
    // And not the 2-spp one: the checkpoints really differ.
    EXPECT_NE(steps[0].second, steps[2].second) << sampler;
  }
}

TEST_F(StudyTools, ConvergeMeasuresTheRectangle) {
  write_exr("black.exr", Image(32, 32));
  // The top-left corner of aa-edges sees only the background (0.05 in every
  // channel, direct emission with a box filter): MSE = 3 * 0.05^2 exactly.
  const Result r = converge("'" + kScene + "' --reference black.exr --checkpoints 4 --rect 0,0,3,3 --csv c.csv");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto rows = csv_rows(slurp(path("c.csv")));
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_NEAR(rows[0].second, 3 * 0.05 * 0.05, 1e-7);
}

TEST_F(StudyTools, ConvergeRefusesBadInputWithoutWritingACsv) {
  write_exr("black.exr", Image(32, 32));
  write_exr("small.exr", Image(16, 16));
  const std::string scene = "'" + kScene + "'";
  Result r = converge(scene + " --reference black.exr --checkpoints 8,4 --csv c.csv");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("increasing"), std::string::npos) << r.err;
  r = converge(scene + " --reference black.exr --checkpoints 4,x --csv c.csv");
  EXPECT_EQ(r.status, 2);
  r = converge(scene + " --reference black.exr --checkpoints 4 --sampler halton --csv c.csv");
  EXPECT_EQ(r.status, 2);
  r = converge(scene + " --reference missing.exr --checkpoints 4 --csv c.csv");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("missing.exr"), std::string::npos) << r.err;
  r = converge(scene + " --reference small.exr --checkpoints 4 --csv c.csv");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("16x16"), std::string::npos) << r.err;
  r = converge(scene + " --reference black.exr --checkpoints 4 --rect 30,30,4,4 --csv c.csv");
  EXPECT_EQ(r.status, 1);
  r = converge("nowhere.json --reference black.exr --checkpoints 4 --csv c.csv");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("nowhere.json"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(path("c.csv")));
}

}  // namespace
}  // namespace pt
