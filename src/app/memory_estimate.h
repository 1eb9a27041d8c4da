// Pre-flight memory estimate (docs/cli.md): before the scene is built and the
// film allocated, the bytes the render will need, compared with the physical
// memory and `--max-memory`.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "accel/accelerator.h"
#include "render/textures/texture.h"

namespace pt {

struct SceneDescription;

// The process's peak resident memory as the render will make it: what is
// resident when the estimate is made (measured), plus what the render will
// allocate (estimated), or the peak so far if that is higher (docs/cli.md,
// "Memory pre-flight"; tools/bench/memory compares it with measured peaks).
struct MemoryEstimate {
  uint64_t baseline = 0;  // resident when estimated: code, libraries, the parsed scene and its meshes (measured)
  uint64_t peak_so_far = 0;  // the process's peak until then (measured): the mesh import's buffers, freed since
  // Of the baseline, heap memory malloc holds free (measured, mallinfo2): the
  // mesh import's freed buffers, which the render's first allocations reuse
  // before the process grows.
  uint64_t reusable = 0;
  uint64_t film = 0;      // the film's sums over the crop window (+ a second film while --resume reads one)
  uint64_t images = 0;    // the output buffers: Film::layers() over the crop window and the largest writer's
  uint64_t textures = 0;  // textures materials use and the environment map, decoded, from their file headers
  uint64_t geometry = 0;  // the render scene's copy of the geometry and the acceleration structure with its build
  uint64_t runtime = 0;   // worker threads, the task scheduler, the image writers' buffers (a measured constant)
  uint64_t added() const;  // film + images + textures + geometry + runtime, saturating (a file header may claim any size)
  uint64_t total() const;  // max(peak_so_far, baseline + added() - reusable)
};

// The process's resident memory now (/proc/self/statm) and its peak so far
// (/proc/self/status VmHWM; getrusage's ru_maxrss keeps a forking parent's
// size across exec); 0 where unknown.
uint64_t resident_bytes();
uint64_t peak_resident_bytes();
// Bytes malloc holds free in its heaps (mallinfo2 fordblks), 0 where unknown.
uint64_t free_heap_bytes();

// What the render allocates for its film and its outputs: per pixel of its
// crop window, and the writer's buffer.
struct PixelBytes {
  uint64_t film = 0;    // per pixel, film_bytes_per_pixel(): sizeof(PixelSum) and the AOVs' sums
  uint64_t images = 0;  // per pixel, layer_bytes_per_pixel(): Film::layers()
  uint64_t writer = 0;  // in all, writer_bytes(): the largest output's own buffer (EXR: one band of rows)
};

// `pixels`: the pixels of the crop window (the frame without a crop);
// `films`: how many films exist at once; `accel`: the backend that will be
// built; `texture_cache_bytes`: --texture-cache. The baseline and the peak so
// far are left 0 (the caller measures them).
MemoryEstimate estimate_memory(const SceneDescription& scene, uint64_t pixels, const PixelBytes& per_pixel,
                               int films = 1, AccelKind accel = AccelKind::Bvh,
                               uint64_t texture_cache_bytes = TextureCache::kDefaultBytes);

// What building the render scene adds for the geometry on `accel`: the
// render scene's copy of every shape (meshes: their vertex, index, normal and
// uv arrays, exactly) and the acceleration structure at its build's peak
// (per-triangle and per-shape figures measured with tools/bench/memory).
uint64_t geometry_bytes(const SceneDescription& scene, AccelKind accel);

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
