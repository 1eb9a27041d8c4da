#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include <Imath/half.h>
#include <gtest/gtest.h>

#include "io/exr_pack.h"

namespace pt {
namespace {

ImageLayer layer(std::size_t channels, ChannelType type) {
  return {"l", std::vector<std::string>(channels, "c"), type, {}};
}

// The packed bytes of `n` pixels, a channel at a time: each value as a
// float's bytes or Imath's half bits, the layers one after another.
std::vector<unsigned char> reference(const std::vector<ImageLayer>& layers, const std::vector<float>& values,
                                     std::size_t n) {
  std::vector<unsigned char> out;
  std::size_t channels = 0;
  for (const ImageLayer& l : layers) channels += l.channels.size();
  for (std::size_t x = 0; x < n; ++x) {
    std::size_t c = 0;
    for (const ImageLayer& l : layers)
      for (std::size_t k = 0; k < l.channels.size(); ++k, ++c) {
        const float v = values[x * channels + c];
        unsigned char bytes[4];
        std::size_t size = sizeof(float);
        if (l.type == ChannelType::Half) {
          const uint16_t bits = Imath::half(v).bits();
          std::memcpy(bytes, &bits, size = sizeof bits);
        } else {
          std::memcpy(bytes, &v, size);
        }
        out.insert(out.end(), bytes, bytes + size);
      }
  }
  return out;
}

// Values that exercise the rounding: ties, subnormals, overflow, infinities, NaN.
std::vector<float> values(std::size_t count) {
  const float special[] = {0.0f, -0.0f, 1.0f, 1.00048828125f, 65504.0f, 65520.0f, 1e6f, 5.96e-8f, 3e-8f, -2.5f,
                           std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity(),
                           std::numeric_limits<float>::quiet_NaN(), 0.1f, 1234.567f, -7e-5f};
  std::vector<float> v(count);
  for (std::size_t i = 0; i < count; ++i)
    v[i] = i < std::size(special) ? special[i] : std::sin(static_cast<float>(i)) * static_cast<float>(i % 97);
  return v;
}

TEST(ExrPack, PacksEveryLayoutAsAChannelByChannelConversion) {
  const std::vector<std::vector<ImageLayer>> cases = {
      {layer(4, ChannelType::Float), layer(3, ChannelType::Float), layer(1, ChannelType::Float)},  // floats: one copy
      {layer(4, ChannelType::Half), layer(3, ChannelType::Half)},
      {layer(4, ChannelType::Float), layer(3, ChannelType::Half), layer(1, ChannelType::Half),
       layer(4, ChannelType::Float), layer(2, ChannelType::Float), layer(1, ChannelType::Half)},
  };
  const std::size_t n = 37;
  for (const std::vector<ImageLayer>& layers : cases) {
    std::vector<const ImageLayer*> pointers;
    for (const ImageLayer& l : layers) pointers.push_back(&l);
    const PackedLayout layout = packed_layout(pointers);
    const std::vector<float> v = values(n * layout.channels);
    std::vector<unsigned char> packed(n * layout.pixel_bytes, 0xAB);
    pack_pixels(layout, v.data(), n, packed.data());
    const std::vector<unsigned char> expected = reference(layers, v, n);
    ASSERT_EQ(packed.size(), expected.size());
    EXPECT_EQ(packed, expected) << layers.size() << " layers";
  }
}

TEST(ExrPack, LayoutPlacesEachLayerAfterTheLast) {
  const std::vector<ImageLayer> layers = {layer(4, ChannelType::Float), layer(3, ChannelType::Half),
                                          layer(1, ChannelType::Float)};
  LayeredImage image;
  image.layers = layers;
  const PackedLayout layout = packed_layout(image);
  ASSERT_EQ(layout.layers.size(), 3u);
  EXPECT_EQ(layout.layers[1].offset, 16u);
  EXPECT_TRUE(layout.layers[1].half);
  EXPECT_EQ(layout.layers[2].offset, 22u);
  EXPECT_EQ(layout.pixel_bytes, 26u);
  EXPECT_EQ(layout.channels, 8u);
}

// pack_lines: each channel's values in its own line, at the line's place in
// the row, from pixel x on; halves as Imath rounds them (groups of 8 with and
// without a NaN, a tail shorter than 8), nothing outside the pixels written.
TEST(ExrPack, PacksLinesAsAChannelByChannelConversion) {
  const std::size_t channels = 5, width = 45, x = 3, n = 37;
  LineLayout layout;
  // Lines in another order than the values' channels, a gap of 8 bytes first.
  const std::size_t order[channels] = {3, 0, 4, 1, 2};
  const bool half[channels] = {false, true, true, false, true};
  layout.channels.resize(channels);
  std::size_t at = 8;
  for (const std::size_t c : order) {
    layout.channels[c] = {at, half[c]};
    at += (half[c] ? 2 : 4) * width;
  }
  layout.row_bytes = at;
  std::vector<float> v = values(n * channels);
  v[8 * channels + 2] = std::numeric_limits<float>::quiet_NaN();  // a NaN in channel 2's second group of 8
  v[9 * channels + 1] = std::numeric_limits<float>::signaling_NaN();
  std::vector<unsigned char> row(layout.row_bytes, 0xAB);
  pack_lines(layout, v.data(), x, n, row.data());
  std::vector<unsigned char> expected(layout.row_bytes, 0xAB);
  for (std::size_t c = 0; c < channels; ++c)
    for (std::size_t i = 0; i < n; ++i) {
      const float f = v[i * channels + c];
      unsigned char* to = expected.data() + layout.channels[c].line;
      if (half[c]) {
        const uint16_t bits = Imath::half(f).bits();
        std::memcpy(to + (x + i) * sizeof bits, &bits, sizeof bits);
      } else {
        std::memcpy(to + (x + i) * sizeof f, &f, sizeof f);
      }
    }
  EXPECT_EQ(row, expected);
}

}  // namespace
}  // namespace pt
