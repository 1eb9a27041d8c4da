// The spellings course files written by students use for what the courses
// left open (area lights, thin lens, meshes, refraction, samples), each on a
// small file of our own, and the messages for what is really wrong
// (docs/scene-format.md, "Path of Light files" and "CGR files").
#include <gtest/gtest.h>

#include <string>

#include "scene_test_util.h"

namespace pt {
namespace {

using test::geometry_of;
using test::near;
using test::TempDir;

// A Path of Light file: a camera looking down +y, `lights` and `shapes` inside "scene", `top` at the top level.
std::string pol(const std::string& lights, const std::string& shapes, const std::string& camera_extra = "",
                const std::string& top = "") {
  return "{" + top + R"(
"camera": { "type": "pinhole", "width": 8, "height": 8, "fov": 40,
            "position": [0, -5, 1], "lookat": [0, 1, 0], "up": [0, 0, 1])" +
         camera_extra + R"( },
"scene": { "backgroundcolor": [0.1, 0.1, 0.1],
  "lightsources": [ )" + lights + R"( ],
  "shapes": [ )" + shapes + R"( ] }
})";
}

const std::string kPointLight = R"({ "type": "pointlight", "position": [0, 0, 3], "id": [1, 1, 1], "is": [1, 1, 1] })";
const std::string kSphere = R"({ "type": "sphere", "center": [0, 2, 0], "radius": 0.5 })";

struct Loaded {
  Diagnostics diag;
  std::optional<SceneDescription> scene;
  bool has(Severity severity, const std::string& text) const {
    for (const Diagnostic& d : diag.all())
      if (d.severity == severity && d.message.find(text) != std::string::npos) return true;
    return false;
  }
  // "line:col" of the first diagnostic containing `text`.
  std::string where(const std::string& text) const {
    for (const Diagnostic& d : diag.all())
      if (d.message.find(text) != std::string::npos) return std::to_string(d.where.line) + ":" + std::to_string(d.where.col);
    return "none";
  }
};

Loaded load(const std::string& text, const std::string& path = "course.json") {
  Loaded l;
  l.scene = load_scene_from_string(path, text, LoadOptions{}, l.diag);
  return l;
}

// A scene of one sphere lit by `light`.
Loaded load_lit(const std::string& light) { return load(pol(light, kSphere)); }

const MaterialDesc& material_of(const SceneDescription& s, std::size_t shape) {
  return s.materials[static_cast<std::size_t>(s.shapes[shape].material)];
}

// ---------------------------------------------------------------- area lights

// The lamp's radiance: seen face-on from afar it is as bright as the point
// light of the same "id" (radiant intensity id / 4): L * area = id / 4.
TEST(CourseAreaLights, QuadCornersBecomeATwoSidedEmissiveQuad) {
  const Loaded l = load_lit(R"({ "type": "arealight", "v0": [-1, 0, 3], "v1": [1, 0, 3], "v2": [1, 2, 3],
                                 "v3": [-1, 2, 3], "id": [8, 8, 8], "is": [8, 8, 8], "samples": 16,
                                 "method": "jittered" })");
  ASSERT_TRUE(l.scene) << l.diag.format();
  EXPECT_EQ(l.diag.all().size(), 0u) << l.diag.format();
  ASSERT_EQ(l.scene->shapes.size(), 2u);
  const Quad& q = geometry_of<Quad>(*l.scene, 1);
  EXPECT_TRUE(near(q.v[2], Vec3f(1, 2, 3)));
  const MaterialDesc& m = material_of(*l.scene, 1);
  EXPECT_TRUE(near(m.emission.value, RGB(0.5f, 0.5f, 0.5f)));  // 8 / 4 / (2 x 2)
  EXPECT_TRUE(m.two_sided.value);
  EXPECT_EQ(m.kd.value, 0.0f);  // the lamp reflects nothing
  EXPECT_TRUE(l.scene->lights.empty());
}

