// The native format's transforms and instancing (docs/scene-format.md,
// "Transforms" and "Instancing"): steps composed in order on every shape and
// the camera, errors at the step's file:line:col, objects placed by
// instances with their own material, unknown names with "did you mean".
#include <gtest/gtest.h>

#include "scene_test_util.h"

namespace pt {
namespace {

using test::near;

std::string scene(const std::string& body) {
  return R"({ "format": "pathtracer-scene", "version": 1,
  "camera": { "position": [0, 1, 5], "look_at": [0, 1, 0] },
  "materials": { "white": { "type": "lambert" }, "red": { "type": "lambert", "diffuse": [1, 0, 0] } },
)" + body + "\n}\n";
}

std::optional<SceneDescription> load(const std::string& text, Diagnostics& diag) {
  return load_scene_from_string("t.json", text, LoadOptions{}, diag);
}

TEST(Transforms, StepsApplyInTheOrderListed) {
  Diagnostics diag;
  const auto s = load(scene(R"("shapes": [
    { "type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "white",
      "transform": [ { "scale": [2, 1, 1] }, { "rotate": { "axis": [0, 0, 1], "angle": 90 } },
                     { "translate": [0, 0, 5] } ] },
    { "type": "quad", "vertices": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]], "material": "white",
      "transform": [ { "matrix": [1,0,0,3, 0,1,0,0, 0,0,1,0, 0,0,0,1] } ] },
    { "type": "triangle", "vertices": [[0,0,0],[1,0,0],[0,1,0]], "material": "white",
      "transform": [ { "scale": 1 } ] } ])"),
                      diag);
  ASSERT_TRUE(s) << diag.format();
  ASSERT_TRUE(s->shapes[0].transform);
  const Transform& t = s->shapes[0].transform->value;
  // (1, 0, 0) -> scale (2, 0, 0) -> rotate (0, 2, 0) -> translate (0, 2, 5).
  EXPECT_TRUE(near(t.point({1, 0, 0}), {0, 2, 5}));
  EXPECT_EQ(s->shapes[0].transform->where.line, 6);
  ASSERT_TRUE(s->shapes[1].transform);
  EXPECT_TRUE(near(s->shapes[1].transform->value.point({0, 0, 0}), {3, 0, 0}));
  EXPECT_FALSE(s->shapes[2].transform) << "the identity is no transform";
}

TEST(Transforms, TheCameraMovesAtImport) {
  Diagnostics diag;
  const auto s = load(R"({ "format": "pathtracer-scene", "version": 1,
  "camera": { "position": [0, 0, 5], "look_at": [0, 0, 0], "up": [0, 1, 0],
              "transform": [ { "rotate": { "axis": [0, 1, 0], "angle": 90 } }, { "translate": [1, 0, 0] } ] } })",
                      diag);
  ASSERT_TRUE(s) << diag.format();
  EXPECT_TRUE(near(s->camera.position, {6, 0, 0}));
  EXPECT_TRUE(near(s->camera.look_at, {1, 0, 0}));
  EXPECT_TRUE(near(s->camera.up, {0, 1, 0}));
  EXPECT_FALSE(s->camera.left_handed.value);
}

