// Image output, chosen by the file extension:
//   .exr          linear float RGB (OpenImageIO/OpenEXR), no display transform;
//   .png, .jpg    8-bit, through the display pipeline (io/display.h);
//   .ppm          8-bit binary P6, through the display pipeline (as the courses expect).
// Files are written atomically: to a temporary file in the same directory,
// then renamed, so a failed or killed run never leaves a partial image.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "core/image.h"
#include "io/display.h"
#include "io/exr_settings.h"
#include "io/image_metadata.h"
#include "io/layered_image.h"
#include "scene/scene_description.h"

namespace pt {

class ExrBandWriter;  // imagelib/image_library.h

// Extensions write_image accepts (".exr", ".png", ".jpg", ".jpeg", ".ppm").
std::vector<std::string> supported_image_extensions();
bool is_supported_image_path(const std::string& path);
// True if writing `path` needs the image module (imagelib/image_library.h):
// EXR, PNG and JPEG; PPM is written without it.
bool needs_image_library(const std::string& path);
// True if write_image / write_layered_image write `path` as OpenEXR (every
// layer, float or half); false for the 8-bit formats and unsupported names.
bool is_exr_path(const std::string& path);

// none, rle, zips, zip, piz, pxr24, b44, b44a, dwaa, dwab.
std::vector<std::string> exr_compression_names();
// True if `compression` is one of exr_compression_names(), or dwaa/dwab with
// ":LEVEL" (a number > 0); false with `error` listing the names.
bool check_exr_compression(const std::string& compression, std::string& error);
// True if `compression` loses bits of 32-bit float channels (pxr24 rounds
// them to 24 bits); such files cannot hold Cryptomatte ids. (b44 and dwa are
// lossy only on half channels and on channels named R, G, B, Y, RY or BY.)
bool exr_compression_rounds_floats(const std::string& compression);

// Returns false and fills `error` on failure (nothing is left at `path` then).
// `metadata` goes into the header (all of it in EXR; strings only in PNG/JPEG;
// nothing in PPM).
bool write_image(const std::string& path, const Image& image, const DisplaySettings& settings,
                 std::string& error, const ImageMetadata& metadata = {});

// Writes a multi-layer image: EXR gets every layer (imagelib/oiio/exr_writer.h, in the image module) with the
// image's data window inside its frame, written as `exr` says; PNG/JPEG/PPM
// get the beauty's RGB of the data window only (a crop is written as a
// smaller image), and a PNG with settings.alpha also its alpha (the colour
// un-premultiplied before the display transform, as PNG's alpha is straight).
bool write_layered_image(const std::string& path, const LayeredImage& image, const DisplaySettings& settings,
                         std::string& error, const ImageMetadata& metadata = {}, const ExrSettings& exr = {});

// Writes an EXR of `layout` (one part; exr.multipart is not taken) band by
// band while the bands are made: `write(writer, why)` writes every row of the
// window through `writer`, top to bottom, or returns false with `why`. The
// same bytes as write_layered_image of the whole image, and as atomically (on
// failure nothing is left at `path`; `error` says "cannot write '<path>':
// <why>"). `layout`: the image's frame, window and layers (names, channels,
// types); its values are not read. Uncompressed ("none"), with the renderer's
// metadata names, it is written without the image module (io/exr_uncompressed.h).
bool write_exr_bands(const std::string& path, const LayeredImage& layout, const ImageMetadata& metadata,
                     const ExrSettings& exr, const std::function<bool(ExrBandWriter&, std::string&)>& write,
                     std::string& error);

// Reads an image (any format OpenImageIO reads) as float RGB: float files (EXR)
// as they are; integer files (PNG, PPM) as code / max code, i.e. the display
// encoding is not undone (the file does not say which transform wrote it).
// Grey images are expanded to RGB; channels past the third are ignored.
bool read_image(const std::string& path, Image& out, std::string& error);

}  // namespace pt
