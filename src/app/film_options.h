// What the command line asks of the film: the AOV layers (--aov), the region
// (--crop, --crop-px) and the replay of one sample (--pixel/--sample or
// --replay); docs/output.md.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "render/film/aov.h"
#include "render/film/film.h"

namespace pt {

struct Options;

// The requested AOVs; a replay reports every AOV of its one sample. Returns
// false after printing why (an unknown name: the valid ones are listed).
bool film_aovs(const Options& o, std::vector<AovRequest>& out);

// The region to render, in pixels of a width x height frame: the crop, the
// replayed pixel, or the whole frame. Returns false after printing why.
bool crop_window(const Options& o, int width, int height, PixelRect& out);

// Bytes the film stores per pixel for these AOVs (the memory pre-flight).
std::size_t film_bytes_per_pixel(const std::vector<AovRequest>& aovs);

// How to replay the report's first offender: "; to replay the first, run this
// command again with --pixel X,Y --sample N" (the same options give the same
// pass plan, so the same sample); empty without an offender.
std::string replay_hint(const NonFiniteReport& report);

// Prints the replayed sample of pixel (x, y): its radiance, filter weight and AOVs.
void print_replay(const Film& film, int x, int y, int sample);

}  // namespace pt
