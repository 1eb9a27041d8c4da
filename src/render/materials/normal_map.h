// Shading normals from a material's bump map ("displacement") and normal map
// ("normalmap"), applied where a ray finds the surface (RenderScene::intersect),
// so every integrator, the BSDF and the N AOV see the same shading normal
// (docs/path-tracing.md, "Normal and bump maps").
//
// - Bump map (pbrt-v4's BumpMap): the surface displaced by h(u, v) along the
//   shading normal n, dp'/du = dp/du + (dh/du) n (likewise v), with dh/du by a
//   forward difference of half a texel; n' = dp'/du x dp'/dv, on n's side.
// - Normal map, tangent space: texel c gives t = 2c - 1 in a frame whose x is
//   dp/du made perpendicular to n, y the image's up (rows decreasing, which is
//   -v: green is up, the OpenGL convention of glTF and Blender) and z the
//   normal: n' = normalize(t.x T + t.y B + t.z n). The tangent comes from the
//   shape's uv parameterisation (per triangle from its texture coordinates for
//   meshes, which carry no tangents).
// - No light through the surface: n' is kept on the geometric normal's side,
//   at least 0.01 above its tangent plane; the BSDF's own policy (bsdf.h) then
//   applies to n' as to any shading normal.
#pragma once

#include "geometry/shape_base.h"
#include "render/materials/material.h"

namespace pt {

// Replaces geo.ns by the normal of m's bump and normal maps (m.perturbs_normal()),
// `d` the world-space uv derivatives at geo.
void perturb_shading_normal(const Material& m, const UvDerivatives& d, SurfaceGeometry& geo);

}  // namespace pt
