// The native format's microfacet materials (docs/scene-format.md): every key
// read into the description, the conductor presets, textured parameters
// (registered once per file and per encoding, colours sRGB-decoded and data
// raw), and the defaults. The errors are in tests/bad-scenes/microfacet-materials.
#include <gtest/gtest.h>

#include "scene/metal_presets.h"
#include "scene_test_util.h"

namespace pt {
namespace {

using test::near;
using test::TempDir;

std::string native(const std::string& materials, const std::string& shapes) {
  return R"({ "format": "pathtracer-scene", "version": 1,
  "camera": { "position": [0, 1, 5], "look_at": [0, 1, 0] },
  "materials": )" + materials + R"(, "shapes": )" + shapes + "}\n";
}

std::string spheres(int n) {
  const char* names[] = {"a", "b", "c", "d", "e", "f"};
  std::string s = "[";
  for (int i = 0; i < n; ++i)
    s += std::string(i ? ", " : "") + R"({ "type": "sphere", "center": [)" + std::to_string(3 * i) +
         R"(, 0, 0], "radius": 1, "material": ")" + names[i] + "\" }";
  return s + "]";
}

TEST(MaterialKeys, MicrofacetTypesReadTheirKeys) {
  TempDir dir;
  dir.write("rough.png", "x");
  dir.write("colour.png", "x");
  dir.write("normals.png", "x");
  const std::string path = dir.write("scene.json", native(R"({
    "a": { "type": "conductor", "metal": "Au", "roughness": 0.2 },
    "b": { "type": "conductor", "eta": [0.2, 0.9, 1.1], "k": [3.9, 2.4, 2.1], "uroughness": 0.1, "vroughness": 0.4,
           "remaproughness": false },
    "c": { "type": "conductor", "reflectance": { "texture": "colour.png", "scale": [1, 0.8, 0.6] },
           "roughness": { "texture": "rough.png", "scale": 0.5 } },
    "d": { "type": "dielectric", "roughness": 0.05, "normalmap": "normals.png" },
    "e": { "type": "coateddiffuse", "reflectance": { "texture": "colour.png" }, "ior": 1.4,
           "displacement": { "texture": "colour.png", "scale": 0.01 } },
    "f": { "type": "conductor" }
  })", spheres(6)));
  Diagnostics diag;
  const auto s = load_scene(path, LoadOptions{}, diag);
  ASSERT_TRUE(s) << diag.format();
  ASSERT_EQ(s->materials.size(), 6u);
  const MaterialDesc &a = s->materials[0], &b = s->materials[1], &c = s->materials[2], &d = s->materials[3],
                     &e = s->materials[4], &f = s->materials[5];
  EXPECT_EQ(a.type.value, MaterialType::Conductor);
  EXPECT_TRUE(near(a.eta.value, find_metal_preset("Au")->eta));
  EXPECT_TRUE(near(a.k.value, find_metal_preset("Au")->k));
  EXPECT_EQ(a.uroughness.value.value, 0.2f);
  EXPECT_EQ(a.vroughness.value.value, 0.2f);
  EXPECT_TRUE(a.remap_roughness.value);
  EXPECT_FALSE(a.schlick);
  EXPECT_TRUE(near(b.eta.value, RGB(0.2f, 0.9f, 1.1f)));
  EXPECT_EQ(b.uroughness.value.value, 0.1f);
  EXPECT_EQ(b.vroughness.value.value, 0.4f);
  EXPECT_FALSE(b.remap_roughness.value);
  EXPECT_TRUE(c.schlick);
  EXPECT_TRUE(near(c.reflectance.value, RGB(1, 0.8f, 0.6f)));
  EXPECT_EQ(c.uroughness.value.value, 0.5f);
  ASSERT_TRUE(c.reflectance.texture && c.uroughness.texture && c.vroughness.texture);
  EXPECT_EQ(c.uroughness.texture, c.vroughness.texture);
  // Colour textures are decoded from sRGB, data textures are raw.
  EXPECT_FALSE(s->textures[static_cast<std::size_t>(*c.reflectance.texture)].raw);
  EXPECT_TRUE(s->textures[static_cast<std::size_t>(*c.uroughness.texture)].raw);
  EXPECT_EQ(d.type.value, MaterialType::Dielectric);
  EXPECT_EQ(d.ior.value, 1.5f);  // the dielectric's default
  ASSERT_TRUE(d.normal_map);
  EXPECT_TRUE(s->textures[static_cast<std::size_t>(*d.normal_map)].raw);
  EXPECT_EQ(e.ior.value, 1.4f);
  EXPECT_EQ(e.reflectance.texture, c.reflectance.texture);  // colour.png, sRGB, once
  ASSERT_TRUE(e.displacement && e.displacement->texture);
  EXPECT_NE(e.displacement->texture, e.reflectance.texture);  // colour.png read raw: an entry of its own
  EXPECT_TRUE(s->textures[static_cast<std::size_t>(*e.displacement->texture)].raw);
  EXPECT_EQ(e.displacement->value.value, 0.01f);
  // A conductor without a preset or an index is copper, as pbrt-v4's.
  EXPECT_TRUE(near(f.eta.value, find_metal_preset("Cu")->eta));
  EXPECT_EQ(s->textures.size(), 4u);
  EXPECT_EQ(diag.warning_count(), 0) << diag.format();
}