TEST(CourseAreaLights, TriangleCornersAndTheIntensityKey) {
  const Loaded l = load_lit(R"({ "type": "arealight", "v0": [0, 0, 3], "v1": [2, 0, 3], "v2": [0, 2, 3],
                                 "intensity": [4, 2, 4] })");
  ASSERT_TRUE(l.scene) << l.diag.format();
  EXPECT_EQ(l.diag.all().size(), 0u) << l.diag.format();
  const TriangleMesh& t = geometry_of<TriangleMesh>(*l.scene, 1);
  EXPECT_EQ(t.triangle_count(), 1u);
  EXPECT_TRUE(near(material_of(*l.scene, 1).emission.value, RGB(0.5f, 0.25f, 0.5f)));  // area 2
}

TEST(CourseAreaLights, ParallelogramFromThreeCornersWarnsWhichCornerIsShared) {
  const Loaded l = load_lit(R"({ "type": "arealight", "c1": [0, 0, 3], "c2": [1, 0, 3], "c3": [0, 1, 3],
                                 "id": [1, 1, 1], "is": [1, 1, 1] })");
  ASSERT_TRUE(l.scene) << l.diag.format();
  EXPECT_TRUE(l.has(Severity::Warning, "c1 the corner between c2 and c3")) << l.diag.format();
  const Quad& q = geometry_of<Quad>(*l.scene, 1);
  EXPECT_TRUE(near(q.v[0], Vec3f(0, 0, 3)));
  EXPECT_TRUE(near(q.v[1], Vec3f(1, 0, 3)));
  EXPECT_TRUE(near(q.v[2], Vec3f(1, 1, 3)));
  EXPECT_TRUE(near(q.v[3], Vec3f(0, 1, 3)));
}

TEST(CourseAreaLights, CgrStyleRectangleAroundItsPosition) {
  const Loaded l = load_lit(R"({ "type": "arealight", "position": [0, 1, 3], "u": [2, 0, 0], "v": [0, 1, 0],
                                 "width": 2, "height": 1, "id": [2, 2, 2], "is": [2, 2, 2] })");
  ASSERT_TRUE(l.scene) << l.diag.format();
  EXPECT_TRUE(l.has(Severity::Warning, "'position' taken as the centre")) << l.diag.format();
  const Quad& q = geometry_of<Quad>(*l.scene, 1);
  EXPECT_TRUE(near(q.v[0], Vec3f(-1, 0.5f, 3)));
  EXPECT_TRUE(near(q.v[2], Vec3f(1, 1.5f, 3)));
  EXPECT_TRUE(near(material_of(*l.scene, 1).emission.value, RGB(0.25f, 0.25f, 0.25f)));
}

TEST(CourseAreaLights, ShapeIdMakesANamedShapeEmit) {
  const Loaded l = load(pol(R"({ "type": "arealight", "shapeid": "lamp", "id": [4, 4, 4], "is": [4, 4, 4] })",
                            kSphere + R"(, { "type": "sphere", "id": "lamp", "center": [0, 2, 2], "radius": 1,
                                             "material": { "diffusecolor": [1, 0, 0] } })"));
  ASSERT_TRUE(l.scene) << l.diag.format();
  EXPECT_EQ(l.diag.all().size(), 0u) << l.diag.format();
  ASSERT_EQ(l.scene->shapes.size(), 2u);
  const MaterialDesc& m = material_of(*l.scene, 1);
  EXPECT_NEAR(m.emission.value.r, 1.0f / kPi, 1e-6f);  // 4 / 4 / (pi r^2): a sphere shows its disc
  EXPECT_FALSE(m.two_sided.value);
  EXPECT_TRUE(near(m.diffuse.value, RGB(1, 0, 0)));  // its own material is kept
  EXPECT_TRUE(near(material_of(*l.scene, 0).emission.value, RGB(0, 0, 0)));
  // A name that no shape has is an error, with the likely one.
  const Loaded bad = load(pol(R"({ "type": "arealight", "shapeid": "lmap", "id": [4, 4, 4], "is": [4, 4, 4] })",
                              R"({ "type": "sphere", "id": "lamp", "center": [0, 2, 2], "radius": 1 })"));
  EXPECT_FALSE(bad.scene);
  EXPECT_TRUE(bad.has(Severity::Error, "no shape has the id 'lmap'")) << bad.diag.format();
  EXPECT_TRUE(bad.has(Severity::Error, "did you mean 'lamp'?")) << bad.diag.format();
}

