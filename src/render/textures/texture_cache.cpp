#include "render/textures/texture_cache.h"

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <system_error>

#include "core/file_access.h"
#include "imagelib/image_library.h"

namespace pt {

namespace fs = std::filesystem;

// The image module's texture system, made on the first open() (a cache that
// opens nothing loads nothing).
struct TextureCache::Impl {
  std::once_flag once;
  std::unique_ptr<TextureSystem> textures;
  std::string error;  // why there is none

  // The texture system, made on the first call; nullptr and `why` if the
  // image module cannot be loaded.
  TextureSystem* system(uint64_t max_bytes, std::string& why) {
    std::call_once(once, [&] {
      if (const ImageLibrary* lib = image_library(error)) textures = lib->texture_system(max_bytes);
    });
    if (!textures) why = error;
    return textures.get();
  }
};

namespace {

// The maketx output beside `path` (same stem, extension .tx), if there is one
// no older than the image; a stale one is named in `warning`.
std::string tiled_version(const std::string& path, std::string& warning) {
  const fs::path source(path);
  if (source.extension() == ".tx") return path;
  fs::path tx = source;
  tx.replace_extension(".tx");
  std::error_code ec;
  if (!fs::is_regular_file(tx, ec)) return path;
  const auto tx_time = fs::last_write_time(tx, ec);
  if (ec) return path;
  const auto source_time = fs::last_write_time(source, ec);
  if (!ec && tx_time < source_time) {
    warning = tx.string();
    warning += " is older than the image and is not used (run maketx again)";
    return path;
  }
  return tx.string();
}

// The header of `file`: its size checked against `limits` before anything is decoded.
bool read_header(const ImageLibrary& lib, const std::string& file, const TextureLimits& limits, ImageHeader& spec,
                 std::string& error) {
  if (const std::string why = why_unreadable(file); !why.empty()) {
    error = "cannot open the file: " + why;
    return false;
  }
  const std::unique_ptr<ImageReader> in = lib.open(file, false, error);
  if (!in) return false;
  spec = in->header();
  return limits.check(spec.width, spec.height, spec.nchannels, spec.depth, error);
}

// The first line of an OpenImageIO error (its later lines repeat it for every
// MIP level), without the name the cache knows a decoded file by.
std::string first_line(std::string error) {
  if (const std::size_t eol = error.find('\n'); eol != std::string::npos) error.resize(eol);
  for (std::size_t at; (at = error.find(kSrgbDecodedSuffix)) != std::string::npos;) error.erase(at, std::strlen(kSrgbDecodedSuffix));
  return error.empty() ? std::string("cannot decode image") : error;
}

LookupOptions options(const CachedImage& image, int first) {
  LookupOptions opt;
  opt.first_channel = first;
  switch (image.wrap) {
    case TextureWrap::Repeat: opt.wrap = LookupWrap::Repeat; break;
    case TextureWrap::Clamp: opt.wrap = LookupWrap::Clamp; break;
    case TextureWrap::Black: opt.wrap = LookupWrap::Black; break;
    case TextureWrap::Mirror: opt.wrap = LookupWrap::Mirror; break;
  }
  switch (image.filter) {
    case TextureFilter::Point: opt.filter = LookupFilter::Point; break;
    case TextureFilter::Bilinear: opt.filter = LookupFilter::Bilinear; break;
    case TextureFilter::Trilinear: opt.filter = LookupFilter::Trilinear; break;
    case TextureFilter::Anisotropic: opt.filter = LookupFilter::Anisotropic; break;
  }
  return opt;
}

}  // namespace

TextureCache::TextureCache(uint64_t max_bytes) : impl_(std::make_unique<Impl>()), max_bytes_(max_bytes) {}

TextureCache::~TextureCache() = default;

bool TextureCache::open(const std::string& path, bool raw, TextureFilter filter, TextureWrap wrap,
                        const TextureLimits& limits, OpenedImage& out, std::string& error) const {
  // Also when the image module cannot be loaded: the error names it.
  TextureSystem* textures = impl_->system(max_bytes_, error);
  if (textures == nullptr) return false;
  const ImageLibrary& lib = *loaded_image_library();
  ImageHeader spec;
  if (!read_header(lib, path, limits, spec, error)) return false;
  const std::string file = tiled_version(path, out.warning);
  if (file != path && !read_header(lib, file, limits, spec, error)) {
    error = "'" + file + "': " + error;
    return false;
  }
  CachedImage& img = out.image;
  img.cache = this;
  std::string why;
  img.handle = textures->handle(file, !raw && spec.srgb_encoded, why);
  img.channels = spec.nchannels;
  img.alpha_channel = spec.alpha_channel;
  img.filter = filter;
  img.wrap = wrap;
  img.file = file;
  // The coarsest level: every texel of an image the cache makes levels for.
  LookupOptions opt = options(img, 0);
  opt.one_level = true;
  float probe[4];
  const int n = std::min(img.channels, 4);
  if (img.handle == nullptr) {
    error = first_line(why);
    return false;
  }
  if (!textures->lookup(img.handle, opt, 0.5f, 0.5f, 1.0f, 0.0f, 0.0f, 1.0f, n, probe)) {
    error = first_line(textures->error());
    return false;
  }
  return true;
}

void TextureCache::lookup(const CachedImage& image, Vec2f st, Vec2f dstdx, Vec2f dstdy, int first, int n,
                          float* out) const {
  const TextureSystem& textures = *impl_->textures;  // an image was opened, so there is one
  if (textures.lookup(image.handle, options(image, first), st.x, st.y, dstdx.x, dstdx.y, dstdy.x, dstdy.y, n, out))
    return;
  for (int i = 0; i < n; ++i) out[i] = 0.0f;
  record_failure(image.file + ": " + first_line(textures.error()));
}

void TextureCache::record_failure(const std::string& what) const {
  if (failed_.load(std::memory_order_acquire)) return;
  const std::lock_guard<std::mutex> lock(failure_mutex_);
  if (failure_.empty()) failure_ = what;
  failed_.store(true, std::memory_order_release);
}

std::string TextureCache::failure() const {
  if (!failed_.load(std::memory_order_acquire)) return {};
  const std::lock_guard<std::mutex> lock(failure_mutex_);
  return failure_;
}

std::string TextureCache::statistics(int level) const {
  std::string error;
  const TextureSystem* textures = impl_->system(max_bytes_, error);
  return textures != nullptr ? textures->statistics(level) : error;
}

}  // namespace pt