// As pbrt-v4's camera transform and Mitsuba 3's to_world: a uniform scale
// scales the camera's lengths (so a scene scaled with its camera looks the
// same; Mitsuba's orthographic camera scaled by s is 2s high), a mirror flips
// the image's handedness, and a non-uniform scale is refused at the transform.
TEST(Transforms, TheCameraKeepsItsPictureUnderScalesAndMirrors) {
  auto camera = [](const std::string& keys) {
    return R"({ "format": "pathtracer-scene", "version": 1,
  "camera": { "position": [0, 0, 5], "look_at": [0, 0, 0], )" +
           keys + " } }";
  };
  Diagnostics diag;
  const auto lens = load(camera(R"("type": "thin_lens", "lens_radius": 0.1, "focus_distance": 5,
      "transform": [ { "scale": 3 }, { "translate": [1, 0, 0] } ])"),
                         diag);
  ASSERT_TRUE(lens) << diag.format();
  EXPECT_TRUE(near(lens->camera.position, {1, 0, 15}));
  EXPECT_NEAR(lens->camera.lens_radius.value, 0.3f, 1e-6f);
  EXPECT_NEAR(lens->camera.focus_distance.value, 15.0f, 1e-5f);
  const auto ortho = load(camera(R"("type": "orthographic", "transform": [ { "scale": 0.5 } ])"), diag);
  ASSERT_TRUE(ortho) << diag.format();
  EXPECT_NEAR(ortho->camera.view_height.value, 1.0f, 1e-6f);
  const auto mirrored = load(camera(R"("transform": [ { "scale": [-1, 1, 1] } ])"), diag);
  ASSERT_TRUE(mirrored) << diag.format();
  EXPECT_TRUE(mirrored->camera.left_handed.value);
  const auto twice = load(camera(R"("handedness": "left", "transform": [ { "scale": [-2, 2, 2] } ])"), diag);
  ASSERT_TRUE(twice) << diag.format();
  EXPECT_FALSE(twice->camera.left_handed.value);

  Diagnostics bad;
  EXPECT_FALSE(load(camera(R"("transform": [ { "scale": [1, 2, 1] } ])"), bad));
  EXPECT_NE(bad.format().find("t.json:2:73: error: a camera's transform must keep angles"), std::string::npos)
      << bad.format();
}

// An infinite plane is no primitive of either backend, so its transform is
// applied to the plane itself at import (no instance), and an object cannot hold one.
TEST(Transforms, APlaneIsTransformedItselfAndRefusedInObjects) {
  Diagnostics diag;
  const auto s = load(scene(R"("shapes": [
    { "type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "material": "white",
      "transform": [ { "translate": [0, -1, 0] }, { "rotate": { "axis": [1, 0, 0], "angle": 90 } } ] } ])"),
                      diag);
  ASSERT_TRUE(s) << diag.format();
  EXPECT_FALSE(s->shapes[0].transform);
  const auto& plane = std::get<InfinitePlane>(s->shapes[0].geometry);
  EXPECT_TRUE(near(plane.point, {0, 0, -1}));  // (0, -1, 0) turned 90 degrees about +x
  EXPECT_TRUE(near(plane.normal, {0, 0, 1}));
  EXPECT_NEAR(length(plane.tangent), 1.0f, 1e-6f);

  Diagnostics bad;
  EXPECT_FALSE(load(scene(R"("objects": [ { "name": "floor", "shapes": [
      { "type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0] } ] } ],
    "shapes": [ { "type": "instance", "object": "floor" } ])"),
                    bad));
  EXPECT_NE(bad.format().find("an infinite plane cannot be part of object 'floor'"), std::string::npos)
      << bad.format();
}

TEST(Transforms, BadStepsAreRefusedAtTheirLocation) {
  struct Case {
    const char* step;
    const char* message;
  };
  const Case cases[] = {
      {R"({ "scale": [1, 0, 1] })", "singular"},
      {R"({ "matrix": [1,0,0,0, 2,0,0,0, 0,0,1,0, 0,0,0,1] })", "singular"},  // rank 2
      {R"({ "matrix": [1,0,0,0, 0,1e400,0,0, 0,0,1,0, 0,0,0,1] })", "overflows to infinity"},
      {R"({ "scale": 1e-100 }, { "scale": 1e-100 })", "singular or not finite"},
      {R"({ "matrix": [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,1,1] })", "affine"},
      {R"({ "matrix": [1,0,0,0, 0,1,0,0, 0,0,1,0] })", "16 numbers"},
      {R"({ "rotate": { "axis": [0, 0, 0], "angle": 3 } })", "axis"},
      {R"({ "rotate": { "axis": [0, 1, 0] } })", "angle"},
      {R"({ "translat": [1, 2, 3] })", "did you mean 'translate'"},
      {R"({ "scale": 1e30 }, { "scale": 1e30 })", "float range"},
  };
  for (const Case& c : cases) {
    Diagnostics diag;
    const auto s = load(scene(std::string(R"("shapes": [ { "type": "sphere", "center": [0, 0, 0], "radius": 1,
      "transform": [ )") + c.step + " ] } ]"),
                        diag);
    EXPECT_FALSE(s) << c.step;
    EXPECT_NE(diag.format().find(c.message), std::string::npos) << c.step << "\n" << diag.format();
    EXPECT_NE(diag.format().find("t.json:5:"), std::string::npos) << diag.format();
  }
}

