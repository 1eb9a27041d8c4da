// The image of test_exr_bytes.cpp (and of the program that wrote its golden
// files with the writer before it): a crop of a frame, a float beauty and
// half and float layers, values that round, overflow and underflow in half.
#pragma once

#include <cmath>

#include "io/image_metadata.h"
#include "io/layered_image.h"

namespace pt::test {

inline float exr_bytes_value(std::size_t layer, std::size_t i) {
  const double x = std::sin(static_cast<double>(i) * 0.37 + static_cast<double>(layer) * 1.3);
  const std::size_t kind = (i + layer) % 7;
  return kind == 0   ? static_cast<float>(x * 7.0e4)     // beyond half's range
         : kind == 1 ? static_cast<float>(x * 1.0e-6)    // half subnormal
         : kind == 2 ? static_cast<float>(-x)            // negative
                     : static_cast<float>(x * x * 3.0);  // ordinary
}

inline LayeredImage exr_bytes_image() {
  LayeredImage image;
  image.full_width = 50;
  image.full_height = 30;
  image.x = 3;
  image.y = 5;
  image.width = 37;
  image.height = 21;
  image.layers.push_back({"", {"R", "G", "B", "A"}, ChannelType::Float, {}});
  image.layers.push_back({"albedo", {"albedo.R", "albedo.G", "albedo.B"}, ChannelType::Half, {}});
  image.layers.push_back({"Z", {"Z"}, ChannelType::Float, {}});
  image.layers.push_back({"N", {"N.X", "N.Y", "N.Z"}, ChannelType::Half, {}});
  for (std::size_t l = 0; l < image.layers.size(); ++l) {
    ImageLayer& layer = image.layers[l];
    layer.values.resize(image.pixel_count() * layer.channels.size());
    for (std::size_t i = 0; i < layer.values.size(); ++i) layer.values[i] = exr_bytes_value(l, i);
  }
  return image;
}

inline ImageMetadata exr_bytes_metadata() {
  ImageMetadata m;
  m.set("pathtracer:backend", "test");
  m.set("pathtracer:spp", 4);
  m.ints.emplace_back("pathtracer:seed", 7);
  m.floats.emplace_back("pathtracer:renderTime", 1.25f);
  m.matrices.emplace_back("worldToCamera", ImageMetadata::Matrix{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 2, 3, 4, 1});
  return m;
}

}  // namespace pt::test