TEST(CourseAreaLights, WithoutAShapeOrIntensityTheyAreErrors) {
  const Loaded l = load_lit(R"({ "type": "arealight", "center": [0, 0, 3], "id": [1, 1, 1] })");
  EXPECT_FALSE(l.scene);
  EXPECT_TRUE(l.has(Severity::Error, "an area light needs its shape")) << l.diag.format();
  const Loaded dark = load_lit(R"({ "type": "arealight", "v0": [0, 0, 3], "v1": [2, 0, 3], "v2": [0, 2, 3] })");
  EXPECT_FALSE(dark.scene);
  EXPECT_TRUE(dark.has(Severity::Error, "missing key 'id' in area light")) << dark.diag.format();
}

TEST(CourseAreaLights, DiffuseAndSpecularIntensitiesMustAgree) {
  const Loaded l = load_lit(R"({ "type": "arealight", "v0": [0, 0, 3], "v1": [2, 0, 3], "v2": [0, 2, 3],
                                 "id": [1, 1, 1], "is": [2, 2, 2] })");
  ASSERT_TRUE(l.scene) << l.diag.format();
  EXPECT_TRUE(l.has(Severity::Warning, "'is' differs from 'id'")) << l.diag.format();
}

// "samples": the classic integrator's samples of the lamp per shading point
// (kept on its material; 0 when absent: the integrator's default).
TEST(CourseAreaLights, SamplesAreTheClassicIntegratorsLightSamples) {
  const std::string corners = R"("type": "arealight", "v0": [0, 0, 3], "v1": [2, 0, 3], "v2": [0, 2, 3], "id": [1, 1, 1])";
  const Loaded nine = load_lit("{ " + corners + R"(, "samples": 9 })");
  ASSERT_TRUE(nine.scene) << nine.diag.format();
  EXPECT_EQ(material_of(*nine.scene, 1).light_samples.value, 9);
  const Loaded plain = load_lit("{ " + corners + " }");
  ASSERT_TRUE(plain.scene) << plain.diag.format();
  EXPECT_EQ(material_of(*plain.scene, 1).light_samples.value, 0);
  const Loaded shape = load(pol(R"({ "type": "arealight", "shapeid": "lamp", "id": [4, 4, 4], "samples": 4 })",
                                R"({ "type": "sphere", "id": "lamp", "center": [0, 2, 0], "radius": 0.5 })"));
  ASSERT_TRUE(shape.scene) << shape.diag.format();
  EXPECT_EQ(material_of(*shape.scene, 0).light_samples.value, 4);
  const Loaded none = load_lit("{ " + corners + R"(, "samples": 0 })");
  EXPECT_FALSE(none.scene);
  EXPECT_TRUE(none.has(Severity::Error, "'samples' must be at least 1")) << none.diag.format();
}

// ---------------------------------------------------------------- lights and types: messages

TEST(CourseMessages, AScenelWithoutLightWarnsThatItWillBeDark) {
  const Loaded l = load_lit(R"({ "type": "spotlight", "position": [0, 0, 3] })");
  ASSERT_TRUE(l.scene) << l.diag.format();
  EXPECT_TRUE(l.has(Severity::Warning, "unsupported light type 'spotlight' (ignored)")) << l.diag.format();
  EXPECT_TRUE(l.has(Severity::Warning, "the scene has no light source")) << l.diag.format();
  const Loaded lit = load(pol(kPointLight, kSphere));
  EXPECT_FALSE(lit.has(Severity::Warning, "no light source")) << lit.diag.format();
}

TEST(CourseMessages, ATypeOneOrTwoEditsFromAKnownOneIsAnError) {
  const Loaded l = load(pol(kPointLight, R"({ "type": "spehre", "center": [0, 2, 0], "radius": 0.5 })"));
  EXPECT_FALSE(l.scene);
  EXPECT_TRUE(l.has(Severity::Error, "unknown shape type 'spehre'; did you mean 'sphere'?")) << l.diag.format();
  const Loaded light = load(pol(R"({ "type": "pointligth", "position": [0, 0, 3], "id": [1, 1, 1], "is": [1, 1, 1] })",
                                kSphere));
  EXPECT_FALSE(light.scene);
  EXPECT_TRUE(light.has(Severity::Error, "did you mean 'pointlight'?")) << light.diag.format();
  // Anything else is a feature of another course variant: skipped with a warning.
  const Loaded cone = load(pol(kPointLight, kSphere + R"(, { "type": "cone", "radius": 1 })"));
  ASSERT_TRUE(cone.scene) << cone.diag.format();
  EXPECT_TRUE(cone.has(Severity::Warning, "unsupported shape type 'cone' (ignored)")) << cone.diag.format();
  EXPECT_EQ(cone.scene->shapes.size(), 1u);
}

