// Model-file materials mapped onto ours (src/scene/import_materials.cpp,
// docs/importing.md "Materials"): the parameters each MTL statement and each
// glTF metallic-roughness property becomes, on tests/data/assets/obj/features.*
// and gltf/pbr.* (written by tests/data/assets/make_assets.py).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "scene/import_materials.h"
#include "scene_test_util.h"

namespace pt {
namespace {

const std::string kAssets = std::string(PT_TEST_DATA_DIR) + "/data/assets/";

const MaterialDesc& named(const SceneDescription& s, const std::string& suffix) {
  for (const MaterialDesc& m : s.materials)
    if (m.name.size() >= suffix.size() && m.name.compare(m.name.size() - suffix.size(), suffix.size(), suffix) == 0)
      return m;
  ADD_FAILURE() << "no material named *" << suffix;
  return s.materials.front();
}

const TextureDesc& texture(const SceneDescription& s, const std::optional<int>& t) {
  EXPECT_TRUE(t);
  return s.textures.at(static_cast<std::size_t>(t.value_or(0)));
}

std::string file_of(const TextureDesc& t) { return t.written; }

TEST(ImportMtlMaterials, CutoutBumpMirrorGlassRoughMetalAndNormalMap) {
  Diagnostics diag;
  const std::optional<SceneDescription> s = load_scene(kAssets + "obj/features.obj", {}, diag);
  ASSERT_TRUE(s) << diag.format();
  // map_d: an alpha texture, read as data, cut at 0.5 (d is 1).
  const MaterialDesc& cutout = named(*s, ":cutout");
  EXPECT_EQ(cutout.type.value, MaterialType::Lambert);
  EXPECT_EQ(file_of(texture(*s, cutout.alpha_texture)), "mask.png");
  EXPECT_TRUE(texture(*s, cutout.alpha_texture).raw);
  EXPECT_FLOAT_EQ(cutout.alpha_cutoff, 0.5f);
  // bump -bm 0.05: a displacement of 0.05 x the texture (file units = scene units here).
  const MaterialDesc& bumpy = named(*s, ":bumpy");
  ASSERT_TRUE(bumpy.displacement);
  EXPECT_FLOAT_EQ(bumpy.displacement->value.value, 0.05f);
  EXPECT_EQ(file_of(texture(*s, bumpy.displacement->texture)), "stripes.png");
  EXPECT_TRUE(texture(*s, bumpy.displacement->texture).raw);
  // illum 3 with a black Kd and no Ns: a smooth conductor, Schlick F0 = Ks.
  const MaterialDesc& mirror = named(*s, ":mirror");
  EXPECT_EQ(mirror.type.value, MaterialType::Conductor);
  EXPECT_TRUE(mirror.schlick);
  EXPECT_TRUE(test::near(mirror.reflectance.value.value, RGB(0.9f, 0.6f, 0.3f)));
  EXPECT_FLOAT_EQ(mirror.uroughness.value.value, 0.0f);
  // illum 7 with d 0.5: glass, a smooth dielectric of index Ni; no cutout.
  const MaterialDesc& glass = named(*s, ":glass");
  EXPECT_EQ(glass.type.value, MaterialType::Dielectric);
  EXPECT_FLOAT_EQ(glass.ior.value, 1.5f);
  EXPECT_FLOAT_EQ(glass.uroughness.value.value, 0.0f);
  EXPECT_FLOAT_EQ(glass.alpha.value, 1.0f);
  EXPECT_FALSE(glass.alpha_texture);
  // illum 3, Ns 50, map_Ks, map_Ns: a rough conductor; F0 = Ks x map_Ks (colour), alpha = map_Ns^2.
  const MaterialDesc& metal = named(*s, ":rough_metal");
  EXPECT_EQ(metal.type.value, MaterialType::Conductor);
  EXPECT_EQ(file_of(texture(*s, metal.reflectance.texture)), "tint.png");
  EXPECT_FALSE(texture(*s, metal.reflectance.texture).raw);
  EXPECT_EQ(file_of(texture(*s, metal.uroughness.texture)), "rough.png");
  EXPECT_TRUE(texture(*s, metal.uroughness.texture).raw);
  EXPECT_EQ(metal.uroughness.texture, metal.vroughness.texture);
  EXPECT_TRUE(metal.uroughness.squared);
  EXPECT_FALSE(metal.remap_roughness.value);
  EXPECT_FLOAT_EQ(metal.uroughness.value.value, 1.0f);
  // norm: a normal map, read as data.
  const MaterialDesc& normal = named(*s, ":normal_mapped");
  EXPECT_EQ(file_of(texture(*s, normal.normal_map)), "normal.png");
  EXPECT_TRUE(texture(*s, normal.normal_map).raw);
  EXPECT_FLOAT_EQ(normal.normal_scale, 1.0f);
  // All of it is mapped exactly: nothing is reported.
  const std::string text = diag.format();
  EXPECT_EQ(text.find("features.mtl"), std::string::npos) << text;
  EXPECT_EQ(text.find("not supported"), std::string::npos) << text;
}

TEST(ImportMtlMaterials, NsBecomesGgxAlphaAndPartialDissolveIsAnOpacity) {
  test::TempDir dir;
  dir.write("m.obj", "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\nusemtl b\nf 1 3 2\n");
  dir.write("m.mtl", "newmtl a\nKd 0 0 0\nKs 0.5 0.5 0.5\nNs 98\nillum 3\n"
                     "newmtl b\nKd 0.5 0.5 0.5\nKs 0.2 0.2 0.2\nNs 10\nd 0.7\nillum 2\n");
  Diagnostics diag;
  const std::optional<SceneDescription> s = load_scene(dir.str() + "/m.obj", {}, diag);
  ASSERT_TRUE(s) << diag.format();
  const MaterialDesc& a = named(*s, ":a");
  EXPECT_EQ(a.type.value, MaterialType::Conductor);
  EXPECT_NEAR(a.uroughness.value.value, std::sqrt(2.0f / 100.0f), 1e-6f);  // Walter et al.: alpha = sqrt(2 / (Ns + 2))
  EXPECT_FALSE(a.remap_roughness.value);
  const MaterialDesc& b = named(*s, ":b");  // a diffuse colour: the Blinn-Phong of the MTL model
  EXPECT_EQ(b.type.value, MaterialType::Phong);
  EXPECT_FLOAT_EQ(b.exponent.value, 10.0f);
  EXPECT_FLOAT_EQ(b.alpha.value, 0.7f);
  EXPECT_TRUE(b.alpha_blend.value);  // d 0.7: the surface is there for 70% of the rays, as in Blender
  EXPECT_FALSE(a.alpha_blend.value);
  EXPECT_EQ(diag.format().find("dissolve"), std::string::npos) << diag.format();
}

// Tf tints the glass's transmission; map_Ke is an emission texture, times Ke
// (1 where Ke is absent or black): no warnings.
TEST(ImportMtlMaterials, TfTintsGlassAndMapKeIsAnEmissionTexture) {
  test::TempDir dir;
  const std::string stripes = kAssets + "obj/stripes.png";
  dir.write("m.obj", "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nusemtl glass\nf 1 2 3\nusemtl lamp\nf 1 3 2\n"
                     "usemtl bright\nf 2 3 1\n");
  dir.write("m.mtl", "newmtl glass\nillum 7\nNi 1.5\nTf 0.2 0.8 0.4\n"
                     "newmtl lamp\nKd 0.5 0.5 0.5\nmap_Ke " + stripes + "\n"
                     "newmtl bright\nKd 0 0 0\nKe 4 4 2\nmap_Ke " + stripes + "\n");
  Diagnostics diag;
  const std::optional<SceneDescription> s = load_scene(dir.str() + "/m.obj", {}, diag);
  ASSERT_TRUE(s) << diag.format();
  const MaterialDesc& glass = named(*s, ":glass");
  EXPECT_EQ(glass.type.value, MaterialType::Dielectric);
  EXPECT_TRUE(test::near(glass.transmittance.value, RGB(0.2f, 0.8f, 0.4f)));
  const MaterialDesc& lamp = named(*s, ":lamp");
  EXPECT_TRUE(test::near(lamp.emission.value, RGB(1.0f)));
  EXPECT_EQ(file_of(texture(*s, lamp.emission_texture)), stripes);
  EXPECT_FALSE(texture(*s, lamp.emission_texture).raw);  // a colour: sRGB-decoded
  const MaterialDesc& bright = named(*s, ":bright");
  EXPECT_TRUE(test::near(bright.emission.value, RGB(4.0f, 4.0f, 2.0f)));
  EXPECT_TRUE(bright.emission_texture);
  EXPECT_EQ(diag.warning_count(), 0) << diag.format();
}

// glTF: emissiveFactor (x KHR_materials_emissive_strength) times emissiveTexture,
// as the specification multiplies them (a texture with the default factor 0 emits nothing).
TEST(ImportGltfMaterials, EmissiveTextureTimesEmissiveFactor) {
  std::vector<AssetTexture> textures(1);
  textures[0].name = textures[0].resolved = kAssets + "gltf/base.png";
  AssetMaterial m;
  m.model = AssetMaterial::Model::MetallicRoughness;
  m.name = "glow";
  m.emission = RGB(2.0f, 1.0f, 0.5f);
  m.emission_map.texture = 0;
  MappedMaterial out = map_asset_material(m, textures);
  EXPECT_TRUE(test::near(out.desc.emission.value, RGB(2.0f, 1.0f, 0.5f)));
  ASSERT_EQ(out.textures.size(), 1u);
  EXPECT_EQ(out.textures[0].slot, TextureSlot::Emission);
  EXPECT_FALSE(out.textures[0].data);
  EXPECT_TRUE(out.notes.empty());
  m.emission = RGB(0.0f);
  out = map_asset_material(m, textures);
  EXPECT_TRUE(out.desc.emission.value.is_black());
  EXPECT_TRUE(out.textures.empty());
}

TEST(ImportGltfMaterials, MetallicRoughnessMaskNormalMapAndBlend) {
  for (const char* file : {"gltf/pbr.gltf", "gltf/pbr.glb"}) {
    SCOPED_TRACE(file);
    Diagnostics diag;
    const std::optional<SceneDescription> s = load_scene(kAssets + file, {}, diag);
    ASSERT_TRUE(s) << diag.format();
    // Every glTF material is glTF's own metallic-roughness blend.
    for (const char* name : {":masked", ":metal_rough", ":plastic", ":half_metal", ":blend"})
      EXPECT_EQ(named(*s, name).type.value, MaterialType::MetallicRoughness) << name;
    // MASK: the base colour texture's alpha (the same texture as the colour) against alphaCutoff.
    const MaterialDesc& masked = named(*s, ":masked");
    ASSERT_TRUE(masked.alpha_texture && masked.reflectance.texture);
    EXPECT_EQ(*masked.alpha_texture, *masked.reflectance.texture);
    EXPECT_FALSE(texture(*s, masked.reflectance.texture).raw);
    EXPECT_FLOAT_EQ(masked.alpha_cutoff, 0.5f);
    EXPECT_FLOAT_EQ(masked.uroughness.value.value, 1.0f);
    EXPECT_FLOAT_EQ(masked.metallic.value.value, 0.0f);
    EXPECT_FALSE(masked.metallic.texture);
    EXPECT_FLOAT_EQ(masked.ior.value, 1.5f);  // F0 0.04
    // A metal: base colour (0.9, 0.6, 0.3), metallic 1 x the texture's blue channel, alpha = (0.8 x G)^2, the normal map at scale 0.5.
    const MaterialDesc& metal = named(*s, ":metal_rough");
    EXPECT_TRUE(test::near(metal.reflectance.value.value, RGB(0.9f, 0.6f, 0.3f)));
    EXPECT_FLOAT_EQ(metal.metallic.value.value, 1.0f);
    EXPECT_EQ(metal.metallic.channel, 2);
    EXPECT_FALSE(metal.metallic.squared);
    EXPECT_EQ(metal.metallic.texture, metal.uroughness.texture);
    EXPECT_TRUE(texture(*s, metal.metallic.texture).raw);
    EXPECT_FALSE(metal.remap_roughness.value);
    EXPECT_NEAR(metal.uroughness.value.value, 0.64f, 1e-6f);
    EXPECT_EQ(metal.uroughness.channel, 1);
    EXPECT_TRUE(metal.uroughness.squared);
    EXPECT_TRUE(texture(*s, metal.uroughness.texture).raw);
    EXPECT_TRUE(texture(*s, metal.normal_map).raw);
    EXPECT_FLOAT_EQ(metal.normal_scale, 0.5f);
    const MaterialDesc& plastic = named(*s, ":plastic");
    EXPECT_TRUE(test::near(plastic.reflectance.value.value, RGB(0.2f, 0.4f, 0.8f)));
    EXPECT_FLOAT_EQ(plastic.metallic.value.value, 0.0f);
    EXPECT_NEAR(plastic.uroughness.value.value, 0.25f, 1e-6f);
    // Metallic 0.5 x the metallic texture's blue channel: the blend, per texel, without a warning.
    const MaterialDesc& half = named(*s, ":half_metal");
    EXPECT_FLOAT_EQ(half.metallic.value.value, 0.5f);
    EXPECT_EQ(half.metallic.channel, 2);
    EXPECT_TRUE(half.metallic.texture);
    const std::string text = diag.format();
    EXPECT_EQ(text.find("metallic"), std::string::npos) << text;
    EXPECT_EQ(text.find("per texel"), std::string::npos) << text;
    // BLEND: alpha an opacity (baseColorFactor's alpha 0.3), not a cutout; MASK is not blended.
    const MaterialDesc& blend = named(*s, ":blend");
    EXPECT_FLOAT_EQ(blend.alpha.value, 0.3f);
    EXPECT_TRUE(blend.alpha_blend.value);
    EXPECT_FALSE(masked.alpha_blend.value);
    EXPECT_EQ(text.find("BLEND"), std::string::npos) << text;
  }
}

}  // namespace
}  // namespace pt
