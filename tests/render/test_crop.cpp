// Crops: a film's crop window holds exactly the pixels (beauty and AOVs) of
// the same pixels of a full render, for the classic and path loops, any pixel
// filter, sampler, thread count and tile size.
#include <gtest/gtest.h>

#include <cstring>

#include "core/parallel.h"
#include "render/film/film.h"
#include "render/integrators/integrator.h"
#include "test_scenes.h"

namespace pt {
namespace {

constexpr int kW = 40, kH = 30;

std::unique_ptr<RenderScene> scene(WorkerPool& pool) {
  SceneDescription d = test::empty_scene(kW, kH, Vec3f(0, 1, 5), Vec3f(0, 0, 0), Vec3f(0, 1, 0));
  test::add_z_square(d, -1.0f, 4.0f, test::add_material(d, test::diffuse_material(RGB(0.7f))));
  MaterialDesc shiny = test::diffuse_material(RGB(0.4f, 0.6f, 0.8f), 0.5f);
  shiny.ks = 0.4f;
  shiny.exponent = 20.0f;
  test::add_sphere(d, Vec3f(0, 0, 0), 0.8f, test::add_material(d, shiny));
  test::add_point_light(d, Vec3f(1, 3, 3), RGB(15.0f), RGB(15.0f));
  return test::build(d, pool);
}

TEST(Crop, PixelsEqualTheFullRender) {
  const std::vector<AovRequest> aovs = {{AovType::Albedo, ChannelType::Half},
                                        {AovType::Depth, ChannelType::Float},
                                        {AovType::DiffuseIndirect, ChannelType::Float},
                                        {AovType::Variance, ChannelType::Float}};
  const PixelRect crop{7, 5, 26, 17};
  struct Case {
    const char* integrator;
    PixelFilterType filter;
    SamplerType sampler;
  };
  for (const Case c : {Case{"whitted", PixelFilterType::Box, SamplerType::Random},
                       Case{"path", PixelFilterType::Mitchell, SamplerType::Random},
                       Case{"path", PixelFilterType::Gaussian, SamplerType::Sobol}}) {
    SCOPED_TRACE(c.integrator);
    IntegratorSettings settings;
    settings.spp = 4;
    settings.seed = 3;
    settings.filter = c.filter;
    settings.sampler = c.sampler;
    std::string error;
    WorkerPool pool1(1), pool2(2);
    const auto s = scene(pool1);
    ASSERT_TRUE(s);
    Film full(kW, kH, PixelRect{0, 0, kW, kH}, aovs);
    settings.tile_size = 16;
    make_integrator(c.integrator, settings, error)->render(*s, full, pool1);
    Film part(kW, kH, crop, aovs);
    settings.tile_size = 5;
    make_integrator(c.integrator, settings, error)->render(*s, part, pool2);

    const Image image = part.image();
    ASSERT_EQ(image.width, crop.width());
    ASSERT_EQ(image.height, crop.height());
    for (int y = crop.y0; y < crop.y1; ++y)
      for (int x = crop.x0; x < crop.x1; ++x) {
        EXPECT_EQ(part.pixel(x, y), full.pixel(x, y)) << x << "," << y;
        EXPECT_EQ(image.at(x - crop.x0, y - crop.y0), full.pixel(x, y));
        for (const AovRequest& r : aovs) EXPECT_EQ(part.aov_value(r.type, x, y), full.aov_value(r.type, x, y));
      }
    const LayeredImage layers = part.layers();
    EXPECT_EQ(layers.x, crop.x0);
    EXPECT_EQ(layers.y, crop.y0);
    EXPECT_EQ(layers.width, crop.width());
    EXPECT_EQ(layers.height, crop.height());
    EXPECT_EQ(layers.full_width, kW);
    EXPECT_EQ(layers.full_height, kH);
  }
}

TEST(Crop, IsClippedToTheFrame) {
  const Film film(10, 8, PixelRect{-3, 2, 50, 6});
  EXPECT_EQ(film.crop(), (PixelRect{0, 2, 10, 6}));
  EXPECT_EQ(film.image().width, 10);
  EXPECT_EQ(film.image().height, 4);
}

}  // namespace
}  // namespace pt