TEST(CourseMessages, SuggestionsThatMisledAreGone) {
  // uv0 on a triangle is a texture coordinate, not a typo of the corner v0.
  const Loaded uv = load(pol(kPointLight, R"({ "type": "triangle", "v0": [0, 2, 0], "v1": [1, 2, 0],
                                               "v2": [0, 2, 1], "uv0": [0, 0] })"));
  ASSERT_TRUE(uv.scene) << uv.diag.format();
  EXPECT_TRUE(uv.has(Severity::Warning, "unknown key 'uv0'")) << uv.diag.format();
  EXPECT_FALSE(uv.has(Severity::Warning, "did you mean")) << uv.diag.format();
  // tPath on a mesh belongs in its material; it is not a typo of mPath.
  const Loaded tex = load(pol(kPointLight, R"({ "type": "mesh", "vertices": [[0, 2, 0], [1, 2, 0], [0, 2, 1]],
                                                "faces": [[0, 1, 2]], "tPath": "wood.png" })"));
  ASSERT_TRUE(tex.scene) << tex.diag.format();
  EXPECT_TRUE(tex.has(Severity::Warning, "'tPath' is a material key")) << tex.diag.format();
  EXPECT_FALSE(tex.has(Severity::Warning, "mPath")) << tex.diag.format();
  // A zero lookat is a zero view direction, reported once.
  const Loaded zero = load(pol(kPointLight, kSphere).replace(pol(kPointLight, kSphere).find("[0, 1, 0]"), 9, "[0, 0, 0]"));
  EXPECT_FALSE(zero.scene);
  EXPECT_EQ(zero.diag.error_count(), 1) << zero.diag.format();
  EXPECT_TRUE(zero.has(Severity::Error, "'lookat' is the camera's view direction")) << zero.diag.format();
  // A mesh file under a key of the author's own is named, before any "missing key".
  const Loaded key = load(pol(kPointLight, R"({ "type": "trimesh", "meshFile": "bunny.ply" })"));
  EXPECT_FALSE(key.scene);
  EXPECT_EQ(key.diag.error_count(), 1) << key.diag.format();
  EXPECT_TRUE(key.has(Severity::Error, "'meshFile' is not a key for the mesh's file; use one of 'filename', "
                                       "'mPath', 'modelpath', 'path' or 'plyPath'"))
      << key.diag.format();
  EXPECT_EQ(key.where("meshFile"), "6:36");
}

