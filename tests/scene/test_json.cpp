// JSON with locations: every value and key knows where it was written; the
// parser's problems are reported at the right place.
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "scene/json.h"

namespace pt {
namespace {

struct Parsed {
  std::optional<JsonDocument> doc;
  Diagnostics diag;
};

std::unique_ptr<Parsed> parse(std::string text, JsonLimits limits = {}) {
  auto p = std::make_unique<Parsed>();
  p->doc = parse_json(std::make_shared<const SourceFile>(SourceFile{"t.json", std::move(text)}), p->diag, limits);
  return p;
}

std::string where(const JsonDocument& doc, const JsonValue& v) {
  const SourceLocation loc = doc.location(v);
  return std::to_string(loc.line) + ":" + std::to_string(loc.col);
}

std::string where(const SourceLocation& loc) { return std::to_string(loc.line) + ":" + std::to_string(loc.col); }

TEST(Json, EveryValueKnowsItsStart) {
  const auto p = parse("{\"a\": [1, -2.5e3, \"x\\\"y\", true, null],\n  \"b\" : {},\n\t\"c\":12}");
  ASSERT_TRUE(p->doc) << p->diag.format();
  const JsonDocument& doc = *p->doc;
  const JsonValue& root = doc.root();
  ASSERT_TRUE(root.is_object());
  EXPECT_EQ(where(doc, root), "1:1");
  const JsonValue::Array& a = root.find("a")->as_array();
  ASSERT_EQ(a.size(), 5u);
  EXPECT_EQ(where(doc, *root.find("a")), "1:7");
  EXPECT_EQ(where(doc, a[0]), "1:8");
  EXPECT_EQ(where(doc, a[1]), "1:11");
  EXPECT_EQ(where(doc, a[2]), "1:19");
  EXPECT_EQ(where(doc, a[3]), "1:27");
  EXPECT_EQ(where(doc, a[4]), "1:33");
  EXPECT_EQ(a[1].as_number(), -2500.0);
  EXPECT_FALSE(a[1].is_integer());
  EXPECT_TRUE(a[0].is_integer());
  EXPECT_EQ(a[2].as_string(), "x\"y");
  EXPECT_EQ(where(doc, *root.find("b")), "2:9");
  // A number at the very end of an object (the lexer reads one character past it).
  EXPECT_EQ(where(doc, *root.find("c")), "3:6");
  EXPECT_EQ(root.find("c")->as_number(), 12.0);
}

TEST(Json, KeysKeepFileOrderAndTheirOwnLocations) {
  const auto p = parse("{\"zeta\": 1,\n \"alpha\": 2, \"mid\": 3}");
  ASSERT_TRUE(p->doc);
  const JsonValue::Object& o = p->doc->root().as_object();
  ASSERT_EQ(o.size(), 3u);
  EXPECT_EQ(o[0].key, "zeta");
  EXPECT_EQ(o[1].key, "alpha");
  EXPECT_EQ(o[2].key, "mid");
  EXPECT_EQ(where(p->doc->location(o[1].key_offset)), "2:2");
  EXPECT_EQ(where(p->doc->location(o[2].key_offset)), "2:14");
}

TEST(Json, NumbersAtEndOfInputAndNestedArrays) {
  const auto p = parse("[[1,2],[3, 40]]");
  ASSERT_TRUE(p->doc);
  const JsonValue::Array& outer = p->doc->root().as_array();
  EXPECT_EQ(where(*p->doc, outer[1].as_array()[1]), "1:12");
  const auto q = parse("  7");
  ASSERT_TRUE(q->doc);
  EXPECT_EQ(where(*q->doc, q->doc->root()), "1:3");
}

TEST(Json, ByteOrderMarkIsSkipped) {
  const auto p = parse("\xEF\xBB\xBF{\"a\": 1}");
  ASSERT_TRUE(p->doc) << p->diag.format();
  EXPECT_EQ(p->doc->location(p->doc->root()).col, 4);  // columns count bytes
}

TEST(Json, DuplicateKeysAreErrorsNamingBothPlaces) {
  const auto p = parse("{\"r\": 1,\n \"r\": 2}");
  ASSERT_TRUE(p->doc);  // not fatal: the rest of the file is still checked
  ASSERT_EQ(p->diag.all().size(), 2u);
  EXPECT_EQ(p->diag.all()[0].severity, Severity::Error);
  EXPECT_EQ(p->diag.all()[0].message, "duplicate key 'r'");
  EXPECT_EQ(where(p->diag.all()[0].where), "2:2");
  EXPECT_EQ(p->diag.all()[1].severity, Severity::Note);
  EXPECT_EQ(where(p->diag.all()[1].where), "1:2");
  // Readers see the first definition only.
  EXPECT_EQ(p->doc->root().find("r")->as_number(), 1.0);
  EXPECT_TRUE(p->doc->root().as_object()[1].duplicate);
}

TEST(Json, NestingLimitIsEnforcedWithoutRecursion) {
  const std::string ok = std::string(100, '[') + std::string(100, ']');
  EXPECT_TRUE(parse(ok)->doc);
  const auto p = parse(std::string(101, '[') + std::string(101, ']'));
  EXPECT_FALSE(p->doc);
  ASSERT_EQ(p->diag.error_count(), 1);
  EXPECT_NE(p->diag.all()[0].message.find("nested more than 100 levels"), std::string::npos);
  EXPECT_EQ(p->diag.all()[0].where.col, 101);
  // Far deeper input is refused just the same (no stack overflow).
  EXPECT_FALSE(parse(std::string(1000000, '['))->doc);
}

TEST(Json, OverflowingNumbersAreErrorsAtTheirLocation) {
  for (const char* text : {"{\"x\": 1e999}", "{\"x\": -1e999}"}) {
    const auto p = parse(text);
    EXPECT_FALSE(p->doc);
    ASSERT_EQ(p->diag.error_count(), 1) << text;
    EXPECT_EQ(where(p->diag.all()[0].where), "1:7");
    EXPECT_NE(p->diag.all()[0].message.find("out of range"), std::string::npos);
  }
  // Underflow is harmless.
  const auto small = parse("[1e-999]");
  ASSERT_TRUE(small->doc);
  EXPECT_EQ(small->doc->root().as_array()[0].as_number(), 0.0);
}

TEST(Json, NanAndInfinityAreNamed) {
  for (const char* text : {"[1, NaN]", "[1, Infinity]", "[1, -Infinity]", "[1, nan]", "[1, inf]"}) {
    const auto p = parse(text);
    EXPECT_FALSE(p->doc) << text;
    ASSERT_EQ(p->diag.error_count(), 1) << text;
    EXPECT_EQ(where(p->diag.all()[0].where), "1:5") << text;
    EXPECT_NE(p->diag.all()[0].message.find("NaN and Infinity"), std::string::npos) << text;
  }
}

TEST(Json, SyntaxErrorsPointAtTheOffendingToken) {
  struct Case {
    const char* text;
    const char* at;
    const char* message_part;
  };
  const Case cases[] = {
      {"{\"a\": 1 \"b\": 2}", "1:9", "missing ','"},
      {"{\"a\": 1,,}", "1:9", "unexpected ','"},
      {"{\"a\": tru}", "1:7", "invalid literal 'tru'"},
      {"{\n  \"a\": [1, 2\n\n", "2:13", "end of input"},
      {"{\"a\": 1} [", "1:10", "expected end of input (text after"},
      {"{\"a\": \"x\x01\"}", "1:9", "control character"},
      {"   \n  ", "1:1", "the file is empty"},
  };
  for (const Case& c : cases) {
    const auto p = parse(c.text);
    EXPECT_FALSE(p->doc) << c.text;
    ASSERT_EQ(p->diag.error_count(), 1) << c.text;
    EXPECT_EQ(where(p->diag.all()[0].where), c.at) << c.text << ": " << p->diag.format();
    EXPECT_NE(p->diag.all()[0].message.find(c.message_part), std::string::npos) << p->diag.all()[0].message;
  }
}

TEST(Json, ValuesCopyAndMove) {
  const auto p = parse("{\"a\": [1, {\"b\": \"c\"}]}");
  ASSERT_TRUE(p->doc);
  JsonValue copy = p->doc->root();
  JsonValue moved = std::move(copy);
  EXPECT_EQ(moved.find("a")->as_array()[1].find("b")->as_string(), "c");
  EXPECT_EQ(moved.find("missing"), nullptr);
  EXPECT_EQ(moved.find("a")->find("b"), nullptr);  // not an object
}

}  // namespace
}  // namespace pt
