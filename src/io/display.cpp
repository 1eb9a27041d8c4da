#include "io/display.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <OpenColorIO/OpenColorIO.h>

namespace OCIO = OCIO_NAMESPACE;

namespace pt {

namespace {


// Linear Rec.709 (D65) to CIE XYZ (D65), as a 4x4 row-major matrix.
const double kRec709ToXyz[16] = {0.4123907993, 0.3575843394, 0.1804807884, 0,  //
                                 0.2126390059, 0.7151686788, 0.0721923154, 0,  //
                                 0.0193308187, 0.1191947798, 0.9505321522, 0,  //
                                 0,            0,            0,            1};

const char* const kXyzToSrgbDisplay = "DISPLAY - CIE-XYZ-D65_to_sRGB";
const char* const kAcesAp0ToXyz = "UTILITY - ACES-AP0_to_CIE-XYZ-D65_BFD";
const char* const kAcesSdrVideo = "ACES-OUTPUT - ACES2065-1_to_CIE-XYZ-D65 - SDR-VIDEO_1.0";

OCIO::TransformRcPtr rec709_to_xyz() {
  OCIO::MatrixTransformRcPtr m = OCIO::MatrixTransform::Create();
  m->setMatrix(kRec709ToXyz);
  return m;
}

OCIO::TransformRcPtr builtin(const char* style, OCIO::TransformDirection dir = OCIO::TRANSFORM_DIR_FORWARD) {
  OCIO::BuiltinTransformRcPtr b = OCIO::BuiltinTransform::Create();
  b->setStyle(style);
  b->setDirection(dir);
  return b;
}

std::string join(const std::vector<std::string>& names) {
  std::string s;
  for (const std::string& n : names) s += (s.empty() ? "'" : ", '") + n + "'";
  return s;
}

// The built-in views: OCIO's built-in transforms only, in a raw config.
OCIO::ConstProcessorRcPtr builtin_view_processor(const std::string& view, std::string& error) {
  OCIO::GroupTransformRcPtr g = OCIO::GroupTransform::Create();
  g->appendTransform(rec709_to_xyz());
  if (view.empty() || view == "standard") {
    g->appendTransform(builtin(kXyzToSrgbDisplay));
  } else if (view == "aces") {
    g->appendTransform(builtin(kAcesAp0ToXyz, OCIO::TRANSFORM_DIR_INVERSE));  // XYZ -> ACES2065-1
    g->appendTransform(builtin(kAcesSdrVideo));
    g->appendTransform(builtin(kXyzToSrgbDisplay));
  } else {
    error = "unknown view '" + view + "'; built-in views: " + join(builtin_view_names()) +
            " (set $OCIO to a config to use its views)";
    return nullptr;
  }
  return OCIO::Config::CreateRaw()->getProcessor(g);
}

std::vector<std::string> config_displays(const OCIO::ConstConfigRcPtr& config) {
  std::vector<std::string> out;
  for (int i = 0; i < config->getNumDisplays(); ++i) out.emplace_back(config->getDisplay(i));
  return out;
}

std::vector<std::string> config_views(const OCIO::ConstConfigRcPtr& config, const std::string& display) {
  std::vector<std::string> out;
  for (int i = 0; i < config->getNumViews(display.c_str()); ++i) out.emplace_back(config->getView(display.c_str(), i));
  return out;
}

// A display/view (and optional looks) of a config file, from its scene_linear role.
OCIO::ConstProcessorRcPtr config_processor(const DisplaySettings& s, std::string& description, std::string& error) {
  const OCIO::ConstConfigRcPtr config = OCIO::Config::CreateFromFile(s.ocio_config.c_str());
  const std::string display = s.display.empty() ? config->getDefaultDisplay() : s.display;
  const std::vector<std::string> displays = config_displays(config);
  if (std::find(displays.begin(), displays.end(), display) == displays.end()) {
    error = "OCIO config '" + s.ocio_config + "' has no display '" + display + "'; displays: " + join(displays);
    return nullptr;
  }
  const std::string view = s.view.empty() ? config->getDefaultView(display.c_str()) : s.view;
  const std::vector<std::string> views = config_views(config, display);
  if (std::find(views.begin(), views.end(), view) == views.end()) {
    error = "OCIO display '" + display + "' has no view '" + view + "'; views: " + join(views);
    return nullptr;
  }
  OCIO::GroupTransformRcPtr g = OCIO::GroupTransform::Create();
  if (!s.look.empty()) {
    OCIO::LookTransformRcPtr look = OCIO::LookTransform::Create();
    look->setSrc(OCIO::ROLE_SCENE_LINEAR);
    look->setDst(OCIO::ROLE_SCENE_LINEAR);
    look->setLooks(s.look.c_str());
    g->appendTransform(look);
  }
  OCIO::DisplayViewTransformRcPtr dv = OCIO::DisplayViewTransform::Create();
  dv->setSrc(OCIO::ROLE_SCENE_LINEAR);
  dv->setDisplay(display.c_str());
  dv->setView(view.c_str());
  g->appendTransform(dv);
  description = "OCIO " + display + " / " + view + (s.look.empty() ? "" : " / look " + s.look) + " (" +
                s.ocio_config + ")";
  return config->getProcessor(g);
}

// The CGR course's display mapping, inferred from its reference images
// (docs/rendering.md, "The CGR mapping"): the colour x is compressed
// by its Rec.709 luminance as in Reinhard's operator, u = s k x / (1 + k L(x)),
// then each channel is shown as the sRGB encoding of u^2.4 (a gamma-2.4 image
// re-encoded as sRGB: a dark toe, then nearly linear). k is fitted; s puts the
// course's one fixed point, a 0.25 grey background, at 87/255.
constexpr float kCgrExposure = 0.9f;  // k
constexpr float kCgrGamma = 2.4f;

float srgb_oetf(float v) { return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f; }

float cgr_channel(float u) { return srgb_oetf(std::pow(std::clamp(u, 0.0f, 1.0f), kCgrGamma)); }

// s: the scale that shows the 0.25 grey as 87/255 (the inverse of the curve at 87/255).
float cgr_scale() {
  const double code = 87.0 / 255.0;
  const double linear = std::pow((code + 0.055) / 1.055, 2.4);  // the sRGB EOTF (code > 0.04045)
  const double u = std::pow(linear, 1.0 / kCgrGamma);
  return static_cast<float>(u * (1.0 + 0.25 * kCgrExposure) / (0.25 * kCgrExposure));
}

// Negative and NaN -> 0, infinity -> a finite stand-in (the curve saturates long before).
float usable(float v) { return v > 0.0f ? std::min(v, 1e30f) : 0.0f; }

RGB cgr_course(RGB x) {
  static const float s = cgr_scale();
  x = RGB(usable(x.r), usable(x.g), usable(x.b));
  const float luminance = 0.2126f * x.r + 0.7152f * x.g + 0.0722f * x.b;
  const float f = s * kCgrExposure / (1.0f + kCgrExposure * luminance);
  return RGB(cgr_channel(f * x.r), cgr_channel(f * x.g), cgr_channel(f * x.b));
}

// The 8-bit-bound value of a linear colour under a course transform (not OCIO's).
RGB course_pixel(DisplayTransform t, RGB v) {
  if (t == DisplayTransform::CgrCourse) return cgr_course(v);
  return RGB(std::clamp(v.r, 0.0f, 1.0f), std::clamp(v.g, 0.0f, 1.0f), std::clamp(v.b, 0.0f, 1.0f));
}

unsigned char to_code(float v) {
  if (!(v > 0.0f)) return 0;  // negative, zero and NaN
  return static_cast<unsigned char>(std::lround(std::min(v, 1.0f) * 255.0f));
}

}  // namespace

std::vector<std::string> builtin_view_names() { return {"standard", "aces"}; }

struct DisplayEncoder::Impl {
  DisplayTransform transform = DisplayTransform::Srgb;
  float scale = 1;                         // 2^exposure
  OCIO::ConstCPUProcessorRcPtr processor;  // colour-managed transforms only
};

DisplayEncoder::DisplayEncoder(std::unique_ptr<Impl> impl, std::string description)
    : impl_(std::move(impl)), description_(std::move(description)) {}
DisplayEncoder::~DisplayEncoder() = default;

std::unique_ptr<DisplayEncoder> DisplayEncoder::create(const DisplaySettings& s, std::string& error) {
  auto impl = std::make_unique<Impl>();
  impl->transform = s.transform;
  impl->scale = std::exp2(s.exposure);
  std::string description;
  switch (s.transform) {
    case DisplayTransform::Linear: description = "Path of Light course: value x 255, clipped"; break;
    case DisplayTransform::CgrCourse:
      description = "CGR course: Reinhard on luminance (k 0.9), sRGB of v^2.4, clipped";
      break;
    case DisplayTransform::Srgb:
      try {
        OCIO::ConstProcessorRcPtr p;
        if (s.ocio_config.empty()) {
          p = builtin_view_processor(s.view, error);
          description = "OCIO built-in: linear Rec.709 -> sRGB display, view '" +
                        (s.view.empty() ? std::string("standard") : s.view) + "'";
        } else {
          p = config_processor(s, description, error);
        }
        if (!p) return nullptr;
        impl->processor = p->getDefaultCPUProcessor();
      } catch (const OCIO::Exception& e) {
        error = std::string("OpenColorIO: ") + e.what();
        return nullptr;
      }
      break;
  }
  if (s.exposure != 0.0f) {
    std::ostringstream os;
    os << ", exposure " << s.exposure << " stops";
    description += os.str();
  }
  return std::unique_ptr<DisplayEncoder>(new DisplayEncoder(std::move(impl), std::move(description)));
}

RGB DisplayEncoder::apply(RGB linear) const {
  RGB v = linear * impl_->scale;
  if (!impl_->processor) {
    return course_pixel(impl_->transform, v);
  }
  float rgb[3] = {v.r, v.g, v.b};
  impl_->processor->applyRGB(rgb);
  return {rgb[0], rgb[1], rgb[2]};
}

void DisplayEncoder::encode(const RGB* linear, std::size_t count, unsigned char* out) const {
  constexpr std::size_t kChunk = 4096;  // pixels per OCIO call
  std::vector<float> buf(3 * std::min(count, kChunk));
  for (std::size_t start = 0; start < count; start += kChunk) {
    const std::size_t n = std::min(kChunk, count - start);
    for (std::size_t i = 0; i < n; ++i) {
      const RGB v = linear[start + i] * impl_->scale;
      buf[3 * i + 0] = v.r;
      buf[3 * i + 1] = v.g;
      buf[3 * i + 2] = v.b;
    }
    if (impl_->processor) {
      OCIO::PackedImageDesc desc(buf.data(), static_cast<long>(n), 1, 3);
      impl_->processor->apply(desc);
    } else {
      for (std::size_t i = 0; i < n; ++i) {
        const RGB c = course_pixel(impl_->transform, RGB(buf[3 * i], buf[3 * i + 1], buf[3 * i + 2]));
        buf[3 * i] = c.r;
        buf[3 * i + 1] = c.g;
        buf[3 * i + 2] = c.b;
      }
    }
    for (std::size_t i = 0; i < 3 * n; ++i) out[3 * start + i] = to_code(buf[i]);
  }
}

unsigned char display_encode(float linear, const DisplaySettings& settings) {
  std::string error;
  const std::unique_ptr<DisplayEncoder> enc = DisplayEncoder::create(settings, error);
  if (!enc) return 0;
  unsigned char code[3];
  const RGB grey(linear);
  enc->encode(&grey, 1, code);
  return code[1];
}

}  // namespace pt
