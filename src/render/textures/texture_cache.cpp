#include "render/textures/texture_cache.h"

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <system_error>

#include <OpenImageIO/imagecache.h>
#include <OpenImageIO/imageio.h>
#include <OpenImageIO/texture.h>
#include <tbb/enumerable_thread_specific.h>

#include "core/file_access.h"
#include "render/textures/srgb_input.h"

namespace pt {

namespace fs = std::filesystem;

// Each thread's OpenImageIO state for this cache (its tile microcache, its
// map of file names) is created here and destroyed with the cache, never left
// to OpenImageIO's thread-specific pointer: in OpenImageIO 2.4 that pointer is
// a member of the cache keyed by the cache's address, and the entries of
// threads other than the destroying one outlive the cache. A thread pool's
// worker then handed its stale state, still holding tiles, to the next cache
// allocated at the same address, and a later cache's tile accounting went
// negative (an abort in ImageCacheImpl::decr_tiles; docs/textures.md).
using Perthread = OIIO::TextureSystem::Perthread;

struct TextureCache::Impl {
  OIIO::ImageCache* images = nullptr;
  OIIO::TextureSystem* textures = nullptr;
  tbb::enumerable_thread_specific<Perthread*> perthread{nullptr};

  // The calling thread's state, created on its first lookup.
  Perthread* thread_info() {
    Perthread*& p = perthread.local();
    if (p == nullptr) p = textures->create_thread_info();
    return p;
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
bool read_header(const std::string& file, const TextureLimits& limits, OIIO::ImageSpec& spec, std::string& error) {
  if (const std::string why = why_unreadable(file); !why.empty()) {
    error = "cannot open the file: " + why;
    return false;
  }
  auto in = OIIO::ImageInput::open(file);
  if (!in) {
    error = OIIO::geterror();
    if (error.empty()) error = "cannot open image";
    return false;
  }
  spec = in->spec();
  return limits.check(spec.width, spec.height, spec.nchannels, spec.depth, error);
}

// The first line of an OpenImageIO error (its later lines repeat it for every
// MIP level), without the name the cache knows a decoded file by.
std::string first_line(std::string error) {
  if (const std::size_t eol = error.find('\n'); eol != std::string::npos) error.resize(eol);
  for (std::size_t at; (at = error.find(kSrgbSuffix)) != std::string::npos;) error.erase(at, std::strlen(kSrgbSuffix));
  return error.empty() ? std::string("cannot decode image") : error;
}

OIIO::TextureOpt::Wrap oiio_wrap(TextureWrap w) {
  switch (w) {
    case TextureWrap::Repeat: return OIIO::TextureOpt::WrapPeriodic;
    case TextureWrap::Clamp: return OIIO::TextureOpt::WrapClamp;
    case TextureWrap::Black: return OIIO::TextureOpt::WrapBlack;
    case TextureWrap::Mirror: return OIIO::TextureOpt::WrapMirror;
  }
  return OIIO::TextureOpt::WrapPeriodic;
}

OIIO::TextureOpt options(const CachedImage& image, int first) {
  OIIO::TextureOpt opt;
  opt.firstchannel = first;
  opt.swrap = opt.twrap = oiio_wrap(image.wrap);
  opt.interpmode = OIIO::TextureOpt::InterpBilinear;
  switch (image.filter) {
    case TextureFilter::Point:
      opt.interpmode = OIIO::TextureOpt::InterpClosest;
      opt.mipmode = OIIO::TextureOpt::MipModeNoMIP;
      break;
    case TextureFilter::Bilinear: opt.mipmode = OIIO::TextureOpt::MipModeNoMIP; break;
    case TextureFilter::Trilinear: opt.mipmode = OIIO::TextureOpt::MipModeTrilinear; break;
    case TextureFilter::Anisotropic: opt.mipmode = OIIO::TextureOpt::MipModeAniso; break;
  }
  return opt;
}

}  // namespace

TextureCache::TextureCache(uint64_t max_bytes) : impl_(std::make_unique<Impl>()), max_bytes_(max_bytes) {
  impl_->images = OIIO::ImageCache::create(/*shared=*/false);
  OIIO::ImageCache& ic = *impl_->images;
  ic.attribute("max_memory_MB", static_cast<float>(static_cast<double>(max_bytes) / (1024.0 * 1024.0)));
  ic.attribute("autotile", 64);        // images without tiles are cached in 64 x 64 tiles,
  ic.attribute("automip", 1);          // and given MIP levels made from their finest one
  ic.attribute("unassociatedalpha", 1);  // colour is not multiplied by alpha
  ic.attribute("deduplicate", 0);      // the decoded and the raw view of one file are two images
  ic.attribute("max_errors_per_file", 1);
  impl_->textures = OIIO::TextureSystem::create(/*shared=*/false, impl_->images);
}

TextureCache::~TextureCache() {
  for (Perthread* p : impl_->perthread)
    if (p != nullptr) impl_->textures->destroy_thread_info(p);
  OIIO::TextureSystem::destroy(impl_->textures);
  OIIO::ImageCache::destroy(impl_->images);
}

bool TextureCache::open(const std::string& path, bool raw, TextureFilter filter, TextureWrap wrap,
                        const TextureLimits& limits, OpenedImage& out, std::string& error) const {
  OIIO::ImageSpec spec;
  if (!read_header(path, limits, spec, error)) return false;
  const std::string file = tiled_version(path, out.warning);
  if (file != path && !read_header(file, limits, spec, error)) {
    error = "'" + file + "': " + error;
    return false;
  }
  std::string name = file;
  if (!raw && srgb_encoded(spec)) {
    name += kSrgbSuffix;
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    impl_->images->add_file(OIIO::ustring(name), create_srgb_decoding_input, &config);
  }
  CachedImage& img = out.image;
  img.cache = this;
  Perthread* const thread_info = impl_->thread_info();
  img.handle = impl_->textures->get_texture_handle(OIIO::ustring(name), thread_info);
  img.channels = spec.nchannels;
  img.alpha_channel = spec.alpha_channel;
  img.filter = filter;
  img.wrap = wrap;
  img.file = file;
  // The coarsest level: every texel of an image the cache makes levels for.
  OIIO::TextureOpt opt = options(img, 0);
  opt.mipmode = OIIO::TextureOpt::MipModeOneLevel;
  float probe[4];
  const int n = std::min(img.channels, 4);
  if (img.handle == nullptr ||
      !impl_->textures->texture(static_cast<OIIO::TextureSystem::TextureHandle*>(img.handle), thread_info, opt, 0.5f,
                                0.5f, 1.0f, 0.0f, 0.0f, 1.0f, n, probe)) {
    error = first_line(impl_->textures->geterror());
    return false;
  }
  return true;
}

void TextureCache::lookup(const CachedImage& image, Vec2f st, Vec2f dstdx, Vec2f dstdy, int first, int n,
                          float* out) const {
  OIIO::TextureOpt opt = options(image, first);
  if (impl_->textures->texture(static_cast<OIIO::TextureSystem::TextureHandle*>(image.handle), impl_->thread_info(), opt, st.x,
                               st.y, dstdx.x, dstdx.y, dstdy.x, dstdy.y, n, out))
    return;
  for (int i = 0; i < n; ++i) out[i] = 0.0f;
  record_failure(image.file + ": " + first_line(impl_->textures->geterror()));
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

std::string TextureCache::statistics(int level) const { return impl_->textures->getstats(level); }

}  // namespace pt
