// When the Embree backend builds compact (docs/geometry.md, "Scene flags"):
// scenes of kEmbreeCompactTriangles mesh triangles or more get
// RTC_SCENE_FLAG_COMPACT, about half the build's peak memory. Shared with the
// memory pre-flight (src/app/memory_estimate.cpp), which estimates them so.
#pragma once

#include <cstddef>

namespace pt {

inline constexpr std::size_t kEmbreeCompactTriangles = std::size_t{4} << 20;

}  // namespace pt
