// How materials read textures: every texture lookup a material, a BSDF or a
// normal map makes goes through texture_rgb() below, with the TexCoord of the
// hit, so that a richer lookup (filter footprints from ray differentials) is a
// change to these two definitions and to tex_coord(), not to every material.
//
// FloatParam and RGBParam are the material parameters that may be textured
// (docs/scene-format.md, "Textured parameters"): a constant, or the constant
// times the texture's value (for a float parameter, the mean of the texel's
// three channels, which is the value itself for a grey image).
#pragma once

#include "core/color.h"
#include "core/math.h"
#include "geometry/shape_base.h"
#include "render/textures/texture.h"

namespace pt {

// Where a material reads its textures at a hit.
struct TexCoord {
  Vec2f uv;
  TexCoord() = default;
  TexCoord(Vec2f uv_) : uv(uv_) {}  // NOLINT(google-explicit-constructor): a uv is a texture coordinate
};

inline TexCoord tex_coord(const SurfaceGeometry& geo) { return TexCoord(geo.uv); }

// The one texture lookup of the materials.
inline RGB texture_rgb(const Texture& t, const TexCoord& tc) { return t.lookup(tc.uv); }

struct FloatParam {
  float value = 0.0f;
  const Texture* texture = nullptr;

  float at(const TexCoord& tc) const {
    if (!texture) return value;
    const RGB c = texture_rgb(*texture, tc);
    return value * ((c.r + c.g + c.b) * (1.0f / 3.0f));
  }
  bool textured() const { return texture != nullptr; }
};

struct RGBParam {
  RGB value;
  const Texture* texture = nullptr;

  RGB at(const TexCoord& tc) const { return texture ? value * texture_rgb(*texture, tc) : value; }
  bool textured() const { return texture != nullptr; }
};

}  // namespace pt
