// Film state round trips (checkpoints) and the render monitor's hooks.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstring>
#include <sstream>

#include "core/parallel.h"
#include "render/film/film.h"
#include "render/integrators/integrator.h"
#include "test_scenes.h"

namespace pt {
namespace {

Film filled_film(int w, int h) {
  Film film(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      PixelSum s;
      s.add(RGB(0.1f * x, 1.0f / 3.0f + y, 1e-30f * (x + 1)), 0.75f, true);
      s.add(RGB(7.0f, 0.0f, 2.5f), 0.25f, x % 2 == 0);
      film.add(x, y, s);
    }
  return film;
}

TEST(FilmState, RoundTripIsBitExact) {
  const Film film = filled_film(5, 3);
  std::stringstream buffer;
  ASSERT_TRUE(film.write_state(buffer));
  Film back(5, 3);
  std::string error;
  ASSERT_TRUE(back.read_state(buffer, error)) << error;
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 5; ++x) {
      const PixelSum &a = film.sum(x, y), &b = back.sum(x, y);
      EXPECT_EQ(a.r, b.r);
      EXPECT_EQ(a.g, b.g);
      EXPECT_EQ(a.b, b.b);
      EXPECT_EQ(a.weight, b.weight);
      EXPECT_EQ(a.coverage, b.coverage);
      EXPECT_EQ(a.samples, b.samples);
    }
}

TEST(FilmState, RejectsWrongSizeTruncationAndGarbage) {
  const Film film = filled_film(4, 4);
  std::stringstream buffer;
  ASSERT_TRUE(film.write_state(buffer));
  const std::string state = buffer.str();
  std::string error;

  Film other(4, 5);
  std::istringstream wrong_size(state);
  EXPECT_FALSE(other.read_state(wrong_size, error));
  EXPECT_NE(error.find("4x4"), std::string::npos) << error;

  Film target = filled_film(4, 4);
  const ExactSum before = target.sum(1, 1).r;
  std::istringstream truncated(state.substr(0, state.size() - 3));
  EXPECT_FALSE(target.read_state(truncated, error));
  EXPECT_NE(error.find("truncated"), std::string::npos) << error;
  EXPECT_EQ(target.sum(1, 1).r, before);  // unchanged

  std::istringstream garbage(std::string(200, 'x'));
  EXPECT_FALSE(target.read_state(garbage, error));
  EXPECT_NE(error.find("magic"), std::string::npos) << error;

  std::istringstream trailing(state + "z");
  EXPECT_FALSE(target.read_state(trailing, error));
  EXPECT_NE(error.find("trailing"), std::string::npos) << error;
}

// A cropped film with AOVs and a non-finite report, rendered for real.
Film rendered_film(WorkerPool& pool, const std::vector<AovRequest>& aovs) {
  SceneDescription d = test::empty_scene(24, 18, Vec3f(0, 0, 5), Vec3f(0, 0, 0), Vec3f(0, 1, 0));
  test::add_sphere(d, Vec3f(0, 0, 0), 1.0f, test::add_material(d, test::diffuse_material(RGB(0.5f))));
  test::add_point_light(d, Vec3f(2, 2, 4), RGB(10.0f), RGB(10.0f));
  const auto scene = test::build(d, pool);
  Film film(24, 18, PixelRect{3, 2, 20, 15}, aovs);
  IntegratorSettings settings;
  settings.spp = 3;
  std::string error;
  make_integrator("path", settings, error)->render(*scene, film, pool);
  NonFiniteReport bad;
  bad.record(5, 4, 2, RGB(1.0f, std::nanf(""), 0.0f));
  film.add_non_finite(bad);
  return film;
}

TEST(FilmState, AovsCropAndNonFiniteReportRoundTripBitExactly) {
  WorkerPool pool(2);
  std::vector<AovRequest> aovs;
  for (const AovInfo& info : aov_catalogue())
    aovs.push_back({info.type, info.default_type, info.accumulation == Accumulation::Ranked ? 3 : 0});
  const Film film = rendered_film(pool, aovs);
  std::stringstream buffer;
  ASSERT_TRUE(film.write_state(buffer));
  Film back(24, 18, PixelRect{3, 2, 20, 15}, aovs);
  std::string error;
  ASSERT_TRUE(back.read_state(buffer, error)) << error;
  const LayeredImage a = film.layers(), b = back.layers();
  ASSERT_EQ(a.layers.size(), aovs.size() + 1 + 2);  // CryptoObject and CryptoMaterial have 2 layers each
  for (std::size_t i = 0; i < a.layers.size(); ++i) {
    ASSERT_EQ(a.layers[i].values.size(), b.layers[i].values.size());
    EXPECT_EQ(0, std::memcmp(a.layers[i].values.data(), b.layers[i].values.data(),
                             a.layers[i].values.size() * sizeof(float)))
        << a.layers[i].name;
  }
  EXPECT_EQ(back.non_finite().nan, 1u);
  EXPECT_EQ(back.non_finite().x, 5);
  EXPECT_EQ(back.non_finite().sample, 2);
  // Adding to a restored film continues exactly where the original was.
  std::stringstream again;
  ASSERT_TRUE(back.write_state(again));
  EXPECT_EQ(again.str(), buffer.str());
}

TEST(FilmState, RejectsAnotherCropOrAovList) {
  WorkerPool pool(1);
  const std::vector<AovRequest> aovs = {{AovType::Albedo, ChannelType::Half}};
  std::stringstream buffer;
  ASSERT_TRUE(rendered_film(pool, aovs).write_state(buffer));
  const std::string state = buffer.str();
  std::string error;
  Film other_crop(24, 18, PixelRect{3, 2, 20, 16}, aovs);
  std::istringstream in1(state);
  EXPECT_FALSE(other_crop.read_state(in1, error));
  EXPECT_NE(error.find("crop"), std::string::npos) << error;
  Film other_aovs(24, 18, PixelRect{3, 2, 20, 15}, {{AovType::Albedo, ChannelType::Float}});
  std::istringstream in2(state);
  EXPECT_FALSE(other_aovs.read_state(in2, error));
  EXPECT_NE(error.find("albedo:half"), std::string::npos) << error;
  Film none(24, 18, PixelRect{3, 2, 20, 15});
  std::istringstream in3(state);
  EXPECT_FALSE(none.read_state(in3, error));
  EXPECT_NE(error.find("none"), std::string::npos) << error;
}

class CountingMonitor final : public RenderMonitor {
 public:
  explicit CountingMonitor(int64_t cancel_after) : cancel_after_(cancel_after) {}
  bool cancelled() const override { return done_.load() >= cancel_after_; }
  void tile_done(int64_t pixel_samples, int64_t rays) override {
    done_ += pixel_samples;
    rays_ += rays;
  }
  int64_t done() const { return done_.load(); }
  int64_t rays() const { return rays_.load(); }

