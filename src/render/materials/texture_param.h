// How materials read textures: every texture lookup a material, a BSDF or a
// normal map makes goes through texture_rgb() below, with the TexCoord of the
// hit (render/textures/tex_coord.h: its uv, object-space point and their
// footprint from ray differentials), so every textured parameter is filtered
// as the diffuse colour is.
//
// FloatParam and RGBParam are the material parameters that may be textured
// (docs/scene-format.md, "Textured parameters"): a constant, or the constant
// times the texture's value (for a float parameter, the mean of the texel's
// three channels, which is the value itself for a grey image, or the one
// channel an importer chose, squared where it asked: docs/importing.md).
#pragma once

#include "core/color.h"
#include "core/math.h"
#include "render/textures/tex_coord.h"
#include "render/textures/texture.h"

namespace pt {

// The one texture lookup of the materials: filtered over the hit's footprint
// (render/textures/tex_coord.h; a point lookup where the hit has none).
inline RGB texture_rgb(const Texture& t, const TexCoord& tc) { return t.eval(tc); }

struct FloatParam {
  float value = 0.0f;
  const Texture* texture = nullptr;
  int channel = -1;      // 0, 1, 2: that channel of the texel; -1: the mean of the three
  bool squared = false;  // value * t^2

  float at(const TexCoord& tc) const {
    if (!texture) return value;
    const RGB c = texture_rgb(*texture, tc);
    const float t = channel < 0 ? (c.r + c.g + c.b) * (1.0f / 3.0f) : c[channel];
    return value * (squared ? t * t : t);
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
