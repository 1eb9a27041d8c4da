// The textures of a render scene (build_render_scene's part, scene_textures.cpp):
// each texture a used material refers to, built once; the materials that
// hold them; the alpha cutouts the accelerator is given.
#pragma once

#include "render/render_scene.h"

namespace pt {

// Builds every texture some material refers to (image textures through the
// scene's TextureCache, sized by options.texture_cache_bytes), the
// background image (decoded into memory), and sets scene.footprints. An
// unreferenced texture is never read. False after reporting a texture that
// cannot be used ("cannot read texture '<file>': ..." at its location).
bool load_textures(const SceneDescription& desc, const BuildOptions& options, RenderScene& scene, Diagnostics& diag);

// The render-time materials of the description, their textures resolved (after
// load_textures); a coated diffuse's albedo tables are computed once per index
// of refraction.
void add_materials(const SceneDescription& desc, RenderScene& scene);

// Fills scene.cutouts (one per material) and scene.cutout_test; the test to
// hand the accelerator, or null if no material has a cutout.
const CutoutTest* prepare_cutouts(const SceneDescription& desc, RenderScene& scene);

}  // namespace pt