TEST(CourseMessages, PointLightIntensityAndCgrTypes) {
  // "intensity" stands for both of a Path of Light point light's id and is.
  const Loaded l = load(pol(R"({ "type": "pointlight", "position": [0, 0, 3], "intensity": [4, 4, 4] })", kSphere));
  ASSERT_TRUE(l.scene) << l.diag.format();
  EXPECT_EQ(l.diag.all().size(), 0u) << l.diag.format();
  const PointLightDesc& p = test::point_light(*l.scene, 0);
  EXPECT_NEAR(p.intensity.value.r, 1.0f / kPi, 1e-6f);
  EXPECT_NEAR(p.specular_intensity.value.r, 1.0f / kPi, 1e-6f);
  // Both spellings at once: an error.
  const Loaded both = load_lit(R"({ "type": "pointlight", "position": [0, 0, 3], "intensity": [4, 4, 4],
                                    "id": [1, 1, 1], "is": [1, 1, 1] })");
  EXPECT_FALSE(both.scene);
  EXPECT_TRUE(both.has(Severity::Error, "'intensity' stands for both 'id' and 'is'")) << both.diag.format();
  const Loaded area = load_lit(R"({ "type": "arealight", "v0": [0, 0, 3], "v1": [2, 0, 3], "v2": [0, 2, 3],
                                    "intensity": [4, 4, 4], "id": [1, 1, 1] })");
  EXPECT_FALSE(area.scene);
  EXPECT_TRUE(area.has(Severity::Error, "say the same thing")) << area.diag.format();
  // A camera without a type is a pinhole, as before.
  std::string text = pol(kPointLight, kSphere);
  const Loaded untyped = load(text.replace(text.find(R"("type": "pinhole", )"), 19, ""));
  ASSERT_TRUE(untyped.scene) << untyped.diag.format();
  EXPECT_EQ(untyped.diag.all().size(), 0u) << untyped.diag.format();
  // The CGR family: a close type is an error, a far one a warning.
  const std::string cgr = R"({ "rendermode": "phong",
  "camera": { "type": "pinhole", "width": 8, "height": 8, "position": [0, 0, 0], "lookAt": [0, 0, 1],
              "upVector": [0, 1, 0], "fov": 45 },
  "scene": { "lightsources": [ { "type": "pointlight", "position": [0, 1, 0], "intensity": [1, 1, 1] } ],
             "shapes": [ { "type": "TYPE", "center": [0, 0, 3], "radius": 1 } ] } })";
  const Loaded typo = load(std::string(cgr).replace(cgr.find("TYPE"), 4, "cylindre"));
  EXPECT_FALSE(typo.scene);
  EXPECT_TRUE(typo.has(Severity::Error, "unknown shape type 'cylindre'; did you mean 'cylinder'?")) << typo.diag.format();
  const Loaded other = load(std::string(cgr).replace(cgr.find("TYPE"), 4, "torus"));
  ASSERT_TRUE(other.scene) << other.diag.format();
  EXPECT_TRUE(other.has(Severity::Warning, "unsupported shape type 'torus' (ignored)")) << other.diag.format();
}

// ---------------------------------------------------------------- zig-zag quads

TEST(CourseQuads, ARectangleInZigZagOrderIsReorderedWithAWarningAtTheCorner) {
  const std::string text = pol(kPointLight, R"({ "type": "plane",
    "v0": [-1, 3, 0], "v1": [1, 3, 0], "v2": [-1, 3, 2], "v3": [1, 3, 2] })");
  const Loaded l = load(text);
  ASSERT_TRUE(l.scene) << l.diag.format();
  EXPECT_EQ(l.diag.error_count(), 0) << l.diag.format();
  EXPECT_TRUE(l.has(Severity::Warning, "zig-zag order: taken as v0, v1, v3, v2")) << l.diag.format();
  EXPECT_EQ(l.where("zig-zag"), "7:46");  // the corner v2, not the shape's '{'
  const Quad& q = geometry_of<Quad>(*l.scene, 0);
  EXPECT_TRUE(near(q.v[2], Vec3f(1, 3, 2)));
  EXPECT_TRUE(near(q.v[3], Vec3f(-1, 3, 2)));
  // The other zig-zag: v0 v2 v1 v3 go round it.
  const Loaded other = load(pol(kPointLight, R"({ "type": "plane",
    "v0": [-1, 3, 0], "v1": [1, 3, 2], "v2": [1, 3, 0], "v3": [-1, 3, 2] })"));
  ASSERT_TRUE(other.scene) << other.diag.format();
  EXPECT_EQ(other.where("zig-zag"), "7:29");  // v1
  // Four corners that no order makes a rectangle stay an error.
  const Loaded bow = load(pol(kPointLight, R"({ "type": "plane",
    "v0": [-1, 3, 0], "v1": [1, 3, 0], "v2": [-1, 3, 2], "v3": [1.5, 3, 2] })"));
  EXPECT_FALSE(bow.scene);
  EXPECT_TRUE(bow.has(Severity::Error, "not in perimeter order")) << bow.diag.format();
}

// ---------------------------------------------------------------- thin lens

struct LensCase {
  const char* name;
  const char* keys;
  float radius, distance;
  int warnings;
};

class CourseThinLens : public ::testing::TestWithParam<LensCase> {};

TEST_P(CourseThinLens, SpellingsOfTheLens) {
  const LensCase& c = GetParam();
  std::string text = pol(kPointLight, kSphere, std::string(", ") + c.keys);
  text.replace(text.find("\"pinhole\""), 9, "\"thinlens\"");
  const Loaded l = load(text);
  ASSERT_TRUE(l.scene) << l.diag.format();
  EXPECT_EQ(l.diag.warning_count(), c.warnings) << l.diag.format();
  EXPECT_EQ(l.scene->camera.type, CameraType::ThinLens);
  EXPECT_FLOAT_EQ(l.scene->camera.lens_radius.value, c.radius);
  EXPECT_FLOAT_EQ(l.scene->camera.focus_distance.value, c.distance);
}

