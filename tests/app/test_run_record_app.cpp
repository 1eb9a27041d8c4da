// The run record as the application fills it (docs/cli.md): the non-finite
// report (and that its first offender replays), mesh and texture loading as
// phases of their own, and the request: outputs, crop, AOV types, pass size,
// checkpoint and resume files, display settings.
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include "app_fixture.h"

namespace pt::test {
namespace {

class RunRecordApp : public AppTest {};

TEST_F(RunRecordApp, NonFiniteCountsAndTheFirstOffenderWhichReplays) {
  write("nf.json", backdrop_scene("inf.exr", 16, 12, 4));
  write_image("inf.exr", 4, 4, std::numeric_limits<float>::infinity());
  const RunResult r = run("nf.json -o nf.exr --aov nonfinite --report run.json");
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json nf = read_json("run.json")["non_finite"];
  ASSERT_TRUE(nf.is_object());
  const uint64_t total = nf["nan"].get<uint64_t>() + nf["pos_inf"].get<uint64_t>() + nf["neg_inf"].get<uint64_t>();
  ASSERT_GT(total, 0u) << nf;
  EXPECT_GT(nf["pos_inf"].get<uint64_t>(), 0u) << nf;
  ASSERT_TRUE(nf["first"].is_object()) << nf;
  const int x = nf["first"]["x"], y = nf["first"]["y"], sample = nf["first"]["sample"];
  // The warning says the same ...
  const std::string said = "warning: " + std::to_string(total) + " non-finite samples (" +
                           std::to_string(nf["nan"].get<uint64_t>()) + " NaN, " +
                           std::to_string(nf["pos_inf"].get<uint64_t>()) + " +Inf, " +
                           std::to_string(nf["neg_inf"].get<uint64_t>()) + " -Inf); first at pixel (" +
                           std::to_string(x) + ", " + std::to_string(y) + ") sample " + std::to_string(sample);
  EXPECT_NE(r.err.find(said), std::string::npos) << said << "\n" << r.err;
  // ... the mask marks that pixel ...
  auto in = OIIO::ImageInput::open(path("nf.exr"));
  ASSERT_TRUE(in);
  const int c = in->spec().channelindex("nonfinite.X");
  ASSERT_GE(c, 0);
  std::vector<float> masks(16 * 12);
  ASSERT_TRUE(in->read_image(0, 0, c, c + 1, OIIO::TypeFloat, masks.data())) << in->geterror();
  EXPECT_EQ(masks[static_cast<std::size_t>(y) * 16 + x], 1.0f);
  // ... and replaying it gives the non-finite value again.
  const RunResult replay = run("nf.json --replay " + std::to_string(x) + "," + std::to_string(y) + "," +
                               std::to_string(sample));
  ASSERT_EQ(replay.status, 0) << replay.err;
  // (+Inf, or NaN where the backdrop's bilinear lookup weighs an infinite texel by 0.)
  const std::string first_line = replay.out.substr(0, replay.out.find('\n'));
  EXPECT_TRUE(first_line.find("radiance inf") != std::string::npos || first_line.find("nan") != std::string::npos)
      << replay.out;

  // A render without any: zero counts and no first offender.
  write("s.json", path_scene(16, 12, 2));
  ASSERT_EQ(run("s.json -o s.exr --report clean.json --quiet").status, 0);
  const nlohmann::json clean = read_json("clean.json")["non_finite"];
  EXPECT_EQ(clean, nlohmann::json::parse(R"({"nan": 0, "pos_inf": 0, "neg_inf": 0, "first": null})"));
}

TEST_F(RunRecordApp, MeshAndTextureLoadingArePhasesOfTheirOwn) {
  // A textured OBJ quad and a textured sphere: a mesh file and a 512 x 256 texture to read.
  write("quad.obj", "v -2 0 -2\nv 2 0 -2\nv 2 0 2\nv -2 0 2\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1 4/4 3/3 2/2\n");
  write_image("wood.exr", 512, 256, 0.5f);
  const std::string scene = R"({"format": "pathtracer-scene", "version": 1,
    "camera": {"position": [0, 1, 4], "look_at": [0, 0.5, 0], "fov": 40},
    "film": {"width": 16, "height": 12},
    "render": {"integrator": "path", "max_depth": 4, "spp": 1, "background": [1, 1, 1]},
    "materials": {"wood": {"type": "lambert", "texture": "wood.exr"}, "white": {"type": "lambert"}},
    "shapes": [{"type": "mesh", "file": "quad.obj", "material": "MESH"},
               {"type": "sphere", "center": [0, 0.5, 0], "radius": 0.5, "material": "SPHERE"}]})";
  const auto with = [&](const char* mesh, const char* sphere) {
    std::string s = scene;
    s.replace(s.find("MESH"), 4, mesh);
    s.replace(s.find("SPHERE"), 6, sphere);
    return s;
  };
  write("textured.json", with("wood", "wood"));
  write("plain.json", with("white", "white"));  // the texture is never decoded
  write("bare.json", path_scene(16, 12, 1));    // no files at all
  for (const char* name : {"textured", "plain", "bare"})
    ASSERT_EQ(run(std::string(name) + ".json -o " + name + ".exr --report " + name + ".run.json --quiet").status, 0)
        << name;
  const nlohmann::json textured = read_json("textured.run.json"), plain = read_json("plain.run.json"),
                       bare = read_json("bare.run.json");
  for (const nlohmann::json* rec : {&textured, &plain, &bare}) {
    const nlohmann::json& t = (*rec)["timings"];
    double sum = 0;
    for (const char* phase : {"parse", "mesh_load", "texture_load", "scene_build", "accel_build", "render", "write"}) {
      EXPECT_GE(t[phase].get<double>(), 0.0) << phase;
      sum += t[phase].get<double>();
    }
    EXPECT_NEAR(t["total"].get<double>(), sum, 1e-9) << t;  // the phases do not overlap
  }
  EXPECT_GT(textured["timings"]["mesh_load"].get<double>(), 0.0) << textured["timings"];
  EXPECT_GT(textured["timings"]["texture_load"].get<double>(), 0.0) << textured["timings"];
  EXPECT_GT(plain["timings"]["mesh_load"].get<double>(), 0.0) << plain["timings"];
  EXPECT_EQ(plain["timings"]["texture_load"].get<double>(), 0.0) << plain["timings"];
  EXPECT_EQ(bare["timings"]["mesh_load"].get<double>(), 0.0) << bare["timings"];
  EXPECT_EQ(bare["timings"]["texture_load"].get<double>(), 0.0) << bare["timings"];
  // The pre-flight estimate counts the texture a material uses: its MIP pyramid in the texture cache
  // (4/3 of 512 x 256 RGB at 4 bytes a channel) and its float decode buffer.
  const double texture = 512.0 * 256.0 * (16 + 12);
  // (The totals also hold the process's measured resident memory, which differs from run to run.)
  EXPECT_EQ(textured["memory"]["estimate_parts"]["textures"].get<double>() -
                plain["memory"]["estimate_parts"]["textures"].get<double>(),
            texture);
}

