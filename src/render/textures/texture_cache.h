// Image textures through OpenImageIO's TextureSystem (docs/textures.md): MIP
// maps (a file's own, or levels the cache makes from the finest), tiles read
// when a lookup needs them and kept in a cache of bounded size, filtered
// lookups over a footprint. One TextureCache per render scene (no shared,
// global cache), owned by it and alive as long as its textures.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>

#include "core/math.h"
#include "render/textures/texture_limits.h"
#include "scene/scene_description.h"

namespace pt {

class TextureCache;

// One image as the cache knows it: what a lookup needs.
struct CachedImage {
  const TextureCache* cache = nullptr;
  void* handle = nullptr;  // OIIO::TextureSystem::TextureHandle
  int channels = 0;        // in the file: 1 grey, 2 grey + alpha, 3 RGB, 4 RGBA, ...
  int alpha_channel = -1;  // -1: none
  TextureFilter filter = TextureFilter::Anisotropic;
  TextureWrap wrap = TextureWrap::Repeat;
  std::string file;        // the file the cache reads (the .tx, if one was used)
};

// What opening an image told the caller besides its result.
struct OpenedImage {
  CachedImage image;
  std::string warning;  // e.g. a .tx older than its image, not used
};

class TextureCache {
 public:
  // The default size of the tile cache (OpenImageIO's own default).
  static constexpr uint64_t kDefaultBytes = uint64_t{256} << 20;

  explicit TextureCache(uint64_t max_bytes = kDefaultBytes);
  ~TextureCache();
  TextureCache(const TextureCache&) = delete;
  TextureCache& operator=(const TextureCache&) = delete;

  // Opens `path` for lookups. A tiled, MIP-mapped `<stem>.tx` beside it (maketx's
  // output) is used instead when there is one no older than the image. The size
  // the file declares is checked against `limits` first (nothing is decoded
  // for a file beyond them), then the coarsest level is read, which for an
  // image without MIP levels reads every texel, so that a truncated or corrupt
  // image is refused here, not in the middle of a render. `raw`: texel values
  // as stored; otherwise integer images are sRGB-decoded unless the file says
  // it is linear (float images are linear). Returns false and fills `error`.
  bool open(const std::string& path, bool raw, TextureFilter filter, TextureWrap wrap, const TextureLimits& limits,
            OpenedImage& out, std::string& error) const;

  // `n` channels from `first` at (s, t) over the footprint (dsdx, dtdx),
  // (dsdy, dtdy) (zero: a point lookup). Thread-safe. A read failure (a file
  // changed or broken since it was opened) gives zeros and is remembered
  // (failure()).
  void lookup(const CachedImage& image, Vec2f st, Vec2f dstdx, Vec2f dstdy, int first, int n, float* out) const;

  // The first lookup failure of the render, empty if there was none.
  std::string failure() const;
  // OpenImageIO's statistics report (level 1..5).
  std::string statistics(int level = 1) const;
  uint64_t max_bytes() const { return max_bytes_; }

 private:
  void record_failure(const std::string& what) const;

  struct Impl;
  std::unique_ptr<Impl> impl_;
  uint64_t max_bytes_;
  mutable std::atomic<bool> failed_{false};
  mutable std::mutex failure_mutex_;
  mutable std::string failure_;
};

}  // namespace pt