INSTANTIATE_TEST_SUITE_P(
    Keys, CourseThinLens,
    ::testing::Values(LensCase{"ours", R"("lensradius": 0.1, "focusdistance": 5)", 0.1f, 5.0f, 0},
                      LensCase{"camel", R"("lensRadius": 0.1, "focalDistance": 5)", 0.1f, 5.0f, 0},
                      LensCase{"focal_length", R"("aperture": 0.2, "focal_length": 4)", 0.1f, 4.0f, 2},
                      LensCase{"focal_d", R"("aperture": 0.2, "focal": 3, "d": 1)", 0.1f, 3.0f, 3}),
    [](const ::testing::TestParamInfo<LensCase>& p) { return std::string(p.param.name); });

TEST(CourseCamera, CgrFiniteApertureAndUnknownTypes) {
  const Loaded cgr = load(R"({ "rendermode": "phong",
  "camera": { "type": "finite-aperture", "width": 8, "height": 8, "position": [0, 0, 0], "lookAt": [0, 0, 1],
              "upVector": [0, 1, 0], "fov": 45, "aperture": 0.5, "focalDistance": 2 },
  "scene": { "lightsources": [ { "type": "pointlight", "position": [0, 1, 0], "intensity": [1, 1, 1] } ],
             "shapes": [] } })");
  ASSERT_TRUE(cgr.scene) << cgr.diag.format();
  EXPECT_EQ(cgr.scene->camera.type, CameraType::ThinLens);
  EXPECT_FLOAT_EQ(cgr.scene->camera.lens_radius.value, 0.25f);
  EXPECT_FLOAT_EQ(cgr.scene->camera.focus_distance.value, 2.0f);
  EXPECT_EQ(cgr.diag.warning_count(), 1) << cgr.diag.format();  // aperture is a diameter
  // Unknown, with an obvious pinhole fallback: a warning.
  std::string text = pol(kPointLight, kSphere);
  const Loaded persp = load(std::string(text).replace(text.find("\"pinhole\""), 9, "\"perspective\""));
  ASSERT_TRUE(persp.scene) << persp.diag.format();
  EXPECT_TRUE(persp.has(Severity::Warning, "unknown camera type 'perspective'; rendered with a pinhole camera"));
  EXPECT_EQ(persp.scene->camera.type, CameraType::Pinhole);
  // A typo of a known type: an error.
  const Loaded typo = load(std::string(text).replace(text.find("\"pinhole\""), 9, "\"pinhloe\""));
  EXPECT_FALSE(typo.scene);
  EXPECT_TRUE(typo.has(Severity::Error, "did you mean 'pinhole'?")) << typo.diag.format();
  // The known types with other case or separators ("thinLens", "Pinhole", "thin_lens"): read, with a warning.
  for (const char* spelt : {"thinLens", "Thin_Lens", "finiteAperture"}) {
    std::string lens = std::string(text).replace(text.find("\"pinhole\""), 9, std::string("\"") + spelt + "\"");
    const Loaded l = load(lens.replace(lens.find(R"("up": [0, 0, 1])"), 15, R"("up": [0, 0, 1], "lensRadius": 0.1, "focalDistance": 5)"));
    ASSERT_TRUE(l.scene) << spelt << l.diag.format();
    EXPECT_EQ(l.scene->camera.type, CameraType::ThinLens) << spelt;
    EXPECT_TRUE(l.has(Severity::Warning, std::string("camera type '") + spelt + "' read as 'thinlens'")) << l.diag.format();
  }
  const Loaded upper = load(std::string(text).replace(text.find("\"pinhole\""), 9, "\"Pinhole\""));
  ASSERT_TRUE(upper.scene) << upper.diag.format();
  EXPECT_EQ(upper.scene->camera.type, CameraType::Pinhole);
  EXPECT_TRUE(upper.has(Severity::Warning, "camera type 'Pinhole' read as 'pinhole'")) << upper.diag.format();
  // A thin lens without its lens keys names what is missing.
  const Loaded bare = load(std::string(text).replace(text.find("\"pinhole\""), 9, "\"thinlens\""));
  EXPECT_FALSE(bare.scene);
  EXPECT_TRUE(bare.has(Severity::Error, "a thin-lens camera needs its lens radius")) << bare.diag.format();
}

