#pragma once

#include "scene/scene_description.h"

namespace pt {

// Which material types share which parts: asked by the native reader (which
// keys a type takes), validation and the render scene's builder, answered here
// once so that a new type is added to these lists in one place.

// Types whose lobes are GGX microfacets: the roughness keys, validated as such.
inline bool is_microfacet(MaterialType t) {
  return t == MaterialType::Conductor || t == MaterialType::Dielectric || t == MaterialType::CoatedDiffuse ||
         t == MaterialType::MetallicRoughness;
}

// Types with a coated-diffuse lobe: a `reflectance` key in [0, 1] and a coating
// table for their index.
inline bool has_coated_diffuse(MaterialType t) {
  return t == MaterialType::CoatedDiffuse || t == MaterialType::MetallicRoughness;
}

}  // namespace pt
