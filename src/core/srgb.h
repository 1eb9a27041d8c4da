// The sRGB transfer curve (IEC 61966-2-1).
#pragma once

#include <cmath>

namespace pt {

// The decoding curve, on values in [0, 1].
inline float srgb_to_linear(float v) { return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f); }

}  // namespace pt
