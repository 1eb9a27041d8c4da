// An OpenImageIO ImageInput that reads an sRGB-encoded image (8- or 16-bit
// PNG, JPEG, ... or a .tx made from one) and hands the texture cache linear
// half-float texels: the colour channels decoded with the sRGB curve, alpha
// as stored. Registered with ImageCache::add_file for the textures that need
// decoding (texture_cache.cpp), so that the MIP levels the cache makes (from
// the finest level, for an image without any) average linear values, as
// filtering must: an average of encoded values decoded afterwards is too dark
// (a black and white checker would filter to 0.21 instead of 0.5).
//
// The cache knows such a file under its path followed by kSrgbDecodedSuffix, so
// that the same file can also be used undecoded (a texture with "encoding":
// "linear"). Internal to the pt_oiio module (src/imagelib/oiio).
#pragma once

#include <OpenImageIO/imageio.h>

namespace pt {

// The ImageInput::Creator of the proxy.
OIIO::ImageInput* create_srgb_decoding_input();

// Whether an image's values are sRGB-encoded: integer images (8- and 16-bit
// PNG, JPEG, ...) unless the file says it is linear; float images (EXR, HDR)
// are linear as they are.
bool srgb_encoded(const OIIO::ImageSpec& spec);

}  // namespace pt
