// The command line's driver pieces without a process: pass planning,
// memory estimate and sizes, progress text, the signal flag.
#include <signal.h>

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include "app/film_options.h"
#include "accel/embree/compact.h"
#include "app/memory_estimate.h"
#include "app/mpi_launch.h"
#include "io/exr_bands.h"
#include "app/options.h"
#include "app/progress.h"
#include "app/render_driver.h"
#include "app/render_settings.h"
#include "app/signals.h"
#include "core/parallel.h"
#include "render/film/film.h"
#include "io/image_metadata.h"
#include "io/run_record.h"
#include "render/render_scene.h"
#include "scene/loader.h"
#include "scene/scene_description.h"

namespace pt {
namespace {

// ---------------------------------------------------------------- settings

SceneDescription cornell_box() {  // path, max_depth 64, box filter, 256x256
  Diagnostics diag;
  std::optional<SceneDescription> desc = load_scene(PT_SCENES_DIR "/cornell-box.json", LoadOptions{}, diag);
  EXPECT_TRUE(desc) << diag.format();
  return desc ? std::move(*desc) : SceneDescription{};
}

TEST(RenderSettings, TheSceneDecidesWhatTheCommandLineLeavesUnset) {
  const SceneDescription desc = cornell_box();
  RenderSettings s;
  Diagnostics diag;
  ASSERT_TRUE(resolve_render_settings(desc, SettingsOverrides{}, s, diag));
  EXPECT_EQ(s.integrator_name(), "path");
  EXPECT_EQ(s.integration.max_depth, 64);
  EXPECT_EQ(s.integration.filter, PixelFilterType::Box);
  EXPECT_EQ(s.integration.sampler, IntegratorSettings{}.sampler);
  EXPECT_EQ(s.width, 256);
  EXPECT_EQ(s.height, 256);
}

TEST(RenderSettings, EveryDerivedViewHoldsTheResolvedValues) {
  const SceneDescription desc = cornell_box();
  SettingsOverrides o;
  o.max_depth = 3;
  o.seed = 7;
  o.filter = "gaussian";
  o.sampler = SamplerType::Jittered;
  o.clamp = 2.0f;
  o.width = 100;  // alone: keeps the square aspect ratio
  RenderSettings s;
  Diagnostics diag;
  ASSERT_TRUE(resolve_render_settings(desc, o, s, diag));
  EXPECT_EQ(s.height, 100);
  const BuildOptions build = s.build_options(AccelKind::Embree);
  EXPECT_EQ(build.accel, AccelKind::Embree);
  int w = 0, h = 0;
  resolve_resolution(desc.film, build, w, h);
  EXPECT_EQ(w, 100);
  EXPECT_EQ(h, 100);
  const RenderStamp stamp = s.stamp();
  EXPECT_EQ(stamp.integrator, "path");
  EXPECT_EQ(stamp.sampler, "jittered");
  EXPECT_EQ(stamp.filter, "gaussian");
  EXPECT_EQ(stamp.seed, 7u);
  EXPECT_EQ(stamp.max_depth, 3);
  EXPECT_EQ(stamp.clamp, 2.0f);
  RunRecord record;
  s.describe(record);
  EXPECT_EQ(record.sampler, "jittered");
  EXPECT_EQ(record.width, 100);
  EXPECT_EQ(s.identity().dump(), R"({"integrator":"path","width":100,"height":100,"max_depth":3,"seed":7,)"
                                 R"("sampler":"jittered","filter":"gaussian","clamp":2.0})");
  EXPECT_TRUE(s.equal_passes());  // jittered stratifies over each pass
}

TEST(RenderSettings, ClassicIntegratorsSampleThePixelGridWithABox) {
  const SceneDescription desc = cornell_box();
  SettingsOverrides o;
  o.integrator = "whitted";
  o.filter = "mitchell";
  o.sampler = SamplerType::Sobol;
  RenderSettings s;
  Diagnostics diag;
  ASSERT_TRUE(resolve_render_settings(desc, o, s, diag));
  EXPECT_STREQ(s.sampler_name(), "pixel-grid");
  EXPECT_STREQ(s.filter_name(), "box");
  EXPECT_TRUE(s.equal_passes());
  EXPECT_EQ(s.stamp().light_sampler, "all");  // whitted visits every light
  // The checkpoint identity keeps the configured names (as every checkpoint so far).
  EXPECT_EQ(s.identity()["sampler"], "sobol");
  EXPECT_EQ(s.identity()["filter"], "mitchell");
}

// The value of the attribute `name` among `attributes` (one of ImageMetadata's
// lists of name/value pairs), or null when it is not there.
template <class Pairs>
const auto* stamped_value(const Pairs& attributes, const std::string& name) {
  const auto it = std::find_if(attributes.begin(), attributes.end(), [&](const auto& kv) { return kv.first == name; });
  return it == attributes.end() ? nullptr : &it->second;
}

TEST(RenderSettings, TheLightSamplerIsStampedAndRecorded) {
  // The scene's render.light_sampler (default bvh) for the path integrator,
  // which picks one light per vertex; "all" and "none" where no light is chosen.
  SceneDescription desc = cornell_box();
  const struct {
    const char* integrator;
    LightSamplerType type;
    const char* expected;
  } cases[] = {{"path", LightSamplerType::Bvh, "bvh"},
               {"path", LightSamplerType::Power, "power"},
               {"whitted", LightSamplerType::Power, "all"},
               {"normal", LightSamplerType::Power, "none"}};
  for (const auto& c : cases) {
    SCOPED_TRACE(std::string(c.integrator) + " " + c.expected);
    desc.render.light_sampler.value = c.type;
    SettingsOverrides o;
    o.integrator = c.integrator;
    RenderSettings s;
    Diagnostics diag;
    ASSERT_TRUE(resolve_render_settings(desc, o, s, diag));
    EXPECT_EQ(s.stamp().light_sampler, c.expected);
    RunRecord record;
    s.describe(record);
    EXPECT_EQ(record.light_sampler, c.expected);
    ImageMetadata metadata;
    add_render_stamp(metadata, s.stamp());
    const auto* stamped = stamped_value(metadata.strings, "pathtracer:lightSampler");
    ASSERT_NE(stamped, nullptr);
    EXPECT_EQ(*stamped, c.expected);
    EXPECT_EQ(nlohmann::json::parse(run_record_json(record))["image"]["light_sampler"], c.expected);
  }
}

TEST(RenderSettings, LightGuidingAndTheTerminatorOffsetAreStampedAndRecorded) {
  // render.light_guiding where a light is chosen per vertex (the path
  // integrator), 0 where it is not used; the terminator offset as resolved.
  SceneDescription desc = cornell_box();
  desc.render.light_guiding.value = 16;
  desc.render.path_guiding.value = 8;  // and render.path_guiding the same way
  desc.render.shadow_terminator_geometry_offset.value = 0.25f;
  const struct {
    const char* integrator;
    int guiding;
  } cases[] = {{"path", 16}, {"whitted", 0}, {"normal", 0}};
  for (const auto& c : cases) {
    SCOPED_TRACE(c.integrator);
    SettingsOverrides o;
    o.integrator = c.integrator;
    RenderSettings s;
    Diagnostics diag;
    ASSERT_TRUE(resolve_render_settings(desc, o, s, diag));
    ImageMetadata metadata;
    add_render_stamp(metadata, s.stamp());
    const auto* guiding = stamped_value(metadata.ints, "pathtracer:lightGuiding");
    ASSERT_NE(guiding, nullptr);
    EXPECT_EQ(*guiding, c.guiding);
    const auto* path_guiding = stamped_value(metadata.ints, "pathtracer:pathGuiding");
    ASSERT_NE(path_guiding, nullptr);
    EXPECT_EQ(*path_guiding, c.guiding / 2);
    const auto* offset = stamped_value(metadata.floats, "pathtracer:shadowTerminatorOffset");
    ASSERT_NE(offset, nullptr);
    EXPECT_EQ(*offset, 0.25f);
    RunRecord record;
    s.describe(record);
    const auto image = nlohmann::json::parse(run_record_json(record))["image"];
    EXPECT_EQ(image["light_guiding"], c.guiding);
    EXPECT_EQ(image["path_guiding"], c.guiding / 2);
    EXPECT_EQ(image["shadow_terminator_geometry_offset"], 0.25f);
  }
}

TEST(RenderSettings, AnUnknownIntegratorIsAnErrorListingTheNames) {
  const SceneDescription desc = cornell_box();
  SettingsOverrides o;
  o.integrator = "nope";
  RenderSettings s;
  Diagnostics diag;
  EXPECT_FALSE(resolve_render_settings(desc, o, s, diag));
  ASSERT_EQ(diag.error_count(), 1);
  EXPECT_EQ(diag.all()[0].message.rfind("unknown integrator 'nope'; valid names are: whitted path", 0), 0u)
      << diag.all()[0].message;
}

TEST(IntegratorRegistry, OnlyThePathIntegratorsJitteredSamplerNeedsEqualPasses) {
  std::string error;
  const IntegratorInfo* path = find_integrator("path", error);
  ASSERT_NE(path, nullptr);
  EXPECT_TRUE(path->configurable_sampling);
  EXPECT_TRUE(path->equal_passes(SamplerType::Jittered));
  EXPECT_FALSE(path->equal_passes(SamplerType::Sobol));
  EXPECT_FALSE(path->equal_passes(SamplerType::Random));
  for (const std::string& name : integrator_names()) {
    const IntegratorInfo* info = find_integrator(name, error);
    ASSERT_NE(info, nullptr) << name;
    EXPECT_EQ(info->configurable_sampling, name == "path") << name;
    EXPECT_NE(info->make(IntegratorSettings{}), nullptr) << name;
  }
  EXPECT_EQ(find_integrator("nope", error), nullptr);
}

TEST(PassPlan, FixedSizes) {
  PassPlan p;
  p.target_spp = 64;
  EXPECT_EQ(fixed_pass_size(p), 64);  // a sample target alone: one pass
  p.pass_spp = 16;
  EXPECT_EQ(fixed_pass_size(p), 16);
  p.pass_spp = 10;
  p.equal_passes = true;
  EXPECT_EQ(fixed_pass_size(p), 8);  // the largest divisor of 64 not above 10
  p.target_spp = 13;
  EXPECT_EQ(fixed_pass_size(p), 1);  // a prime: passes of one sample
  p = PassPlan{};
  p.time_budget_s = 5;
  p.equal_passes = true;
  EXPECT_EQ(fixed_pass_size(p), 4);  // the default equal pass under a budget
}

// A replay's sampler is made for the size of the pass that drew the sample.
TEST(PassPlan, ReplaySamplerSppIsThePassSize) {
  PassPlan p;
  p.target_spp = 2;
  p.pass_spp = 1;
  p.equal_passes = true;
  EXPECT_EQ(replay_sampler_spp(p), 1);  // jittered, 2 spp in passes of 1
  p.target_spp = 64;
  p.pass_spp = 0;
  EXPECT_EQ(replay_sampler_spp(p), 64);  // one pass
  p.pass_spp = 10;
  EXPECT_EQ(replay_sampler_spp(p), 8);
  p = PassPlan{};
  p.time_budget_s = 5;
  p.equal_passes = true;
  EXPECT_EQ(replay_sampler_spp(p), 4);  // a budget without a target: passes of 4
  p.pass_spp = 2;
  EXPECT_EQ(replay_sampler_spp(p), 2);
  p.equal_passes = false;
  EXPECT_EQ(replay_sampler_spp(p), 1);  // random, Sobol': any size draws the same samples
}

TEST(PassPlan, AdaptiveSizesFitTheTimeLeft) {
  EXPECT_EQ(adaptive_pass_size(0.0, 10.0, 0, 1000), 1);    // first pass: one sample to measure
  EXPECT_EQ(adaptive_pass_size(0.0, 10.0, 4, 1000), 8);    // unmeasured: doubles
  EXPECT_EQ(adaptive_pass_size(0.01, 4.0, 1, 1000), 100);  // a quarter of the time left
  EXPECT_EQ(adaptive_pass_size(0.1, 40.0, 1, 1000), 40);   // ... but no more than ~4 s
  EXPECT_EQ(adaptive_pass_size(0.01, 0.2, 50, 1000), 10);  // near the end: at least 0.1 s
  EXPECT_EQ(adaptive_pass_size(0.01, 0.05, 50, 1000), 4);  // what fits in 90% of the time left
  EXPECT_EQ(adaptive_pass_size(0.1, 0.1, 50, 1000), 0);    // not even one sample per pixel: stop
  EXPECT_EQ(adaptive_pass_size(0.001, 100.0, 1, 7), 7);    // never past the target
  EXPECT_EQ(adaptive_pass_size(0.1, 10.0, 1, 0), 0);
}

// An integrator that records the sample ranges it was asked for.
class RecordingIntegrator : public Integrator {
 public:
  RecordingIntegrator(const IntegratorSettings& s, std::vector<std::pair<int, int>>& log) : s_(s), log_(log) {}
  void render(const RenderScene&, Film& film, WorkerPool&) const override {
    log_.emplace_back(s_.first_sample, s_.spp);
    PixelSum sum;
    for (int i = 0; i < s_.spp; ++i) sum.add(RGB(1, 1, 1), 1.0f, true);
    film.add(0, 0, sum);
  }

