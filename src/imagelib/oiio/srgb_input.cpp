#include "imagelib/oiio/srgb_input.h"

#include <cmath>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include <OpenImageIO/half.h>

#include "core/srgb.h"
#include "imagelib/image_library.h"

namespace pt {

bool srgb_encoded(const OIIO::ImageSpec& spec) {
  if (spec.format.is_floating_point()) return false;
  const std::string cs = spec.get_string_attribute("oiio:ColorSpace");
  return !(cs == "Linear" || cs == "linear" || cs == "lin_srgb" || cs == "scene_linear");
}

namespace {

// Delegates to the real reader of the file and converts every scanline or
// tile it reads. Its spec is the file's with format half and a linear colour
// space; tiles, MIP levels and subimages are the file's own.
class SrgbDecodingInput final : public OIIO::ImageInput {
 public:
  const char* format_name() const override { return "pt-srgb-decoded"; }
  int supports(OIIO::string_view feature) const override { return inner_ ? inner_->supports(feature) : 0; }

  bool open(const std::string& name, OIIO::ImageSpec& newspec) override {
    const OIIO::ImageSpec config;
    return open(name, newspec, config);
  }
  bool open(const std::string& name, OIIO::ImageSpec& newspec, const OIIO::ImageSpec& config) override {
    const std::size_t n = std::strlen(kSrgbDecodedSuffix);
    const std::string file = name.size() > n ? name.substr(0, name.size() - n) : name;
    inner_ = OIIO::ImageInput::open(file, &config);
    if (!inner_) {
      errorfmt("{}", OIIO::geterror());
      return false;
    }
    adopt_spec();
    newspec = m_spec;
    return true;
  }
  bool close() override {
    inner_.reset();
    return true;
  }
  int current_subimage() const override { return inner_ ? inner_->current_subimage() : 0; }
  int current_miplevel() const override { return inner_ ? inner_->current_miplevel() : 0; }
  bool seek_subimage(int subimage, int miplevel) override {
    if (!inner_) return false;
    if (subimage == current_subimage() && miplevel == current_miplevel()) return true;
    if (!inner_->seek_subimage(subimage, miplevel)) {
      errorfmt("{}", inner_->geterror());
      return false;
    }
    adopt_spec();
    return true;
  }

  bool read_native_scanline(int subimage, int miplevel, int y, int z, void* data) override {
    return read_native_scanlines(subimage, miplevel, y, y + 1, z, data);
  }
  bool read_native_scanlines(int subimage, int miplevel, int ybegin, int yend, int z, void* data) override {
    if (!seek_subimage(subimage, miplevel)) return false;
    const OIIO::ImageSpec& s = inner_->spec();
    const std::size_t values = static_cast<std::size_t>(yend - ybegin) * s.width * s.nchannels;
    std::vector<float> f(values);
    if (!inner_->read_scanlines(subimage, miplevel, ybegin, yend, z, 0, s.nchannels, OIIO::TypeDesc::FLOAT,
                                f.data())) {
      errorfmt("{}", inner_->geterror());
      return false;
    }
    decode(f, data);
    return true;
  }
  bool read_native_tile(int subimage, int miplevel, int x, int y, int z, void* data) override {
    if (!seek_subimage(subimage, miplevel)) return false;
    const OIIO::ImageSpec& s = inner_->spec();
    const std::size_t values = static_cast<std::size_t>(s.tile_pixels()) * s.nchannels;
    std::vector<float> f(values);
    if (!inner_->read_tile(x, y, z, OIIO::TypeDesc::FLOAT, f.data())) {
      errorfmt("{}", inner_->geterror());
      return false;
    }
    decode(f, data);
    return true;
  }

 private:
  void adopt_spec() {
    m_spec = inner_->spec();
    m_spec.set_format(OIIO::TypeDesc::HALF);
    m_spec.channelformats.clear();
    m_spec.attribute("oiio:ColorSpace", "Linear");
  }
  // Colour channels through the sRGB curve (clamped to [0, 1] first: integer
  // files hold nothing else), alpha as it is; to half.
  void decode(const std::vector<float>& f, void* data) const {
    const int nc = m_spec.nchannels, alpha = m_spec.alpha_channel;
    auto* out = static_cast<half*>(data);
    for (std::size_t i = 0; i < f.size(); ++i) {
      const int c = static_cast<int>(i % static_cast<std::size_t>(nc));
      const float v = std::fmin(std::fmax(f[i], 0.0f), 1.0f);
      out[i] = half(c == alpha ? f[i] : srgb_to_linear(v));
    }
  }

  std::unique_ptr<OIIO::ImageInput> inner_;
};

}  // namespace

OIIO::ImageInput* create_srgb_decoding_input() { return new SrgbDecodingInput; }

}  // namespace pt
