// Where a texture is looked up, and over how much of it: the record every
// texture evaluation takes (Texture::eval, Texture::alpha).
//
// `uv` are the hit's texture coordinates and `p` its position in the object
// space of the shape (world space for a shape placed directly; the space of
// its prototype for a transformed shape or an instance), which 3D textures
// (mapping "object") read. The derivatives are the change of each across one
// pixel of the image, from the camera ray's differentials at the first hit
// and an approximation at later ones (RenderScene::intersect,
// docs/textures.md); zero derivatives ask for a point lookup (the finest
// level, bilinear).
#pragma once

#include "core/math.h"
#include "geometry/shape_base.h"

namespace pt {

struct TexCoord {
  Vec2f uv;
  Vec2f duvdx, duvdy;  // per pixel in x and y of the image
  Vec3f p;             // object space
  Vec3f dpdx, dpdy;    // object space, per pixel

  TexCoord() = default;
  // A point lookup at `uv` (p at the origin).
  TexCoord(Vec2f uv_) : uv(uv_) {}  // NOLINT(google-explicit-constructor): a uv is a texture coordinate
  TexCoord(Vec2f uv_, Vec2f duvdx_, Vec2f duvdy_, Vec3f p_ = {}, Vec3f dpdx_ = {}, Vec3f dpdy_ = {})
      : uv(uv_), duvdx(duvdx_), duvdy(duvdy_), p(p_), dpdx(dpdx_), dpdy(dpdy_) {}

  // The same place without a footprint (what alpha tests and point-sampled textures read).
  TexCoord point() const { return TexCoord(uv, {}, {}, p); }
};

// The lookup record of a hit (its footprint as RenderScene::intersect left it).
inline TexCoord tex_coord(const SurfaceGeometry& geo) {
  return TexCoord(geo.uv, geo.duvdx, geo.duvdy, geo.p_object, geo.dpdx, geo.dpdy);
}

}  // namespace pt