 private:
  IntegratorSettings s_;
  std::vector<std::pair<int, int>>& log_;
};

TEST(RenderPasses, ConsecutiveRangesUpToTheTarget) {
  RenderScene scene;
  Film film(1, 1);
  WorkerPool pool(1);
  std::vector<std::pair<int, int>> log;
  std::vector<int> done;
  DriverCallbacks cb;
  cb.make_integrator = [&](const IntegratorSettings& s) { return std::make_unique<RecordingIntegrator>(s, log); };
  cb.pass_done = [&](int spp) { done.push_back(spp); };
  PassPlan plan;
  plan.target_spp = 10;
  plan.pass_spp = 4;
  plan.start_spp = 2;  // resumed
  const RenderOutcome out = render_passes(scene, film, pool, plan, IntegratorSettings{}, cb);
  EXPECT_EQ(out.spp_done, 10);
  EXPECT_EQ(out.passes, 2);
  EXPECT_FALSE(out.cancelled);
  EXPECT_EQ(log, (std::vector<std::pair<int, int>>{{2, 4}, {6, 4}}));
  EXPECT_EQ(done, (std::vector<int>{6, 10}));
  EXPECT_EQ(film.sum(0, 0).samples, 8u);
}

// Every pass of one render gets the same RenderCache (what an integrator
// learns before its samples is learned once per render), unless the caller
// brings its own.
TEST(RenderPasses, GuidesAreLearnedOncePerRender) {
  RenderScene scene;
  Film film(1, 1);
  WorkerPool pool(1);
  std::vector<std::pair<int, int>> log;
  std::vector<RenderCache*> caches;
  int learned = 0;
  DriverCallbacks cb;
  cb.make_integrator = [&](const IntegratorSettings& s) {
    caches.push_back(s.cache);
    if (s.cache != nullptr && !s.cache->slot) {
      s.cache->slot = std::make_shared<int>(1);
      ++learned;
    }
    return std::make_unique<RecordingIntegrator>(s, log);
  };
  PassPlan plan;
  plan.target_spp = 12;
  plan.pass_spp = 4;
  render_passes(scene, film, pool, plan, IntegratorSettings{}, cb);
  ASSERT_EQ(caches.size(), 3u);
  EXPECT_NE(caches[0], nullptr);
  EXPECT_EQ(caches[1], caches[0]);
  EXPECT_EQ(caches[2], caches[0]);
  EXPECT_EQ(learned, 1);
  RenderCache mine;
  IntegratorSettings settings;
  settings.cache = &mine;
  caches.clear();
  render_passes(scene, film, pool, plan, settings, cb);
  for (RenderCache* c : caches) EXPECT_EQ(c, &mine);
  EXPECT_TRUE(mine.slot);
}

TEST(RenderPasses, EqualPassesNeverEndWithASmallerOne) {
  RenderScene scene;
  Film film(1, 1);
  WorkerPool pool(1);
  std::vector<std::pair<int, int>> log;
  DriverCallbacks cb;
  cb.make_integrator = [&](const IntegratorSettings& s) { return std::make_unique<RecordingIntegrator>(s, log); };
  PassPlan plan;
  plan.target_spp = 12;
  plan.pass_spp = 5;
  plan.equal_passes = true;
  EXPECT_EQ(render_passes(scene, film, pool, plan, IntegratorSettings{}, cb).spp_done, 12);
  EXPECT_EQ(log, (std::vector<std::pair<int, int>>{{0, 4}, {4, 4}, {8, 4}}));
}

class CancelledMonitor : public RenderMonitor {
 public:
  bool cancelled() const override { return true; }
};

TEST(RenderPasses, ACancelledPassDoesNotCount) {
  RenderScene scene;
  Film film(1, 1);
  WorkerPool pool(1);
  std::vector<std::pair<int, int>> log;
  DriverCallbacks cb;
  cb.make_integrator = [&](const IntegratorSettings& s) { return std::make_unique<RecordingIntegrator>(s, log); };
  PassPlan plan;
  plan.target_spp = 8;
  plan.pass_spp = 2;
  CancelledMonitor monitor;
  IntegratorSettings settings;
  settings.monitor = &monitor;
  const RenderOutcome out = render_passes(scene, film, pool, plan, settings, cb);
  EXPECT_TRUE(out.cancelled);
  EXPECT_EQ(out.spp_done, 0);
  EXPECT_EQ(log.size(), 1u);
}

TEST(MemoryEstimate, ParsesSizes) {
  EXPECT_EQ(parse_byte_size("4G"), uint64_t{4} << 30);
  EXPECT_EQ(parse_byte_size("512M"), uint64_t{512} << 20);
  EXPECT_EQ(parse_byte_size("64k"), uint64_t{64} << 10);
  EXPECT_EQ(parse_byte_size("2GiB"), uint64_t{2} << 30);
  EXPECT_EQ(parse_byte_size("1000"), 1000u);
  EXPECT_EQ(parse_byte_size("1000B"), 1000u);
  EXPECT_FALSE(parse_byte_size("").has_value());
  EXPECT_FALSE(parse_byte_size("G").has_value());
  EXPECT_FALSE(parse_byte_size("4X").has_value());
  EXPECT_FALSE(parse_byte_size("-4G").has_value());
  EXPECT_FALSE(parse_byte_size("99999999999999999999").has_value());
  EXPECT_FALSE(parse_byte_size("99999999999T").has_value());
}

// The estimate is of the process's peak (issue 20): what is resident when it
// is made, plus what the render adds, less what malloc holds free to reuse;
// or the peak so far if that was higher (the mesh import's buffers).
TEST(MemoryEstimate, CountsTheProcessAsItIsAndReusesFreedHeap) {
  MemoryEstimate e;
  e.film = 100;
  e.images = 20;
  e.textures = 30;
  e.geometry = 50;
  EXPECT_EQ(e.added(), 200u);
  e.baseline = 1000;
  EXPECT_EQ(e.total(), 1200u);
  e.reusable = 80;
  EXPECT_EQ(e.total(), 1120u);
  e.reusable = 500;  // more free than the render needs: it does not grow
  EXPECT_EQ(e.total(), 1000u);
  e.peak_so_far = 5000;
  EXPECT_EQ(e.total(), 5000u);
  const std::string why = check_memory(e, 4096, 0);
  EXPECT_NE(why.find("the peak while the scene was read 4.88 KiB"), std::string::npos) << why;
  // Measured for this process: it is resident, and at its peak at least as much.
  EXPECT_GT(resident_bytes(), 1u << 20);
  EXPECT_GE(peak_resident_bytes(), resident_bytes() / 2);
  // And counted for every shape of the scene, instanced objects included.
  SceneDescription scene;
  ShapeDesc mesh;
  TriangleMesh m;
  m.positions.resize(30);
  m.indices.resize(3 * 10);
  mesh.geometry = m;
  ObjectDesc object;
  object.shapes.push_back(mesh);
  scene.objects.push_back(object);
  const uint64_t one = geometry_bytes(scene, AccelKind::Bvh);
  EXPECT_GE(one, 30u * 12u + 30u * 4u);  // at least the render scene's copy of the mesh
  scene.objects.push_back(object);
  EXPECT_GT(geometry_bytes(scene, AccelKind::Bvh), one);
  EXPECT_GT(geometry_bytes(scene, AccelKind::Embree), geometry_bytes(scene, AccelKind::Bvh));
}

// Embree builds scenes of kEmbreeCompactTriangles or more compact, about a
// third of the bytes a triangle at its build's peak (docs/bench/scale.md): the
// estimate follows the backend's choice, counting a scene's triangles together.
TEST(MemoryEstimate, EmbreeCompactBuildFromItsTriangleCount) {
  const auto scene_of = [](std::size_t triangles, int meshes) {
    SceneDescription scene;
    for (int k = 0; k < meshes; ++k) {
      ShapeDesc mesh;
      TriangleMesh m;
      m.positions.resize(3);
      m.indices.resize(3 * (triangles / meshes));  // every triangle the same: only the count matters here
      mesh.geometry = std::move(m);
      scene.shapes.push_back(std::move(mesh));
    }
    return scene;
  };
  const SceneDescription below = scene_of(kEmbreeCompactTriangles - 2, 2);
  const SceneDescription at = scene_of(kEmbreeCompactTriangles, 2);
  EXPECT_LT(geometry_bytes(at, AccelKind::Embree), geometry_bytes(below, AccelKind::Embree));
  EXPECT_GT(geometry_bytes(at, AccelKind::Bvh), geometry_bytes(below, AccelKind::Bvh));
  EXPECT_LT(geometry_bytes(at, AccelKind::Embree), geometry_bytes(at, AccelKind::Bvh));
}

TEST(MemoryEstimate, ScalesWithPixelsFilmBytesAndTriangles) {
  SceneDescription scene;
  const MemoryEstimate small = estimate_memory(scene, 100 * 100, {40, 32});
  EXPECT_EQ(small.film, 100u * 100u * 40u);
  EXPECT_EQ(small.images, 100u * 100u * 32u);
  EXPECT_EQ(small.textures, 0u);
  EXPECT_EQ(estimate_memory(scene, 100 * 100, {80, 32}).film, 2 * small.film);  // e.g. AOV layers
  EXPECT_EQ(estimate_memory(scene, 100 * 100, {40, 32}, 2).film, 2 * small.film);
  EXPECT_EQ(estimate_memory(scene, 50 * 100, {40, 32}).images, small.images / 2);  // a crop of half the frame
  EXPECT_EQ(estimate_memory(scene, 100 * 100, {40, 32, 1000}).images, small.images + 1000u);  // the writer's buffer
  ShapeDesc mesh;
  TriangleMesh m;
  m.positions.resize(3000);
  m.indices.resize(3 * 1000);
  mesh.geometry = m;
  scene.shapes.push_back(mesh);
  // The arrays (positions, indices) and at least 40 bytes a triangle of acceleration structure.
  EXPECT_GT(estimate_memory(scene, 100 * 100, {40, 32}).geometry, 3000u * 12u + 3000u * 4u + 1000u * 40u);
  const MemoryEstimate e = estimate_memory(scene, 100 * 100, {40, 32});
  EXPECT_EQ(e.total(), e.film + e.images + e.textures + e.geometry + e.runtime);
  EXPECT_TRUE(check_memory(e, 0, 0).empty());
  EXPECT_TRUE(check_memory(e, e.total(), 0).empty());
  const std::string why = check_memory(e, e.total() - 1, 0);
  EXPECT_NE(why.find("--max-memory"), std::string::npos) << why;
  EXPECT_NE(why.find(", textures 0 bytes, "), std::string::npos) << why;  // every part is named
  EXPECT_NE(check_memory(e, 0, e.total() - 1).find("physical memory"), std::string::npos);
}

// The bytes the writers take: 4 per channel of Film::layers() per pixel, and
// the largest output's own buffer: for EXR one band of packed rows (the
// writer's, io/exr_bands.h) and OpenEXR's line buffers, for PNG, JPEG and PPM
// the RGB image and its codes.
TEST(MemoryEstimate, OutputBuffersCountEveryAovChannel) {
  EXPECT_EQ(layer_bytes_per_pixel({}), 16u);  // R, G, B, A
  const ExrSettings zip{"zip", false, 2}, multipart{"zip", true, 2};
  EXPECT_EQ(writer_bytes({}, ChannelType::Float, {}, zip, 64, 48), 0u);  // a replay writes nothing
  // OpenEXR's line buffers: 2 per thread, no more than the blocks, 3 blocks' rows each.
  EXPECT_EQ(exr_block_rows("zip"), 16);
  EXPECT_EQ(exr_block_rows("dwaa:45"), 32);
  EXPECT_EQ(exr_block_rows("none"), 1);
  EXPECT_EQ(exr_line_buffer_bytes(100, 48, 16, 2), 3u * 3u * 16u * 100u);  // 3 blocks: 3 buffers
  EXPECT_EQ(exr_line_buffer_bytes(100, 2160, 16, 2), 4u * 3u * 16u * 100u);
  EXPECT_EQ(exr_line_buffer_bytes(100, 2160, 32, 8), 16u * 3u * 32u * 100u);
  // A small EXR is one band: every row, 16 bytes a pixel; 8 with a half beauty.
  EXPECT_EQ(writer_bytes({}, ChannelType::Float, {"a.exr"}, zip, 64, 48),
            64u * 48u * 16u + exr_line_buffer_bytes(64 * 16, 48, 16, 2));
  EXPECT_EQ(writer_bytes({}, ChannelType::Half, {"a.exr"}, zip, 64, 48),
            64u * 48u * 8u + exr_line_buffer_bytes(64 * 8, 48, 16, 2));
  EXPECT_EQ(writer_bytes({}, ChannelType::Float, {"a.PNG", "b.ppm"}, zip, 64, 48), 64u * 48u * 15u);
  std::vector<AovRequest> all;
  std::size_t channels = 4, packed = 16;
  for (const AovInfo& info : aov_catalogue()) {
    const AovRequest r{info.type, info.default_type, info.accumulation == Accumulation::Ranked ? 6 : 0};
    all.push_back(r);
    channels += static_cast<std::size_t>(aov_channel_count(r));
    packed += static_cast<std::size_t>(aov_channel_count(r)) * (r.channel_type == ChannelType::Half ? 2 : 4);
  }
  EXPECT_EQ(channels, 39u + 2 * 12u);  // Cryptomatte: 6 ranks are 3 layers of r, g, b, a
  EXPECT_EQ(packed, 63u * 4u - 7u * 2u);  // albedo, N and nonfinite are half
  EXPECT_EQ(layer_bytes_per_pixel(all), 63u * 4u);  // 252 bytes a pixel
  // 4K: a band is the 32-row blocks that fit 32 MiB (32 rows of 3840 pixels
  // of 238 bytes are 28 MiB); one part per layer: the largest layer's band
  // (the float beauty and the Cryptomatte layers: 16 bytes a pixel, 32 MiB / 60 KiB = 546 rows, 544 in
  // whole blocks); with a half beauty too. OpenEXR's line buffers are those of every part.
  const uint64_t lines = exr_line_buffer_bytes(3840 * packed, 2160, 16, 2);
  EXPECT_EQ(writer_bytes(all, ChannelType::Float, {"a.exr"}, zip, 3840, 2160), 32u * 3840u * packed + lines);
  EXPECT_EQ(writer_bytes(all, ChannelType::Float, {"a.exr"}, multipart, 3840, 2160), 544u * 3840u * 16u + lines);
  EXPECT_EQ(writer_bytes(all, ChannelType::Half, {"a.exr"}, multipart, 3840, 2160),
            544u * 3840u * 16u + exr_line_buffer_bytes(3840 * (packed - 8), 2160, 16, 2));
  EXPECT_EQ(writer_bytes({}, ChannelType::Half, {"a.exr"}, multipart, 3840, 2160),
            1088u * 3840u * 8u + exr_line_buffer_bytes(3840 * 8, 2160, 16, 2));
  // The largest writer's: at 4K the EXR's (28 MiB of band, 167 of line buffers) against a PNG's RGB image
  // and codes (119 MiB); without the AOVs the PNG's.
  EXPECT_EQ(writer_bytes(all, ChannelType::Float, {"a.png", "a.exr"}, zip, 3840, 2160), 32u * 3840u * packed + lines);
  EXPECT_EQ(writer_bytes({}, ChannelType::Float, {"a.png", "a.exr"}, zip, 3840, 2160), 3840u * 2160u * 15u);
  EXPECT_EQ(exr_band_rows(3840 * packed, 2160), 32);
  EXPECT_EQ(exr_band_rows(3840 * 12, 2160), 704);
  EXPECT_EQ(exr_band_rows(3840 * 12, 300), 300);
  // The film: PixelSum (five 16-byte exact sums: r, g, b, weight, coverage;
  // and a count), then each AOV's exact sums and plain values (Cryptomatte:
  // two exact sums per rank, the id's bits and its weight).
  EXPECT_EQ(sizeof(PixelSum), 88u);
  EXPECT_EQ(film_bytes_per_pixel({}), sizeof(PixelSum));
  EXPECT_EQ(film_bytes_per_pixel({{AovType::Position, ChannelType::Float}}), sizeof(PixelSum) + 4 * sizeof(double));
  EXPECT_EQ(film_bytes_per_pixel({{AovType::Variance, ChannelType::Float}}), sizeof(PixelSum) + 6 * sizeof(ExactSum));
  EXPECT_EQ(film_bytes_per_pixel({{AovType::CryptoObject, ChannelType::Float, 6}}),
            sizeof(PixelSum) + 12 * sizeof(ExactSum));  // 280 bytes
}

// Textures are estimated from their files' headers: only those a material
// uses, and the environment map with its sampling distribution.
TEST(MemoryEstimate, TexturesFromTheirFileHeaders) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("pt_memory_test_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto write_image = [&](const std::string& name, int w, int h, int channels) {
    const std::string file = (dir / name).string();
    auto out = OIIO::ImageOutput::create(file);
    ASSERT_TRUE(out);
    ASSERT_TRUE(out->open(file, OIIO::ImageSpec(w, h, channels, OIIO::TypeDesc::HALF)));
    std::vector<float> pixels(static_cast<std::size_t>(w * h * channels), 0.5f);
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()));
    ASSERT_TRUE(out->close());
  };
  write_image("used.exr", 64, 32, 3);
  write_image("unused.exr", 100, 100, 3);
  write_image("env.exr", 16, 8, 4);
  SceneDescription scene;
  scene.textures.push_back({{}, "unused.exr", (dir / "unused.exr").string()});
  scene.textures.push_back({{}, "used.exr", (dir / "used.exr").string()});
  MaterialDesc material;
  material.texture = 1;
  scene.materials.push_back(material);
  // A material's image is in the texture cache: its MIP pyramid at 4 bytes a
  // channel (4/3 of 64 * 32 * 12 bytes), and its decode buffer.
  constexpr uint64_t kCached = 64u * 32u * 12u + 64u * 32u * 12u / 3u, kDecode = 64u * 32u * 3u * 4u;
  EXPECT_EQ(texture_bytes(scene), kCached + kDecode);
  // The cache holds no more than its size (--texture-cache).
  EXPECT_EQ(texture_bytes(scene, TextureLimits{}, 1000), 1000 + kDecode);
  EXPECT_EQ(estimate_memory(scene, 1, {40, 32}, 1, AccelKind::Bvh, 1000).textures, 1000 + kDecode);
  scene.environment = EnvironmentDesc{};
  scene.environment->resolved = (dir / "env.exr").string();
  EXPECT_EQ(texture_bytes(scene), kCached + 16u * 8u * 24u + kDecode);  // the environment map is decoded
  EXPECT_EQ(estimate_memory(scene, 1, {40, 32}).textures, texture_bytes(scene));
  scene.environment->resolved = (dir / "missing.exr").string();  // the build reports it
  EXPECT_EQ(texture_bytes(scene), kCached + kDecode);
  // An image the loader would refuse counts nothing, by either limit, at the
  // loader's exact values (Texture::load reads 3 channels as float and keeps
  // RGB texels: 64 * 32 * 24 bytes).
  scene.environment.reset();
  constexpr uint64_t kPixels = 64 * 32, kBytes = kPixels * 24;
  EXPECT_EQ(texture_bytes(scene, TextureLimits{kPixels, kBytes}), kCached + kDecode);
  EXPECT_EQ(texture_bytes(scene, TextureLimits{kPixels - 1, kBytes}), 0u);
  EXPECT_EQ(texture_bytes(scene, TextureLimits{kPixels, kBytes - 1}), 0u);
  // An image embedded in a model file (a .glb's PNG) counts as the same file would.
  write_image("embedded.png", 64, 32, 3);
  std::ifstream png(dir / "embedded.png", std::ios::binary);
  auto bytes = std::make_shared<const std::vector<unsigned char>>(std::istreambuf_iterator<char>(png),
                                                                  std::istreambuf_iterator<char>());
  scene.textures[1].resolved.clear();
  scene.textures[1].embedded = bytes;
  scene.textures[1].embedded_format = "png";
  EXPECT_EQ(texture_bytes(scene), kCached + kDecode);
  std::filesystem::remove_all(dir);
}

