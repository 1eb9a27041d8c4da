#include "imagelib/oiio/srgb_input.h"

#include <cmath>
#include <cstdint>
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
    return read_decoded(values, data, [&](OIIO::TypeDesc type, void* buffer) {
      return inner_->read_scanlines(subimage, miplevel, ybegin, yend, z, 0, s.nchannels, type, buffer);
    });
  }
  bool read_native_tile(int subimage, int miplevel, int x, int y, int z, void* data) override {
    if (!seek_subimage(subimage, miplevel)) return false;
    const std::size_t values = static_cast<std::size_t>(inner_->spec().tile_pixels()) * inner_->spec().nchannels;
    return read_decoded(values, data,
                        [&](OIIO::TypeDesc type, void* buffer) { return inner_->read_tile(x, y, z, type, buffer); });
  }

 private:
  void adopt_spec() {
    m_spec = inner_->spec();
    m_spec.set_format(OIIO::TypeDesc::HALF);
    m_spec.channelformats.clear();
    m_spec.attribute("oiio:ColorSpace", "Linear");
    make_tables(inner_->spec());
  }

  // 8- and 16-bit files are decoded through tables of every stored value
  // (their float values converted by OpenImageIO as read_tile would, then
  // the curve), so each texel costs a table read instead of a pow: the same
  // halves, 20 times faster (docs/bench/texture-memory.md).
  void make_tables(const OIIO::ImageSpec& s) {
    const bool tabled = s.channelformats.empty() && (s.format == OIIO::TypeDesc::UINT8 || s.format == OIIO::TypeDesc::UINT16);
    if (!tabled) {
      stored_ = OIIO::TypeDesc::FLOAT;
      colour_.clear();
      alpha_.clear();
      return;
    }
    if (s.format == stored_ && !colour_.empty()) return;
    stored_ = s.format;
    const std::size_t n = s.format == OIIO::TypeDesc::UINT8 ? 256 : 65536;
    std::vector<unsigned char> stored(n * s.format.size());
    for (std::size_t i = 0; i < n; ++i) {
      if (n == 256) {
        stored[i] = static_cast<unsigned char>(i);
      } else {
        const auto code = static_cast<uint16_t>(i);
        std::memcpy(&stored[2 * i], &code, 2);
      }
    }
    std::vector<float> f(n);
    OIIO::convert_pixel_values(s.format, stored.data(), OIIO::TypeDesc::FLOAT, f.data(), static_cast<int>(n));
    colour_.resize(n);
    alpha_.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      colour_[i] = decode_colour(f[i]);
      alpha_[i] = half(f[i]);
    }
  }

  static half decode_colour(float v) { return half(srgb_to_linear(std::fmin(std::fmax(v, 0.0f), 1.0f))); }

  // `values` channel values read by read(type, buffer) in the type the
  // tables take (else float), decoded into `data`: colour channels through
  // the sRGB curve (clamped to [0, 1] first: integer files hold nothing
  // else), alpha as it is; to half.
  template <typename Read>
  bool read_decoded(std::size_t values, void* data, Read read) {
    std::vector<unsigned char> buffer(values * stored_.size());
    if (!read(stored_, buffer.data())) {
      errorfmt("{}", inner_->geterror());
      return false;
    }
    auto* out = static_cast<half*>(data);
    if (stored_ == OIIO::TypeDesc::UINT8) {
      through_tables(buffer.data(), values, out);
    } else if (stored_ == OIIO::TypeDesc::UINT16) {
      std::vector<uint16_t> codes(values);
      std::memcpy(codes.data(), buffer.data(), values * sizeof(uint16_t));
      through_tables(codes.data(), values, out);
    } else {
      const int nc = m_spec.nchannels;
      for (std::size_t i = 0; i < values; ++i) {
        float v;
        std::memcpy(&v, &buffer[4 * i], 4);
        out[i] = static_cast<int>(i % static_cast<std::size_t>(nc)) == m_spec.alpha_channel ? half(v) : decode_colour(v);
      }
    }
    return true;
  }

  template <typename Code>
  void through_tables(const Code* codes, std::size_t values, half* out) const {
    const std::size_t nc = static_cast<std::size_t>(m_spec.nchannels);
    const std::size_t alpha = m_spec.alpha_channel < 0 ? nc : static_cast<std::size_t>(m_spec.alpha_channel);
    for (std::size_t p = 0; p < values; p += nc)
      for (std::size_t c = 0; c < nc; ++c) out[p + c] = (c == alpha ? alpha_ : colour_)[codes[p + c]];
  }

  std::unique_ptr<OIIO::ImageInput> inner_;
  OIIO::TypeDesc stored_ = OIIO::TypeDesc::FLOAT;  // what read_decoded asks the file for
  std::vector<half> colour_, alpha_;               // by stored value (8- and 16-bit files)
};

}  // namespace

OIIO::ImageInput* create_srgb_decoding_input() { return new SrgbDecodingInput; }

}  // namespace pt
