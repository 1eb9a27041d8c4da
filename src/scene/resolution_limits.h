// The largest image the program accepts, per side and in all: one struct for
// the loader (the file's film), the render-scene builder (after the command
// line's overrides) and the command line (option ranges, memory pre-flight).
#pragma once

namespace pt {

struct ResolutionLimits {
  // Largest accepted width or height.
  int max_resolution = 32768;
  // Largest accepted width x height (16384^2): the film alone then takes 3 GiB;
  // beyond it a scene is refused with a message instead of failing to allocate.
  long long max_pixels = 1LL << 28;

  bool admits(int width, int height) const {
    return width <= max_resolution && height <= max_resolution &&
           static_cast<long long>(width) * height <= max_pixels;
  }
};

}  // namespace pt
