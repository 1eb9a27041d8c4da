// Pixels packed as an EXR part stores them ("native" data: every channel in
// its file type, half or float, a pixel's channels one after another, in the
// part's channel order), for the EXR writer (imagelib/oiio/exr_writer.cpp),
// which hands such rows to OpenImageIO as they are, and for the streamed
// merge (app/shard_band_merge.cpp), which packs its resolved rows itself, so
// that only the file write needs the image module. Or packed in lines, as an
// uncompressed file stores a row (io/exr_uncompressed.h, LineLayout): each
// channel's values of the row one after another. Halves are rounded to
// nearest even, as OpenImageIO's conversion (Imath's) rounds them.
#pragma once

#include <cstddef>
#include <vector>

#include "io/layered_image.h"

namespace pt {

// One layer of a part as packed: its channels, where they go in a packed
// pixel (bytes from its start), and whether they are stored as half.
struct PackedLayer {
  std::size_t channels = 0, offset = 0;
  bool half = false;
};

// The layers of a part, in order, the bytes of a packed pixel and its channels.
struct PackedLayout {
  std::vector<PackedLayer> layers;
  std::size_t pixel_bytes = 0, channels = 0;
};

// Every layer of `image`, in order (a part holding them all).
std::vector<const ImageLayer*> every_layer(const LayeredImage& image);
// The bytes of one pixel of `layer` packed: its channels in its file type.
std::size_t packed_pixel_bytes(const ImageLayer& layer);

// The layout of a part holding `layers` (in order); only their channels and types are read.
PackedLayout packed_layout(const std::vector<const ImageLayer*>& layers);
// The layout of a part holding every layer of `image`.
PackedLayout packed_layout(const LayeredImage& image);

// `n` pixels of `channels` floats each into `out`, halves converted: pixel x
// reads `channels` floats at v + x * in_step and writes them at
// out + x * out_step, one after another.
void pack_halves(const float* v, std::size_t in_step, std::size_t channels, std::size_t n, unsigned char* out,
                 std::size_t out_step);
void pack_floats(const float* v, std::size_t in_step, std::size_t channels, std::size_t n, unsigned char* out,
                 std::size_t out_step);

// `n` pixels of `layout.channels` floats each (every layer's channels of a
// pixel one after another, in the layout's order) packed into `out`
// (n * layout.pixel_bytes bytes).
void pack_pixels(const PackedLayout& layout, const float* values, std::size_t n, unsigned char* out);

// One channel of a row packed in lines: where its line begins (bytes from the
// row's start) and whether it is stored as half.
struct LineChannel {
  std::size_t line = 0;
  bool half = false;
};

// A row packed in lines: per channel of a pixel's values (every layer's
// channels, in the layers' order, as pack_pixels reads them), its line; the
// bytes of a row (its lines and whatever else the row holds).
struct LineLayout {
  std::vector<LineChannel> channels;
  std::size_t row_bytes = 0;
};

// `n` pixels of `layout.channels.size()` floats each (as pack_pixels reads
// them), pixels x, x + 1, ... of a row, packed into that row's lines (`row`,
// its first byte): channel c of pixel x + i at row + line(c) + (x + i) * its
// bytes (2 half, 4 float).
void pack_lines(const LineLayout& layout, const float* values, std::size_t x, std::size_t n, unsigned char* row);

}  // namespace pt
