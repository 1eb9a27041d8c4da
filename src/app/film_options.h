// What the command line asks of the film: the AOV layers (--aov), the region
// (--crop, --crop-px) and the replay of one sample (--pixel/--sample or
// --replay); docs/output.md.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "app/memory_estimate.h"
#include "io/exr_settings.h"
#include "render/film/aov.h"
#include "render/film/film.h"
#include "render/integrators/integrator.h"

namespace pt {

struct Options;
struct SceneDescription;

// The requested AOVs and the beauty's pixel type ("--aov beauty:half"); a
// replay reports every AOV of its one sample that `integrator` produces.
// Returns false with `error`: an unknown name (the valid ones are listed), or
// one the integrator cannot produce (the ones it can are listed).
bool film_aovs(const Options& o, const IntegratorInfo& integrator, std::vector<AovRequest>& out, ChannelType& beauty,
               std::string& error);

// The region to render, in pixels of a width x height frame: the crop, the
// replayed pixel, or the whole frame; then its tile (--tile K/N,
// docs/distributed.md). Returns false with `error`.
bool crop_window(const Options& o, int width, int height, PixelRect& out, std::string& error);
// The same before the tile: the region that tiles split.
bool region_window(const Options& o, int width, int height, PixelRect& out, std::string& error);

// Bytes the film stores per pixel for these AOVs (the memory pre-flight).
std::size_t film_bytes_per_pixel(const std::vector<AovRequest>& aovs);

// Bytes per pixel of Film::layers() (the memory pre-flight), which the
// writers read: a float per channel, R, G, B, A and every AOV channel.
std::size_t layer_bytes_per_pixel(const std::vector<AovRequest>& aovs);

// Bytes the largest of `outputs`' writers holds beside Film::layers() for a
// crop window of width x height pixels (the memory pre-flight): for EXR one
// band of packed rows (io/exr_bands.h) of the largest part (every layer in one,
// or with `exr.multipart` one per layer), 2 bytes a half channel and 4 a float,
// and OpenEXR's line buffers (exr_line_buffer_bytes: blocks of `exr.compression`,
// two per thread of `exr.threads`, 0 for every hardware thread); for PNG, JPEG
// and PPM the float RGB image and its 8-bit codes, 15 bytes a pixel.
uint64_t writer_bytes(const std::vector<AovRequest>& aovs, ChannelType beauty, const std::vector<std::string>& outputs,
                      const ExrSettings& exr, int width, int height);

// The pre-flight memory estimate of the render `o` asks for in a width x
// height frame: the film and output buffers of its crop window (crop_window()),
// a second film while --resume reads a checkpoint, the textures and the
// geometry of `scene`. Returns false with `error` (a bad crop).
bool estimate_render_memory(const Options& o, const SceneDescription& scene, int width, int height,
                            const std::vector<AovRequest>& aovs, ChannelType beauty, MemoryEstimate& out,
                            std::string& error);

// How to replay the report's first offender: "; to replay the first, run this
// command again with --pixel X,Y --sample N" (the same options give the same
// pass plan, so the same sample); empty without an offender.
std::string replay_hint(const NonFiniteReport& report);

// The report of the replayed sample of pixel (x, y), for standard output: its
// radiance, filter weight and AOVs.
std::string replay_text(const Film& film, int x, int y, int sample);

}  // namespace pt
