// Writing multi-layer EXR files through OpenImageIO (internal to the pt_oiio
// module; the public entry point is write_layered_image in io/image_io.h).
#pragma once

#include <memory>
#include <string>

#include <OpenImageIO/imageio.h>

#include "imagelib/image_library.h"
#include "io/exr_settings.h"
#include "io/image_metadata.h"
#include "io/layered_image.h"

namespace pt {

// Puts `metadata` into `spec`: strings always; ints, floats and matrices when
// `typed` (EXR). For EXR (`typed`) also the chromaticities: Rec.709 / sRGB
// primaries and the D65 white point.
void add_image_metadata(OIIO::ImageSpec& spec, const ImageMetadata& metadata, bool typed);

// Writes `image` to `path`: channels R, G, B, A, then each AOV's channels in
// the image's layer order, each stored as its layer's type; data window = the
// image's window, display window = its frame; compressed as `exr` says. One
// part, or with exr.multipart one part per layer (named after it, the beauty
// "rgba"), each with every metadata attribute.
bool write_exr_layers(const std::string& path, const LayeredImage& image, const ImageMetadata& metadata,
                      const ExrSettings& exr, std::string& error);

// The same file (one part) written band by band (ImageLibrary::open_exr).
std::unique_ptr<ExrBandWriter> open_exr_bands(const std::string& path, const LayeredImage& layout,
                                              const ImageMetadata& metadata, const ExrSettings& exr,
                                              std::string& error);

}  // namespace pt