TEST(Progress, SnapshotFractionAndEta) {
  ProgressSettings st;
  st.pixels = 100;
  st.target_spp = 10;
  ProgressSnapshot s = make_snapshot(st, 2.0, 250, 2);
  EXPECT_DOUBLE_EQ(s.fraction, 0.25);
  EXPECT_DOUBLE_EQ(s.samples_per_s, 125.0);
  EXPECT_DOUBLE_EQ(s.eta_s, 6.0);
  st.time_budget_s = 4.0;  // the budget ends first
  s = make_snapshot(st, 2.0, 250, 2);
  EXPECT_DOUBLE_EQ(s.fraction, 0.5);
  EXPECT_DOUBLE_EQ(s.eta_s, 2.0);
  const std::string line = format_progress_line(s);
  EXPECT_NE(line.find("50.0%"), std::string::npos) << line;
  EXPECT_NE(line.find("ETA 0:02"), std::string::npos) << line;
  EXPECT_NE(line.find("125 samples/s"), std::string::npos) << line;
  const std::string bar = format_progress_bar(s, 10);
  EXPECT_EQ(bar.substr(0, 12), "[#####.....]") << bar;
}

TEST(Progress, MonitorCountsTilesAndPrintsLines) {
  std::ostringstream out;
  ProgressSettings st;
  st.style = ProgressStyle::Lines;
  st.interval_s = 0.05;
  st.pixels = 10;
  st.target_spp = 10;
  ProgressMonitor monitor(st, nullptr, out);
  monitor.start();
  monitor.tile_done(30, 150);
  monitor.tile_done(20, 100);
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  monitor.stop();
  EXPECT_EQ(monitor.samples(), 50);
  EXPECT_EQ(monitor.rays(), 250);
  EXPECT_NE(out.str().find("rays/s"), std::string::npos) << out.str();
  EXPECT_FALSE(monitor.cancelled());
  EXPECT_NE(out.str().find("progress: 50.0%"), std::string::npos) << out.str();
}

