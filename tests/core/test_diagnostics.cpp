#include <gtest/gtest.h>

#include "core/diagnostics.h"

namespace pt {
namespace {

std::shared_ptr<const SourceFile> make_file(std::string text) {
  return std::make_shared<SourceFile>(SourceFile{"scene.json", std::move(text)});
}

TEST(Diagnostics, LocationFromOffset) {
  auto f = make_file("{\n  \"a\": 1,\n  \"b\": -2\n}\n");
  const std::size_t off = f->text.find("-2");
  SourceLocation loc = location_at(f, off);
  EXPECT_EQ(loc.line, 3);
  EXPECT_EQ(loc.col, 8);
  EXPECT_EQ(loc.to_string(), "scene.json:3:8");
}

TEST(Diagnostics, FormatQuotesLineWithCaret) {
  auto f = make_file("{\n  \"radius\": -1\n}\n");
  Diagnostics d;
  d.error(location_at(f, f->text.find("-1")), "radius must be > 0, got -1");
  const std::string out = d.format();
  EXPECT_NE(out.find("scene.json:2:13: error: radius must be > 0, got -1"), std::string::npos) << out;
  EXPECT_NE(out.find(" 2 |   \"radius\": -1\n"), std::string::npos) << out;
  EXPECT_NE(out.find("   |             ^\n"), std::string::npos) << out;
  EXPECT_NE(out.find("1 error, 0 warnings"), std::string::npos) << out;
}

TEST(Diagnostics, CollectsAllAndPromotesWarningsInStrictMode) {
  auto f = make_file("x\ny\n");
  Diagnostics d;
  d.warning(location_at(f, 0), "unknown key 'x'");
  EXPECT_FALSE(d.has_errors());
  d.set_warnings_as_errors(true);
  d.warning(location_at(f, 2), "unknown key 'y'");
  d.error(location_at(f, 2), "bad");
  EXPECT_EQ(d.error_count(), 2);
  EXPECT_EQ(d.warning_count(), 1);
  EXPECT_EQ(d.all().size(), 3u);
}

TEST(Diagnostics, NoLocationSaysCommandLine) {
  Diagnostics d;
  d.error(SourceLocation{}, "--width must be > 0");
  EXPECT_NE(d.format().find("<command line>: error: --width must be > 0"), std::string::npos);
}

}  // namespace
}  // namespace pt
