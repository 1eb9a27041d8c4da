// The run record's JSON (io/run_record.h, docs/cli.md): the non-finite report
// with and without a first offender, and the request's outputs, crop, AOV
// types, pass size, checkpoint files, display settings and phase timings.
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "io/run_record.h"

namespace pt {
namespace {

nlohmann::json parse(const RunRecord& record) { return nlohmann::json::parse(run_record_json(record)); }

TEST(RunRecordJson, NonFiniteWithoutAFirstOffenderIsNull) {
  RunRecord r;
  r.non_finite.x = 3;  // ignored without has_first
  const nlohmann::json j = parse(r);
  ASSERT_TRUE(j.contains("non_finite"));
  EXPECT_EQ(j["non_finite"]["nan"], 0);
  EXPECT_EQ(j["non_finite"]["pos_inf"], 0);
  EXPECT_EQ(j["non_finite"]["neg_inf"], 0);
  ASSERT_TRUE(j["non_finite"].contains("first"));
  EXPECT_TRUE(j["non_finite"]["first"].is_null()) << j["non_finite"];
}

TEST(RunRecordJson, NonFiniteCountsAndFirstOffender) {
  RunRecord r;
  r.non_finite = {5, 2, 1, true, 7, 11, 42};
  r.non_finite.nan = uint64_t{1} << 40;  // 64-bit counts survive
  const nlohmann::json nf = parse(r)["non_finite"];
  EXPECT_EQ(nf["nan"].get<uint64_t>(), uint64_t{1} << 40);
  EXPECT_EQ(nf["pos_inf"], 2);
  EXPECT_EQ(nf["neg_inf"], 1);
  ASSERT_TRUE(nf["first"].is_object()) << nf;
  EXPECT_EQ(nf["first"], (nlohmann::json{{"x", 7}, {"y", 11}, {"sample", 42}}));
}

TEST(RunRecordJson, RequestOutputsCheckpointsAndDisplay) {
  RunRecord r;
  r.outputs = {"a.exr", "a.png"};
  r.crop = {8, 4, 20, 16};
  r.beauty_type = "half";
  r.aovs = {{"albedo", "half"}, {"Z", "float"}};
  r.pass_spp = 16;
  r.checkpoint = "a.ckpt";
  r.checkpoint_every = 30;
  r.display = {"srgb", 1.5f, "Raw", "sRGB", "+grade", "/x/config.ocio", "OCIO config ..."};
  nlohmann::json j = parse(r);
  EXPECT_EQ(j["output"]["files"], (nlohmann::json{"a.exr", "a.png"}));
  EXPECT_EQ(j["output"]["crop"], (nlohmann::json{{"x", 8}, {"y", 4}, {"width", 20}, {"height", 16}}));
  EXPECT_EQ(j["output"]["beauty_type"], "half");
  EXPECT_EQ(j["output"]["aovs"], nlohmann::json::parse(R"([{"name": "albedo", "type": "half"},
                                                           {"name": "Z", "type": "float"}])"));
  EXPECT_EQ(j["progress"]["pass_spp"], 16);
  EXPECT_EQ(j["checkpoint"]["file"], "a.ckpt");
  EXPECT_EQ(j["checkpoint"]["every_seconds"], 30.0);
  EXPECT_TRUE(j["checkpoint"]["resumed_from"].is_null());
  EXPECT_EQ(j["display"], nlohmann::json::parse(R"({"transform": "srgb", "exposure": 1.5, "view": "Raw",
      "display": "sRGB", "look": "+grade", "ocio_config": "/x/config.ocio", "pipeline": "OCIO config ..."})"));
  // Adaptive passes (a time budget) have no size; no files: null; no AOVs: an empty list.
  r = RunRecord{};
  r.resumed_from = "b.ckpt";
  j = parse(r);
  EXPECT_EQ(j["progress"]["pass_spp"], "adaptive");
  EXPECT_TRUE(j["checkpoint"]["file"].is_null());
  EXPECT_EQ(j["checkpoint"]["resumed_from"], "b.ckpt");
  EXPECT_TRUE(j["display"]["ocio_config"].is_null());
  EXPECT_EQ(j["output"]["aovs"], nlohmann::json::array());
  EXPECT_EQ(j["output"]["beauty_type"], "float");
}

TEST(RunRecordJson, PhaseTimingsIncludeMeshAndTextureLoading) {
  RunRecord r;
  r.timings = {0.5, 0.25, 0.125, 1.0, 2.0, 4.0, 8.0, 15.875};
  EXPECT_EQ(parse(r)["timings"], nlohmann::json::parse(R"({"parse": 0.5, "mesh_load": 0.25, "texture_load": 0.125,
      "scene_build": 1.0, "accel_build": 2.0, "render": 4.0, "write": 8.0, "total": 15.875})"));
  const std::string text = run_record_json(r);
  EXPECT_LT(text.find("\"parse\""), text.find("\"mesh_load\""));  // the phases in order
  EXPECT_LT(text.find("\"mesh_load\""), text.find("\"texture_load\""));
  EXPECT_LT(text.find("\"texture_load\""), text.find("\"scene_build\""));
}

}  // namespace
}  // namespace pt