TEST(Signals, FirstSignalSetsTheFlagAndHandlersAreRestored) {
  struct sigaction before {};
  ::sigaction(SIGINT, nullptr, &before);
  {
    SignalCancellation signals;
    EXPECT_FALSE(signals.cancelled());
    ::raise(SIGTERM);  // handled: the process goes on
    EXPECT_TRUE(signals.cancelled());
    EXPECT_EQ(signals.received(), SIGTERM);
  }
  struct sigaction after {};
  ::sigaction(SIGINT, nullptr, &after);
  EXPECT_EQ(before.sa_handler, after.sa_handler);
  EXPECT_EQ(exit_status_for_signal(SIGINT), 130);
  EXPECT_EQ(exit_status_for_signal(SIGTERM), 143);
}

TEST(Signals, ASecondSignalExitsAtOnce) {
  EXPECT_EXIT(
      {
        SignalCancellation signals;
        ::raise(SIGINT);
        ::raise(SIGINT);
        std::_Exit(0);  // not reached
      },
      ::testing::ExitedWithCode(130), "");
}

}  // namespace
// src/app/mpi_launch_none.cpp, linked into this test in every build (the
// executable has it only where CMake finds no MPI, or -DPT_WITH_MPI=OFF): --mpi
// says the build has no MPI, exits 2 and runs nothing.
TEST(MpiLaunchNone, SaysTheBuildHasNoMpiAndRunsNothing) {
  EXPECT_FALSE(mpi_built());
  std::ostringstream err;
  std::streambuf* const old = std::cerr.rdbuf(err.rdbuf());
  bool ran = false;
  const int status = run_with_mpi(Options{}, [&](const Options&) {
    ran = true;
    return 0;
  });
  std::cerr.rdbuf(old);
  EXPECT_EQ(status, kExitUsage);
  EXPECT_FALSE(ran);
  EXPECT_NE(err.str().find("this pathtracer was built without MPI"), std::string::npos) << err.str();
}

}  // namespace pt
