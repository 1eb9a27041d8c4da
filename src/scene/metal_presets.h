// The conductor presets of the native format ("metal": "Au"): RGB complex
// indices of refraction (eta + i k) per linear sRGB channel, fitted to the
// spectral Fresnel reflectance of published measured data by
// tools/dev/metal_presets.py (sources and method there and in
// docs/path-tracing.md, "Conductor presets").
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/color.h"

namespace pt {

struct MetalPreset {
  const char* name;  // chemical symbol, as Mitsuba's conductor presets
  RGB eta, k;
};

// The preset called `name` (exact, case-sensitive), if any.
std::optional<MetalPreset> find_metal_preset(std::string_view name);
// Every preset's name, in the table's order (for messages).
std::vector<std::string> metal_preset_names();

}  // namespace pt