 private:
  int64_t cancel_after_;
  std::atomic<int64_t> done_{0};
  std::atomic<int64_t> rays_{0};
};

TEST(RenderMonitor, CountsEveryPixelSampleAndCancelsBetweenTiles) {
  WorkerPool pool(2);
  SceneDescription d = test::empty_scene(40, 30, Vec3f(0, 0, 5), Vec3f(0, 0, 0), Vec3f(0, 1, 0));
  test::add_sphere(d, Vec3f(0, 0, 0), 1.0f, test::add_material(d, test::diffuse_material(RGB(0.5f))));
  test::add_point_light(d, Vec3f(2, 2, 4), RGB(10.0f), RGB(10.0f));
  const auto scene = test::build(d, pool);
  ASSERT_TRUE(scene);
  IntegratorSettings settings;
  settings.spp = 3;
  settings.tile_size = 8;
  std::string error;

  CountingMonitor all(INT64_MAX);
  settings.monitor = &all;
  Film full(40, 30);
  make_integrator("path", settings, error)->render(*scene, full, pool);
  EXPECT_EQ(all.done(), 40 * 30 * 3);
  // Every sample traces its camera ray; those that hit the lit sphere also a
  // shadow ray to the point light and a bounce: more rays than samples, and
  // at most max_depth + 1 camera/bounce rays plus one shadow ray per vertex.
  EXPECT_GT(all.rays(), all.done());
  EXPECT_LE(all.rays(), all.done() * 2 * (settings.max_depth + 1));

  CountingMonitor early(1);  // cancels once the first tile is done
  settings.monitor = &early;
  Film partial(40, 30);
  make_integrator("path", settings, error)->render(*scene, partial, pool);
  uint64_t samples = 0;
  for (int y = 0; y < 30; ++y)
    for (int x = 0; x < 40; ++x) {
      samples += partial.sum(x, y).samples;
      EXPECT_TRUE(partial.sum(x, y).samples == 0 || partial.sum(x, y).samples == 3);
    }
  EXPECT_EQ(static_cast<int64_t>(samples), early.done());
  EXPECT_GT(samples, 0u);
  EXPECT_LT(samples, 40u * 30u * 3u);  // the remaining tiles were skipped
}

}  // namespace
}  // namespace pt
