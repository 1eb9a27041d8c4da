// Pre-flight memory estimate (docs/cli.md): before the scene is built and the
// film allocated, the bytes the render will need, compared with the physical
// memory and `--max-memory`.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "render/textures/texture.h"

namespace pt {

struct SceneDescription;

struct MemoryEstimate {
  uint64_t film = 0;      // the film's sums over the crop window (+ a second film while --resume reads one)
  uint64_t images = 0;    // the output buffers over the crop window: Film::layers() and the largest writer's
  uint64_t textures = 0;  // textures materials use and the environment map, decoded, from their file headers
  uint64_t geometry = 0;  // scene geometry and acceleration structure, from primitive counts
  uint64_t total() const;  // saturating (a file header may claim any size)
};

// What the render allocates per pixel of its crop window.
struct PixelBytes {
  uint64_t film = 0;    // film_bytes_per_pixel(): sizeof(PixelSum) and the AOVs' doubles
  uint64_t images = 0;  // output_bytes_per_pixel(): the layers and the largest output conversion
};

// `pixels`: the pixels of the crop window (the frame without a crop);
// `films`: how many films exist at once; `texture_cache_bytes`: --texture-cache.
MemoryEstimate estimate_memory(const SceneDescription& scene, uint64_t pixels, const PixelBytes& per_pixel,
                               int films = 1, uint64_t texture_cache_bytes = TextureCache::kDefaultBytes);

// The memory of the image textures some material uses, of the environment map
// and of the background image, from their files' headers (OpenImageIO, nothing
// is decoded): a material's images live in the texture cache, which holds at
// most their MIP pyramids (4/3 of the finest level, counted at 4 bytes a
// channel) and at most `cache_bytes`; the environment map and the background
// image are decoded into memory, 12 bytes a texel (float RGB) and 12 more for
// the environment map's sampling distribution; and the largest file's float
// decode buffer (4 bytes per channel per texel), which exists while that file
// is read. A file that cannot be opened counts 0 (the build reports it), and so
// does one the loader refuses under `limits` (TextureLimits::admit: the build
// reports it too, before decoding).
uint64_t texture_bytes(const SceneDescription& scene, const TextureLimits& limits = {},
                       uint64_t cache_bytes = TextureCache::kDefaultBytes);

// "4G", "512M", "64k", "1000" (bytes; K/M/G/T are powers of 1024, an optional
// trailing "B"/"iB" is accepted). std::nullopt for anything else.
std::optional<uint64_t> parse_byte_size(const std::string& text);
std::string byte_size_text(uint64_t bytes);  // "1.50 GiB"

// Physical memory (sysconf), 0 if unknown.
uint64_t physical_memory_bytes();

// An error message when `estimate` exceeds `limit` (0: no limit) or the
// physical memory; empty otherwise.
std::string check_memory(const MemoryEstimate& estimate, uint64_t limit, uint64_t physical);

}  // namespace pt
