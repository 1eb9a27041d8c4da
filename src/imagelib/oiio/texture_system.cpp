#include "imagelib/oiio/texture_system.h"

#include <OpenImageIO/imagecache.h>
#include <OpenImageIO/imageio.h>
#include <OpenImageIO/texture.h>
#include <tbb/enumerable_thread_specific.h>

#include "imagelib/oiio/srgb_input.h"

namespace pt {
namespace {

OIIO::TextureOpt::Wrap oiio_wrap(LookupWrap w) {
  switch (w) {
    case LookupWrap::Repeat: return OIIO::TextureOpt::WrapPeriodic;
    case LookupWrap::Clamp: return OIIO::TextureOpt::WrapClamp;
    case LookupWrap::Black: return OIIO::TextureOpt::WrapBlack;
    case LookupWrap::Mirror: return OIIO::TextureOpt::WrapMirror;
  }
  return OIIO::TextureOpt::WrapPeriodic;
}

OIIO::TextureOpt texture_options(const LookupOptions& o) {
  OIIO::TextureOpt opt;
  opt.firstchannel = o.first_channel;
  opt.swrap = opt.twrap = oiio_wrap(o.wrap);
  opt.interpmode = OIIO::TextureOpt::InterpBilinear;
  switch (o.filter) {
    case LookupFilter::Point:
      opt.interpmode = OIIO::TextureOpt::InterpClosest;
      opt.mipmode = OIIO::TextureOpt::MipModeNoMIP;
      break;
    case LookupFilter::Bilinear: opt.mipmode = OIIO::TextureOpt::MipModeNoMIP; break;
    case LookupFilter::Trilinear: opt.mipmode = OIIO::TextureOpt::MipModeTrilinear; break;
    case LookupFilter::Anisotropic: opt.mipmode = OIIO::TextureOpt::MipModeAniso; break;
  }
  if (o.one_level) opt.mipmode = OIIO::TextureOpt::MipModeOneLevel;
  return opt;
}

// Each thread's OpenImageIO state for this cache (its tile microcache, its map
// of file names) is created here and destroyed with the cache, never left to
// OpenImageIO's thread-specific pointer: in OpenImageIO 2.4 that pointer is a
// member of the cache keyed by the cache's address, and the entries of threads
// other than the destroying one outlive the cache. A thread pool's worker then
// handed its stale state, still holding tiles, to the next cache allocated at
// the same address, and a later cache's tile accounting went negative (an
// abort in ImageCacheImpl::decr_tiles; docs/textures.md).
using Perthread = OIIO::TextureSystem::Perthread;

class OiioTextureSystem final : public TextureSystem {
 public:
  explicit OiioTextureSystem(uint64_t max_bytes) {
    images_ = OIIO::ImageCache::create(/*shared=*/false);
    OIIO::ImageCache& ic = *images_;
    ic.attribute("max_memory_MB", static_cast<float>(static_cast<double>(max_bytes) / (1024.0 * 1024.0)));
    ic.attribute("autotile", 64);          // images without tiles are cached in 64 x 64 tiles,
    ic.attribute("automip", 1);            // and given MIP levels made from their finest one
    ic.attribute("unassociatedalpha", 1);  // colour is not multiplied by alpha
    ic.attribute("deduplicate", 0);        // the decoded and the raw view of one file are two images
    ic.attribute("max_errors_per_file", 1);
    textures_ = OIIO::TextureSystem::create(/*shared=*/false, images_);
  }
  ~OiioTextureSystem() override {
    for (Perthread* p : perthread_)
      if (p != nullptr) textures_->destroy_thread_info(p);
    OIIO::TextureSystem::destroy(textures_);
    OIIO::ImageCache::destroy(images_);
  }
  OiioTextureSystem(const OiioTextureSystem&) = delete;
  OiioTextureSystem& operator=(const OiioTextureSystem&) = delete;

  void* handle(const std::string& file, bool srgb_decode, std::string& error) override {
    std::string name = file;
    if (srgb_decode) {
      name += kSrgbDecodedSuffix;
      OIIO::ImageSpec config;
      config.attribute("oiio:UnassociatedAlpha", 1);
      images_->add_file(OIIO::ustring(name), create_srgb_decoding_input, &config);
    }
    void* h = textures_->get_texture_handle(OIIO::ustring(name), thread_info());
    if (h == nullptr) error = textures_->geterror();
    return h;
  }

  bool lookup(void* handle, const LookupOptions& options, float s, float t, float dsdx, float dtdx, float dsdy,
              float dtdy, int n, float* out) const override {
    OIIO::TextureOpt opt = texture_options(options);
    return textures_->texture(static_cast<OIIO::TextureSystem::TextureHandle*>(handle), thread_info(), opt, s, t, dsdx,
                              dtdx, dsdy, dtdy, n, out);
  }

  std::string error() const override { return textures_->geterror(); }
  std::string statistics(int level) const override { return textures_->getstats(level); }

 private:
  // The calling thread's state, created on its first lookup.
  Perthread* thread_info() const {
    Perthread*& p = perthread_.local();
    if (p == nullptr) p = textures_->create_thread_info();
    return p;
  }

  OIIO::ImageCache* images_ = nullptr;
  OIIO::TextureSystem* textures_ = nullptr;
  mutable tbb::enumerable_thread_specific<Perthread*> perthread_{nullptr};
};

}  // namespace

std::unique_ptr<TextureSystem> make_texture_system(uint64_t max_bytes) {
  return std::make_unique<OiioTextureSystem>(max_bytes);
}

}  // namespace pt
