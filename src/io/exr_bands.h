// How many rows the EXR writer packs and writes at a time (one band), for
// the writer (imagelib/oiio/exr_writer.cpp), which holds one band of packed
// rows per part, and for the memory pre-flight (app/film_options.cpp,
// docs/cli.md "Memory pre-flight"), which counts that band and OpenEXR's line
// buffers beside it. Pure arithmetic.
#pragma once

#include <algorithm>
#include <cstddef>
#include <string_view>

namespace pt {

// About this many bytes of packed rows are written at a time.
inline constexpr std::size_t kExrBandBytes = std::size_t{32} << 20;

// The rows of a band of a part whose packed rows (every channel in its file
// type, half or float) are `row_bytes` long, in an image `height` rows high:
// whole blocks of 32 rows (zip's 16, piz's 32), so that OpenEXR compresses a
// band's blocks in parallel, at least one block, at most the image.
constexpr int exr_band_rows(std::size_t row_bytes, int height) {
  const std::size_t rows = std::max<std::size_t>(32, kExrBandBytes / std::max<std::size_t>(1, row_bytes) / 32 * 32);
  return rows >= static_cast<std::size_t>(std::max(0, height)) ? height : static_cast<int>(rows);
}

// The bytes of that band: what the writer holds for a part whose packed
// pixel is `pixel_bytes` long, in an image of `width` x `height` pixels.
constexpr std::size_t exr_band_bytes(std::size_t pixel_bytes, int width, int height) {
  const std::size_t row_bytes = pixel_bytes * static_cast<std::size_t>(std::max(0, width));
  return row_bytes * static_cast<std::size_t>(std::max(0, exr_band_rows(row_bytes, height)));
}

// The rows OpenEXR compresses as one block with `compression` (a name of
// exr_compression_names(), "dwaa:45" with its level): 1 for none, rle and
// zips, 16 for zip and pxr24, 32 for piz, b44, b44a and dwaa, 256 for dwab.
constexpr int exr_block_rows(std::string_view compression) {
  const std::string_view name = compression.substr(0, compression.find(':'));
  if (name == "zip" || name == "pxr24") return 16;
  if (name == "piz" || name == "b44" || name == "b44a" || name == "dwaa") return 32;
  if (name == "dwab") return 256;
  return 1;
}

// What OpenEXR's scanline writer holds beside the band, for parts whose
// packed rows are `row_bytes` long together (each part has its own, all
// alive until the file is closed): two line buffers per compression thread
// (`threads`, at least one buffer, and no more than the image's blocks), each
// a block of raw rows, the compressor's reordered copy of it and its output
// (at most as large): three blocks' rows per buffer. An upper bound: the
// output is the compressed size (measured: 2.1 to 2.4 blocks a buffer with
// zip, docs/cli.md).
constexpr std::size_t exr_line_buffer_bytes(std::size_t row_bytes, int height, int block_rows, int threads) {
  const int rows = std::max(1, block_rows);
  const std::size_t blocks = static_cast<std::size_t>((std::max(0, height) + rows - 1) / rows);
  const std::size_t buffers = std::min(blocks, static_cast<std::size_t>(std::max(1, 2 * threads)));
  return buffers * 3 * static_cast<std::size_t>(rows) * row_bytes;
}

}  // namespace pt
