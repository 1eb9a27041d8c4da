// The image library's TextureSystem (imagelib/image_library.h) on
// OpenImageIO's ImageCache and TextureSystem. Internal to the pt_oiio module.
#pragma once

#include <cstdint>
#include <memory>

#include "imagelib/image_library.h"

namespace pt {

std::unique_ptr<TextureSystem> make_texture_system(uint64_t max_bytes);

}  // namespace pt