TEST_F(RunRecordApp, RecordsOutputsCropAovsPassesCheckpointsAndDisplay) {
  write("s.json", path_scene(32, 24, 1));
  RunResult r = run("s.json -o a.exr -o a.png --spp 4 --pass-spp 2 --crop 0.25,0.5,0.75,1 --aov Z,albedo:float "
                    "--checkpoint a.ckpt --checkpoint-every 0 --exposure 1.5 --view aces --report run.json --quiet");
  ASSERT_EQ(r.status, 0) << r.err;
  nlohmann::json rec = read_json("run.json");
  EXPECT_EQ(rec["output"]["files"], (nlohmann::json{"a.exr", "a.png"}));
  // [floor(0.25 * 32), ceil(0.75 * 32)) x [floor(0.5 * 24), 24)
  EXPECT_EQ(rec["output"]["crop"], (nlohmann::json{{"x", 8}, {"y", 12}, {"width", 16}, {"height", 12}}));
  EXPECT_EQ(rec["output"]["beauty_type"], "float");
  EXPECT_EQ(rec["output"]["aovs"], nlohmann::json::parse(R"([{"name": "albedo", "type": "float"},
                                                              {"name": "Z", "type": "float"}])"));
  EXPECT_EQ(rec["progress"]["pass_spp"], 2);
  EXPECT_EQ(rec["progress"]["passes"], 2);
  EXPECT_EQ(rec["checkpoint"]["file"], "a.ckpt");
  EXPECT_EQ(rec["checkpoint"]["every_seconds"], 0.0);
  EXPECT_TRUE(rec["checkpoint"]["resumed_from"].is_null());
  EXPECT_EQ(rec["display"]["transform"], "srgb");
  EXPECT_EQ(rec["display"]["exposure"], 1.5);
  EXPECT_EQ(rec["display"]["view"], "aces");
  EXPECT_EQ(rec["display"]["display"], "");
  EXPECT_EQ(rec["display"]["look"], "");
  EXPECT_TRUE(rec["display"]["ocio_config"].is_null());
  const std::string pipeline = rec["display"]["pipeline"];
  EXPECT_NE(pipeline.find("'aces'"), std::string::npos) << pipeline;
  EXPECT_NE(pipeline.find("exposure 1.5 stops"), std::string::npos) << pipeline;

  // Resumed to 6 spp: the checkpoint it came from; a crop given in pixels.
  r = run("s.json -o b.exr --spp 6 --pass-spp 2 --crop-px 8,12,16,12 --aov albedo:float,Z --resume a.ckpt "
          "--report resumed.json --quiet");
  ASSERT_EQ(r.status, 0) << r.err;
  rec = read_json("resumed.json");
  EXPECT_EQ(rec["checkpoint"]["resumed_from"], "a.ckpt");
  EXPECT_TRUE(rec["checkpoint"]["file"].is_null());
  EXPECT_EQ(rec["progress"]["resumed_spp"], 4);
  EXPECT_EQ(rec["output"]["crop"], (nlohmann::json{{"x", 8}, {"y", 12}, {"width", 16}, {"height", 12}}));

  // Without a crop, the whole frame; under a time budget alone the passes adapt.
  ASSERT_EQ(run("s.json -o c.exr --time-budget 0.2 --report budget.json --quiet").status, 0);
  rec = read_json("budget.json");
  EXPECT_EQ(rec["output"]["crop"], (nlohmann::json{{"x", 0}, {"y", 0}, {"width", 32}, {"height", 24}}));
  EXPECT_EQ(rec["output"]["aovs"], nlohmann::json::array());
  EXPECT_EQ(rec["progress"]["pass_spp"], "adaptive");
  EXPECT_EQ(rec["display"]["view"], "");
}