TEST(Instancing, ObjectsArePlacedByInstancesWithTheirOwnMaterial) {
  Diagnostics diag;
  const auto s = load(scene(R"("objects": [ { "name": "pair", "shapes": [
      { "type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "white" },
      { "type": "mesh", "positions": [[0,0,0],[1,0,0],[0,1,0]], "indices": [[0,1,2]], "material": "white" } ] } ],
  "shapes": [
    { "type": "instance", "object": "pair" },
    { "type": "instance", "object": "pair", "material": "red", "transform": [ { "translate": [3, 0, 0] } ] } ])"),
                      diag);
  ASSERT_TRUE(s) << diag.format();
  EXPECT_TRUE(s->shapes.empty());
  ASSERT_EQ(s->objects.size(), 1u);
  EXPECT_EQ(s->objects[0].shapes.size(), 2u);
  ASSERT_EQ(s->instances.size(), 2u);
  EXPECT_FALSE(s->instances[0].transform);
  EXPECT_FALSE(s->instances[0].material);
  ASSERT_TRUE(s->instances[1].material);
  EXPECT_EQ(s->materials[static_cast<std::size_t>(*s->instances[1].material)].name, "red");
  EXPECT_TRUE(near(s->instances[1].transform->value.point({0, 0, 0}), {3, 0, 0}));
}

TEST(Instancing, UnknownObjectsAndNestingAreRefused) {
  Diagnostics diag;
  EXPECT_FALSE(load(scene(R"("objects": [ { "name": "bunny", "shapes": [] } ],
  "shapes": [ { "type": "instance", "object": "buny" } ])"),
                    diag));
  EXPECT_NE(diag.format().find("did you mean 'bunny'"), std::string::npos) << diag.format();
  Diagnostics nested;
  EXPECT_FALSE(load(scene(R"("objects": [ { "name": "a", "shapes": [] },
      { "name": "b", "shapes": [ { "type": "instance", "object": "a" } ] } ])"),
                    nested));
  EXPECT_NE(nested.format().find("one level of instancing"), std::string::npos) << nested.format();
  Diagnostics twice;
  EXPECT_FALSE(load(scene(R"("objects": [ { "name": "a", "shapes": [] }, { "name": "a", "shapes": [] } ])"), twice));
  EXPECT_NE(twice.format().find("already defined"), std::string::npos) << twice.format();
}

// An object no instance places is never drawn: a warning at the object (as
// for a material no shape uses), and the scene still loads.
TEST(Instancing, AnObjectNoInstancePlacesGetsAWarning) {
  Diagnostics diag;
  const auto s = load(scene(R"("objects": [ { "name": "used", "shapes": [
      { "type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "white" } ] },
    { "name": "forgotten", "shapes": [ { "type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "red" } ] } ],
  "shapes": [ { "type": "instance", "object": "used" } ])"),
                      diag);
  ASSERT_TRUE(s) << diag.format();
  EXPECT_EQ(diag.warning_count(), 1) << diag.format();
  EXPECT_NE(diag.format().find("t.json:6:5: warning: object 'forgotten' is not placed by any instance"),
            std::string::npos)
      << diag.format();
}

TEST(Instancing, ObjectShapesAreValidatedLikeOthers) {
  Diagnostics diag;
  EXPECT_FALSE(load(scene(R"("objects": [ { "name": "a", "shapes": [
      { "type": "sphere", "center": [0, 0, 0], "radius": -1 } ] } ])"),
                    diag));
  EXPECT_NE(diag.format().find("radius"), std::string::npos) << diag.format();
}

}  // namespace
}  // namespace pt
