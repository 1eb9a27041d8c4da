// Typed access: conversions, type errors at the value, unknown keys with
// suggestions (errors in the native format, warnings in the course formats).
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "scene/json_reader.h"
#include "scene/suggest.h"

namespace pt {
namespace {

class ReaderTest : public ::testing::Test {
 protected:
  const JsonValue& load(std::string text) {
    doc_ = parse_json(std::make_shared<const SourceFile>(SourceFile{"t.json", std::move(text)}), diag_);
    EXPECT_TRUE(doc_.has_value()) << diag_.format();
    ctx_ = std::make_unique<ReadContext>(ReadContext{*doc_, diag_, UnknownKeyPolicy::Error});
    return doc_->root();
  }
  std::string messages() const {
    std::string all;
    for (const Diagnostic& d : diag_.all()) all += d.where.to_string() + ": " + d.message + "\n";
    return all;
  }

  Diagnostics diag_;
  std::optional<JsonDocument> doc_;
  std::unique_ptr<ReadContext> ctx_;
};

TEST(Suggest, EditDistanceCountsTranspositionsAsOneEdit) {
  EXPECT_EQ(edit_distance("raduis", "radius"), 1);
  EXPECT_EQ(edit_distance("", "abc"), 3);
  EXPECT_EQ(edit_distance("kitten", "sitting"), 3);
  EXPECT_EQ(edit_distance("same", "same"), 0);
}

TEST(Suggest, ClosestMatchOnlyForLikelyTypos) {
  const std::vector<std::string> keys = {"center", "radius", "material", "pole"};
  EXPECT_EQ(closest_match("raduis", keys), "radius");
  EXPECT_EQ(closest_match("centre", keys), "center");
  EXPECT_EQ(closest_match("Radius", keys), "radius");
  EXPECT_EQ(closest_match("matrial", keys), "material");
  EXPECT_EQ(closest_match("colour", keys), "");
  EXPECT_EQ(closest_match("kt", {"ks", "kd"}), "");  // two letters: too short to guess
  EXPECT_EQ(closest_match("KS", {"ks", "kd"}), "ks");
  EXPECT_EQ(quoted_list({"b", "a", "b"}), "'a' or 'b'");
  EXPECT_EQ(quoted_list({"x", "z", "y"}, "and"), "'x', 'y' and 'z'");
}

TEST_F(ReaderTest, ReadsTypedValuesWithLocations) {
  const JsonValue& root = load("{\"f\": 1.5, \"i\": 800.0, \"b\": true, \"s\": \"x\",\n \"v\": [1, 2, 3], \"c\": [0.5, 0.25, 1]}");
  ObjectReader r(*ctx_, root, "thing");
  Sourced<float> f;
  Sourced<int> i;
  Sourced<bool> b;
  Sourced<std::string> s;
  Sourced<Vec3f> v;
  Sourced<RGB> c;
  EXPECT_TRUE(r.read("f", f));
  EXPECT_TRUE(r.read("i", i));
  EXPECT_TRUE(r.read("b", b));
  EXPECT_TRUE(r.read("s", s));
  EXPECT_TRUE(r.read("v", v));
  EXPECT_TRUE(r.read("c", c));
  r.finish();
  EXPECT_TRUE(r.ok());
  EXPECT_EQ(diag_.all().size(), 0u) << messages();
  EXPECT_EQ(f.value, 1.5f);
  EXPECT_EQ(i.value, 800);  // an integral number written with a fraction is fine
  EXPECT_TRUE(b.value);
  EXPECT_EQ(s.value, "x");
  EXPECT_EQ(v.value, Vec3f(1, 2, 3));
  EXPECT_EQ(c.value, RGB(0.5f, 0.25f, 1.0f));
  EXPECT_EQ(v.where.line, 2);
  EXPECT_EQ(v.where.col, 7);
}

TEST_F(ReaderTest, AbsentOptionalKeysKeepDefaultsAndRequiredOnesAreReported) {
  const JsonValue& root = load("{}");
  ObjectReader r(*ctx_, root, "sphere");
  Sourced<float> radius{2.0f};
  EXPECT_TRUE(r.read("radius", radius));
  EXPECT_EQ(radius.value, 2.0f);
  EXPECT_FALSE(r.read_required("center", radius));
  EXPECT_FALSE(r.ok());
  ASSERT_EQ(diag_.error_count(), 1);
  EXPECT_EQ(diag_.all()[0].message, "missing key 'center' in sphere");
}

TEST_F(ReaderTest, WrongTypesAreReportedAtTheValue) {
  const JsonValue& root = load("{\"radius\": \"big\", \"n\": 2.5, \"big\": 1e10, \"v\": [1, \"2\", 3], \"w\": [1, 2]}");
  ObjectReader r(*ctx_, root, "sphere");
  Sourced<float> radius{1.0f};
  Sourced<int> n, big;
  Sourced<Vec3f> v, w;
  EXPECT_FALSE(r.read("radius", radius));
  EXPECT_EQ(radius.value, 1.0f);  // unchanged
  EXPECT_FALSE(r.read("n", n));
  EXPECT_FALSE(r.read("big", big));
  EXPECT_FALSE(r.read("v", v));
  EXPECT_FALSE(r.read("w", w));
  ASSERT_EQ(diag_.error_count(), 5) << messages();
  EXPECT_EQ(diag_.all()[0].message, "expected a number for 'radius', got the string \"big\"");
  EXPECT_EQ(diag_.all()[0].where.col, 12);
  EXPECT_EQ(diag_.all()[1].message, "expected an integer for 'n', got the number 2.5");
  EXPECT_EQ(diag_.all()[2].message, "'big' is out of range: 1e+10");
  EXPECT_EQ(diag_.all()[3].message, "expected a number in 'v', got the string \"2\"");
  EXPECT_EQ(diag_.all()[3].where.col, 51);
  EXPECT_EQ(diag_.all()[4].message, "expected an array of 3 numbers for 'w', got an array of 2 values");
}

TEST_F(ReaderTest, UnknownKeysAreErrorsWithSuggestionsInTheNativeFormat) {
  const JsonValue& root = load("{\"center\": [0, 0, 0], \"raduis\": 1, \"colour\": 2}");
  ObjectReader r(*ctx_, root, "sphere");
  Sourced<Vec3f> c;
  Sourced<float> radius;
  r.read("center", c);
  r.read("radius", radius);
  r.allow({"pole"});
  r.finish();
  EXPECT_FALSE(r.ok());
  ASSERT_EQ(diag_.error_count(), 2) << messages();
  EXPECT_EQ(diag_.all()[0].message, "unknown key 'raduis' in sphere; did you mean 'radius'?");
  EXPECT_EQ(diag_.all()[0].where.col, 23);
  EXPECT_EQ(diag_.all()[1].message,
            "unknown key 'colour' in sphere; valid keys are 'center', 'pole' and 'radius'");
}

TEST_F(ReaderTest, UnknownKeysAreWarningsInTheCourseFormats) {
  const JsonValue& root = load("{\"ks\": 0.5, \"kt\": 0.5, \"specularexponant\": 3}");
  ctx_->unknown_keys = UnknownKeyPolicy::Warning;
  ObjectReader r(*ctx_, root, "material");
  Sourced<float> ks, e;
  r.read("ks", ks);
  r.read("specularexponent", e);
  r.finish();
  EXPECT_TRUE(r.ok());
  EXPECT_EQ(diag_.error_count(), 0);
  ASSERT_EQ(diag_.warning_count(), 2);
  EXPECT_EQ(diag_.all()[0].message, "unknown key 'kt' in material (ignored)");
  EXPECT_EQ(diag_.all()[1].message,
            "unknown key 'specularexponant' in material (ignored); did you mean 'specularexponent'?");
}

TEST_F(ReaderTest, ChoicesSuggestTheClosestName) {
  const JsonValue& root = load("{\"display\": \"sRGB\", \"mode\": \"fancy\"}");
  ObjectReader r(*ctx_, root, "film");
  EXPECT_EQ(read_choice(r, "display", {"srgb", "linear"}), -2);
  EXPECT_EQ(read_choice(r, "mode", {"a", "b"}), -2);
  EXPECT_EQ(read_choice(r, "absent", {"a"}), -1);
  ASSERT_EQ(diag_.error_count(), 2);
  EXPECT_EQ(diag_.all()[0].message, "unknown display 'sRGB' in film; did you mean 'srgb'?");
  EXPECT_EQ(diag_.all()[1].message, "unknown mode 'fancy' in film; expected 'a' or 'b'");
}

}  // namespace
}  // namespace pt
