// The pixel loop shared by every integrator: tiles rendered in parallel inside
// the worker pool, each pixel computed entirely by one task from a random
// stream keyed on (seed, pixel index, sample index) only, so the image is
// bit-identical for any thread count, tile size and tile order.
#pragma once

#include <cstdint>
#include <memory>

#include "core/color.h"
#include "core/function_ref.h"
#include "core/math.h"
#include "render/integrators/integrator.h"

namespace pt {

class Film;
class WorkerPool;
struct RenderScene;

// Film position (in pixels) of sample `index` of `spp` in pixel (x, y):
//  - spp == 1: the pixel centre;
//  - spp a perfect square n*n: one jittered sample in each cell of an n x n grid;
//  - otherwise: uniformly random positions in the pixel.
// The jitter comes from Rng(hash(seed, pixel_index, index)).
Vec2f sample_position(int x, int y, int index, int spp, uint64_t seed, uint64_t pixel_index);

// Position on the lens, in [0,1)^2, of sample `index` of a pixel (thin-lens
// cameras only): from a stream of its own keyed on (seed, pixel_index, index).
Vec2f lens_position(int index, uint64_t seed, uint64_t pixel_index);

// Computes one radiance estimate for a camera ray.
using RadianceFn = FunctionRef<RGB(const Ray&)>;

// Renders every pixel of `film`: the average (accumulated in double) of
// `radiance` over settings.spp camera rays per pixel. Non-finite estimates are
// counted as black. Runs tiles of settings.tile_size pixels in parallel inside `pool`.
void render_pixels(const RenderScene& scene, Film& film, WorkerPool& pool, const IntegratorSettings& settings,
                   RadianceFn radiance);

}  // namespace pt