TEST_F(RunRecordApp, SamplerAndFilterAreWhatTookTheSamples) {
  // The path integrator's own; the classic integrators sample a pixel grid with
  // a box filter, whatever the path integrator's settings say. The run record
  // and the EXR's header say the same.
  write("s.json", path_scene(8, 6, 1));
  ASSERT_EQ(run("s.json -o p.exr --sampler jittered --filter gaussian --report path.json --quiet").status, 0);
  ASSERT_EQ(run("s.json -o q.exr --set render.light_sampler=power --report power.json --quiet").status, 0);
  ASSERT_EQ(run("s.json -o w.exr --integrator whitted --sampler jittered --filter gaussian --report whitted.json --quiet").status, 0);
  const struct {
    const char *exr, *record, *sampler, *filter, *light_sampler;
  } expected[] = {{"p.exr", "path.json", "jittered", "gaussian", "bvh"},
                  {"q.exr", "power.json", "sobol", "box", "power"},
                  {"w.exr", "whitted.json", "pixel-grid", "box", "all"}};
  for (const auto& e : expected) {
    SCOPED_TRACE(e.record);
    const nlohmann::json rec = read_json(e.record);
    EXPECT_EQ(rec["image"]["sampler"], e.sampler);
    EXPECT_EQ(rec["image"]["filter"], e.filter);
    auto in = OIIO::ImageInput::open(path(e.exr));
    ASSERT_TRUE(in);
    EXPECT_EQ(in->spec().get_string_attribute("pathtracer:sampler"), e.sampler);
    EXPECT_EQ(in->spec().get_string_attribute("pathtracer:filter"), e.filter);
    EXPECT_EQ(rec["image"]["light_sampler"], e.light_sampler);
    EXPECT_EQ(in->spec().get_string_attribute("pathtracer:lightSampler"), e.light_sampler);
  }
}

TEST_F(RunRecordApp, ImportedModelFilesArePrintedAndRecorded) {
  // A model file given as the scene (docs/importing.md): what it brought in
  // and left out is a note on stderr and the run record's "imports".
  const std::string dae = std::string(PT_TEST_DATA_DIR) + "/data/assets/dae/scene.dae";
  const RunResult r = run("'" + dae + "' -o m.png --width 24 --spp 1 --report run.json");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("note: imported '" + dae + "' (COLLADA, "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("2 instances"), std::string::npos) << r.err;
  const nlohmann::json imports = read_json("run.json")["imports"];
  ASSERT_EQ(imports.size(), 1u) << imports;
  EXPECT_EQ(imports[0]["file"], dae);
  EXPECT_EQ(imports[0]["format"], "COLLADA");
  EXPECT_EQ(imports[0]["imported"]["instances"], 2);
  EXPECT_EQ(imports[0]["imported"]["lights"], 1);
  EXPECT_TRUE(imports[0]["skipped"].is_object());
  EXPECT_GE(imports[0]["seconds"].get<double>(), 0.0);
}

}  // namespace
}  // namespace pt::test
