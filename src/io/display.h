// Display encoding: scene-linear Rec.709 radiance -> 8-bit display code values
// for PNG, JPEG and PPM. (EXR stays scene-linear and never passes through here.)
//
// Colour management goes through OpenColorIO:
//  - view "standard" (default): exposure, then the sRGB display encoding
//    (OCIO built-in "DISPLAY - CIE-XYZ-D65_to_sRGB"), values clipped to [0,1];
//  - view "aces": exposure, then the ACES 1.0 SDR-video output transform to an
//    sRGB display, built only from OCIO 2.1's built-in transforms (no config
//    file needed): a filmic tone curve that rolls highlights off instead of
//    clipping them;
//  - a config named by $OCIO (or DisplaySettings::ocio_config): `display`,
//    `view` and `look` select from it, from its scene_linear role.
// The course families keep their documented curves (Path of Light: value x 255;
// CGR: the fitted power curve; docs/rendering.md): those are the courses'
// definitions of their images, not colour management, and are hand-coded.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/color.h"
#include "scene/scene_description.h"

namespace pt {

struct DisplaySettings {
  DisplayTransform transform = DisplayTransform::Srgb;  // from the scene file
  float exposure = 0;                                   // stops, applied before the view
  // For DisplayTransform::Srgb only (the course transforms ignore these):
  std::string view;         // "" or "standard", "aces"; with a config: a view of `display`
  std::string ocio_config;  // a config file; "" = $OCIO if set, else the built-in views above
  std::string display;      // config display ("" = the config's default)
  std::string look;         // config look(s), e.g. "+grade"; "" = none
  // PNG only: write the beauty's alpha too (RGBA, straight alpha). The
  // command line sets it for a transparent film (docs/output.md).
  bool alpha = false;
};

// The names accepted as DisplaySettings::view without a config.
std::vector<std::string> builtin_view_names();

class DisplayEncoder {
 public:
  // Builds the colour pipeline for `settings`. Returns nullptr and sets `error`
  // (naming the valid displays/views/looks) if a name or the config is wrong.
  static std::unique_ptr<DisplayEncoder> create(const DisplaySettings& settings, std::string& error);
  ~DisplayEncoder();

  // Display-referred value in [0,1] for one linear colour.
  RGB apply(RGB linear) const;
  // 8-bit RGB codes (interleaved, 3 bytes per pixel) of `count` linear colours.
  void encode(const RGB* linear, std::size_t count, unsigned char* out) const;
  // A one-line description for metadata and run records, e.g. "OCIO sRGB standard".
  const std::string& description() const { return description_; }

 private:
  struct Impl;
  explicit DisplayEncoder(std::unique_ptr<Impl> impl, std::string description);
  std::unique_ptr<Impl> impl_;
  std::string description_;
};

// Convenience for a single grey value (tests, documentation examples): the
// 8-bit code of `linear` under `settings`, or 0 if the pipeline cannot be built.
unsigned char display_encode(float linear, const DisplaySettings& settings);

}  // namespace pt
