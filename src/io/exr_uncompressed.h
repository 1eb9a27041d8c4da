// Uncompressed ("none") EXR files of one part written without the image
// module (OpenImageIO): the streamed merge's file (io/image_io.h,
// write_exr_bands) when it is stored uncompressed, for which loading the
// module (~10% of the merge's CPU) and OpenEXR's per-channel copy of the rows
// cost more than the file's format asks for. The file is the same, byte for
// byte but the time of writing (capDate), as the image module's writer
// (imagelib/oiio/exr_writer.cpp) writes: OpenEXR's header (every attribute
// sorted by name, the long-names flag when a name has 32 characters or more),
// its offset table, then one chunk per row, each channel's values of the row
// in the order of the channels' names (tests/render/test_exr_uncompressed.cpp
// compares the two writers' bytes).
#pragma once

#include <memory>
#include <string>

#include "io/exr_pack.h"
#include "io/exr_settings.h"
#include "io/image_metadata.h"
#include "io/layered_image.h"

namespace pt {

class ExrBandWriter;  // imagelib/image_library.h

// Whether open_uncompressed_exr writes the file of `layout` and `metadata`
// with `exr`: compression "none"; channel names unique, 1 to 255 characters;
// metadata named as the renderer names it ("pathtracer:..." and
// "cryptomatte/..." strings, ints and floats, the matrices worldToCamera and
// worldToNDC), each name once, whatever its case, and no string holding a
// zero byte. Anything else (a shard's metadata can name anything) goes to the
// image module, whose writer gives names of its own a meaning of its own.
bool writes_uncompressed_exr(const LayeredImage& layout, const ImageMetadata& metadata, const ExrSettings& exr);

// Opens `path` (created or truncated) for the file of `layout` (its frame,
// window, layers' channels and types; no values) and `metadata`, written band
// by band (the interface of ImageLibrary::open_exr), when
// writes_uncompressed_exr. nullptr with `error` (the system's words) on failure.
std::unique_ptr<ExrBandWriter> open_uncompressed_exr(const std::string& path, const LayeredImage& layout,
                                                     const ImageMetadata& metadata, std::string& error);

// A row of that file as it stores it, for pack_lines (io/exr_pack.h): its
// y and its values' byte count (two int32, which the writer's write_lines
// sets), then each channel's line, the channels in the order of their
// names; row_bytes counts all of it. The channels of a pixel's values are
// the layout's layers' channels, in order.
LineLayout uncompressed_exr_lines(const LayeredImage& layout);

}  // namespace pt
