// Unit-level regressions for the limits the hostile corpus found missing:
// the JSON tree's value count (its memory), the film's pixel count, and
// diagnostics quoting a window of a very long line instead of all of it.
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "core/diagnostics.h"
#include "scene/json.h"
#include "scene/loader.h"

namespace pt {
namespace {

std::shared_ptr<const SourceFile> file_of(std::string text) {
  return std::make_shared<const SourceFile>(SourceFile{"limits.json", std::move(text)});
}

TEST(InputLimits, JsonValueCountIsBounded) {
  JsonLimits limits;
  limits.max_values = 10;
  Diagnostics ok_diag;
  EXPECT_TRUE(parse_json(file_of("[1, 2, 3, 4, 5, 6, 7, 8, 9]"), ok_diag, limits));  // 10 values with the array
  EXPECT_FALSE(ok_diag.has_errors());
  Diagnostics diag;
  EXPECT_FALSE(parse_json(file_of("[1, 2, 3, 4, 5, 6, 7, 8, 9, 10]"), diag, limits));
  ASSERT_EQ(diag.error_count(), 1);
  EXPECT_EQ(diag.all()[0].message, "the file holds more than 10 values; put large meshes in PLY files");
  EXPECT_EQ(diag.all()[0].where.line, 1);
  EXPECT_EQ(diag.all()[0].where.col, 29);  // the eleventh value
}

TEST(InputLimits, FilmPixelCountIsBounded) {
  const std::string scene = R"({"format": "pathtracer-scene", "version": 1,
    "camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]},
    "film": {"width": 20000, "height": 20000}})";
  Diagnostics diag;
  EXPECT_FALSE(load_scene_from_string("film.json", scene, LoadOptions{}, diag));
  ASSERT_EQ(diag.error_count(), 1) << diag.format();
  EXPECT_EQ(diag.all()[0].where.line, 3);
  EXPECT_EQ(diag.all()[0].message, "the film has 20000x20000 = 400000000 pixels; at most 268435456 are accepted");
  LoadOptions larger;
  larger.limits.max_pixels = 400000000;
  Diagnostics fine;
  EXPECT_TRUE(load_scene_from_string("film.json", scene, larger, fine)) << fine.format();
}

TEST(InputLimits, DiagnosticsQuoteAWindowOfALongLine) {
  std::string line(1'000'000, 'x');
  line[700'000] = '!';
  const auto file = file_of(line);
  Diagnostics diag;
  diag.error(location_at(file, 700'000), "here");
  const std::string report = diag.format();
  EXPECT_LT(report.size(), 1000u);
  // The caret is under the '!': same column in the quote and the caret line.
  const std::size_t quote = report.find(" | ...");
  ASSERT_NE(quote, std::string::npos) << report;
  const std::size_t bang = report.find('!', quote);
  const std::size_t caret_line = report.find('\n', quote) + 1;
  const std::size_t caret = report.find('^', caret_line);
  EXPECT_EQ(bang - quote, caret - caret_line - (quote - report.rfind('\n', quote) - 1));
  // Short lines are quoted whole, control characters shown as '?'.
  Diagnostics short_diag;
  short_diag.error(location_at(file_of(std::string("ab\0cd", 5)), 3), "nul");
  EXPECT_NE(short_diag.format().find("1 | ab?cd\n"), std::string::npos) << short_diag.format();
}

}  // namespace
}  // namespace pt
