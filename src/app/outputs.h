// The images a render writes (-o, repeatable) and their display pipeline.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "io/display.h"
#include "io/image_io.h"
#include "io/image_metadata.h"

namespace pt {

struct FilmDesc;
struct LayeredImage;
struct Options;
class OutputStamps;

// Checks every output path before any work is done. Returns false with `error`.
bool check_outputs(const std::vector<std::string>& outputs, std::string& error);

// The display pipeline for PNG/JPEG/PPM outputs: the scene's transform and
// exposure, overridden from the command line; $OCIO names a config when
// --ocio-config does not.
DisplaySettings display_settings(const Options& o, const FilmDesc& film);

// Writes `image` (the beauty and any AOV layers; display images take the
// beauty) to every output with `metadata` (io/image_metadata.h: RenderStamp
// says what the render reached, "pathtracer:partial" = 1 when a signal stopped
// it). Returns false with the first error.
// An output another program wrote since the run started is not replaced
// (write_guarded, app/output_checks.h); the others are still written.
bool write_outputs(const std::vector<std::string>& outputs, const LayeredImage& image, const DisplaySettings& display,
                   const ExrSettings& exr, const ImageMetadata& metadata, OutputStamps& stamps, std::string& error);

std::string join(const std::vector<std::string>& items, const char* sep);

}  // namespace pt