// ---------------------------------------------------------------- meshes

const char* kPly =
    "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
    "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";

TEST(CourseMeshes, EveryFileKeyAndBothShapeTypes) {
  TempDir dir;
  dir.write("m/tri.ply", kPly);
  dir.write("m/tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const Loaded l = load(pol(kPointLight, R"({ "type": "trimesh", "mPath": "m/tri.ply" },
    { "type": "mesh", "modelpath": "m/tri.ply" }, { "type": "trimesh", "plyPath": "m/tri.ply" },
    { "type": "mesh", "filename": "m/tri.ply" }, { "type": "mesh", "path": "m/tri.obj" })"),
                        dir.write("pol.json", ""));
  ASSERT_TRUE(l.scene) << l.diag.format();
  EXPECT_EQ(l.diag.all().size(), 0u) << l.diag.format();
  ASSERT_EQ(l.scene->shapes.size(), 5u);
  for (std::size_t i = 0; i < 5; ++i) EXPECT_EQ(geometry_of<TriangleMesh>(*l.scene, i).triangle_count(), 1u);
  EXPECT_EQ(l.scene->shapes[4].file, "m/tri.obj");
  // Two file keys on one mesh: an error.
  const Loaded two = load(pol(kPointLight, R"({ "type": "mesh", "mPath": "m/tri.ply", "path": "m/tri.ply" })"),
                          dir.write("pol2.json", ""));
  EXPECT_FALSE(two.scene);
  EXPECT_TRUE(two.has(Severity::Error, "say the same thing")) << two.diag.format();
}

TEST(CourseMeshes, PlacementIsBakedIntoTheVertices) {
  const std::string tri = R"("vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]], "faces": [[0, 1, 2]])";
  const Loaded l = load(pol(kPointLight, "{ \"type\": \"mesh\", " + tri + R"(, "pos": [1, 2, 3], "scale": 2 },
    { "type": "mesh", )" + tri + R"(, "center": [1, 2, 3], "sizeScale": [1, 2, 3] },
    { "type": "mesh", )" + tri + R"(, "locX": 5, "locZ": -1 })"));
  ASSERT_TRUE(l.scene) << l.diag.format();
  EXPECT_EQ(l.diag.all().size(), 0u) << l.diag.format();
  EXPECT_TRUE(near(geometry_of<TriangleMesh>(*l.scene, 0).positions[1], Vec3f(3, 2, 3)));
  EXPECT_TRUE(near(geometry_of<TriangleMesh>(*l.scene, 1).positions[2], Vec3f(1, 4, 3)));
  EXPECT_TRUE(near(geometry_of<TriangleMesh>(*l.scene, 2).positions[0], Vec3f(5, 0, -1)));
  const Loaded both = load(pol(kPointLight, "{ \"type\": \"mesh\", " + tri + R"(, "pos": [1, 2, 3], "locX": 1 })"));
  EXPECT_FALSE(both.scene);
  EXPECT_TRUE(both.has(Severity::Error, "'pos' and 'locX'/'locY'/'locZ' say the same thing")) << both.diag.format();
}

TEST(CourseMeshes, NormalsFromTheFileFollowTheScale) {
  TempDir dir;
  dir.write("n.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                     "property float z\nproperty float nx\nproperty float ny\nproperty float nz\n"
                     "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
                     "0 0 0 0.6 0.8 0\n1 0 0 0.6 0.8 0\n0 1 0 0.6 0.8 0\n3 0 1 2\n");
  const Loaded l = load(pol(kPointLight, R"({ "type": "mesh", "plyPath": "n.ply", "scale": [2, 1, 1] })"),
                        dir.write("pol.json", ""));
  ASSERT_TRUE(l.scene) << l.diag.format();
  const TriangleMesh& m = geometry_of<TriangleMesh>(*l.scene, 0);
  EXPECT_TRUE(near(m.positions[1], Vec3f(2, 0, 0)));
  ASSERT_EQ(m.normals.size(), 3u);
  EXPECT_TRUE(near(m.normals[0], normalize(Vec3f(0.3f, 0.8f, 0))));  // the inverse transpose of the scale
}

