// A multi-layer image as written to one EXR file: a frame (the display window)
// and a data window inside it that holds the pixels, and named layers of
// channels, each stored as half or float. Pure data: the film fills it
// (render/film/film.h), the writers (io/image_io.h) read it.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace pt {

enum class ChannelType { Half, Float };

struct ImageLayer {
  std::string name;                   // "" for the beauty (channels R, G, B, A)
  std::vector<std::string> channels;  // full channel names, e.g. "albedo.R"
  ChannelType type = ChannelType::Float;
  // Interleaved values: (y * width + x) * channels.size() + c, row 0 at the top
  // of the data window.
  std::vector<float> values;
};

struct LayeredImage {
  int full_width = 0, full_height = 0;  // display window: (0,0) to (full_width-1, full_height-1)
  int x = 0, y = 0;                     // data window origin in the frame
  int width = 0, height = 0;            // data window size
  std::vector<ImageLayer> layers;       // layers[0] is the beauty
  std::size_t pixel_count() const { return static_cast<std::size_t>(width) * static_cast<std::size_t>(height); }
};

}  // namespace pt