// Textured parameters take every texture reference "texture" and "alpha" take
// (a name in "textures", an image file, an inline object): procedural textures
// included. Data parameters read an image without "encoding" raw: a named
// image used as colour and as data is two entries.
TEST(MaterialKeys, TexturedParametersTakeTextureReferences) {
  TempDir dir;
  dir.write("colour.png", "x");
  const std::string path = dir.write("scene.json", native(R"({
    "a": { "type": "conductor", "roughness": { "texture": "grain", "scale": 0.5 }, "reflectance": { "texture": "mask" } },
    "b": { "type": "coateddiffuse", "roughness": { "texture": "mask" }, "alpha": "mask",
           "normalmap": { "type": "checker", "scale": 8 } },
    "c": { "type": "dielectric", "uroughness": { "texture": { "type": "checker", "scale": 4 } }, "vroughness": 0.3,
           "displacement": { "texture": "srgb_mask", "scale": 0.02 } }
  }, "textures": {
    "grain": { "type": "noise", "octaves": 3 },
    "mask": { "type": "image", "file": "colour.png" },
    "srgb_mask": { "type": "image", "file": "colour.png", "encoding": "srgb" }
  })", spheres(3)));
  Diagnostics diag;
  const auto s = load_scene(path, LoadOptions{}, diag);
  ASSERT_TRUE(s) << diag.format();
  const MaterialDesc &a = s->materials[0], &b = s->materials[1], &c = s->materials[2];
  const auto tex = [&](const std::optional<int>& t) -> const TextureDesc& {
    return s->textures[static_cast<std::size_t>(*t)];
  };
  ASSERT_TRUE(a.uroughness.texture && a.reflectance.texture && b.uroughness.texture && b.alpha_texture &&
              b.normal_map && c.uroughness.texture && c.displacement && c.displacement->texture);
  EXPECT_EQ(tex(a.uroughness.texture).type, TextureType::Noise);
  EXPECT_EQ(a.uroughness.texture, a.vroughness.texture);
  EXPECT_EQ(a.uroughness.value.value, 0.5f);
  // "mask" as colour (a's reflectance, b's alpha: one entry) and as data (b's roughness: its own, raw).
  EXPECT_FALSE(tex(a.reflectance.texture).raw);
  EXPECT_EQ(b.alpha_texture, a.reflectance.texture);
  EXPECT_NE(b.uroughness.texture, a.reflectance.texture);
  EXPECT_TRUE(tex(b.uroughness.texture).raw);
  EXPECT_EQ(tex(b.uroughness.texture).resolved, tex(a.reflectance.texture).resolved);
  EXPECT_EQ(tex(b.normal_map).type, TextureType::Checker);
  EXPECT_EQ(tex(c.uroughness.texture).type, TextureType::Checker);
  EXPECT_FALSE(c.vroughness.texture);
  // An explicit "encoding" is kept even for data.
  EXPECT_FALSE(tex(c.displacement->texture).raw);
  EXPECT_EQ(diag.warning_count(), 0) << diag.format();
}

TEST(MaterialKeys, EveryPresetIsListedAndFound) {
  const std::vector<std::string> names = metal_preset_names();
  for (const char* m : {"Ag", "Al", "Au", "Cr", "Cu", "Fe", "Ni", "Pt", "Ti", "W"}) {
    ASSERT_TRUE(find_metal_preset(m)) << m;
    EXPECT_NE(std::find(names.begin(), names.end(), m), names.end()) << m;
    const MetalPreset p = *find_metal_preset(m);
    for (int c = 0; c < 3; ++c) {
      EXPECT_GT(p.eta[c], 0.0f) << m;
      EXPECT_GT(p.k[c], 0.0f) << m;
    }
  }
  EXPECT_FALSE(find_metal_preset("gold"));
}

}  // namespace
}  // namespace pt