TEST(CourseMeshes, NumberedVerticesAndFaces) {
  const Loaded l = load(pol(kPointLight, R"({ "type": "trimesh", "v0": [0, 0, 0], "v1": [1, 0, 0], "v2": [1, 1, 0],
    "v3": [0, 1, 0], "f0": [0, 1, 2, 3], "f1": [0, 2, 1] })"));
  ASSERT_TRUE(l.scene) << l.diag.format();
  EXPECT_EQ(l.diag.all().size(), 0u) << l.diag.format();
  const TriangleMesh& m = geometry_of<TriangleMesh>(*l.scene, 0);
  EXPECT_EQ(m.positions.size(), 4u);
  EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3, 0, 2, 1}));  // the quad f0 as a fan
  const Loaded bad = load(pol(kPointLight, R"({ "type": "trimesh", "v0": [0, 0, 0], "v1": [1, 0, 0],
    "f0": [0, 1, 2] })"));
  EXPECT_FALSE(bad.scene);
  EXPECT_TRUE(bad.has(Severity::Error, "'f0' holds an index that is not a vertex")) << bad.diag.format();
}

// ---------------------------------------------------------------- refraction and samples

TEST(CourseMaterials, TransmissionWithEachSpellingOfTheIndex) {
  for (const char* key : {"eta", "ior", "refractiveIndex"}) {
    const Loaded l = load(pol(kPointLight, std::string(R"({ "type": "sphere", "center": [0, 2, 0], "radius": 0.5,
      "material": { "kt": 1, ")") + key + R"(": 1.33 } })"));
    ASSERT_TRUE(l.scene) << key << l.diag.format();
    EXPECT_EQ(l.diag.all().size(), 0u) << key << l.diag.format();
    const MaterialDesc& m = material_of(*l.scene, 0);
    EXPECT_TRUE(m.refractive.value) << key;
    EXPECT_FLOAT_EQ(m.ior.value, 1.33f) << key;
  }
  const Loaded half = load(pol(kPointLight, R"({ "type": "sphere", "center": [0, 2, 0], "radius": 0.5,
      "material": { "kt": 0.5 } })"));
  ASSERT_TRUE(half.scene) << half.diag.format();
  EXPECT_TRUE(half.has(Severity::Warning, "kt 0.5 taken as a fully transparent dielectric")) << half.diag.format();
  EXPECT_TRUE(half.has(Severity::Warning, "glass's 1.5 is used")) << half.diag.format();
  EXPECT_FLOAT_EQ(material_of(*half.scene, 0).ior.value, 1.5f);
  const Loaded opaque = load(pol(kPointLight, R"({ "type": "sphere", "center": [0, 2, 0], "radius": 0.5,
      "material": { "eta": 1.5 } })"));
  ASSERT_TRUE(opaque.scene) << opaque.diag.format();
  EXPECT_TRUE(opaque.has(Severity::Warning, "'eta' has no effect without 'kt' > 0")) << opaque.diag.format();
  EXPECT_FALSE(material_of(*opaque.scene, 0).refractive.value);
}

TEST(CourseSettings, SamplesPerPixelSpellings) {
  for (const char* top : {R"("spp": 16,)", R"("samples": 16,)", R"("sampling": { "samples": 16 },)"}) {
    const Loaded l = load(pol(kPointLight, kSphere, "", top));
    ASSERT_TRUE(l.scene) << top << l.diag.format();
    EXPECT_EQ(l.diag.all().size(), 0u) << top << l.diag.format();
    EXPECT_EQ(l.scene->render.spp.value, 16) << top;
  }
  const Loaded method = load(pol(kPointLight, kSphere, "", R"("sampling": { "spp": 4, "method": "jittered" },)"));
  ASSERT_TRUE(method.scene) << method.diag.format();
  EXPECT_EQ(method.scene->render.spp.value, 4);
  EXPECT_TRUE(method.has(Severity::Warning, "choose the sampler with --sampler")) << method.diag.format();
  const Loaded twice = load(pol(kPointLight, kSphere, "", R"("spp": 4, "samples": 8,)"));
  EXPECT_FALSE(twice.scene);
}

}  // namespace
}  // namespace pt
