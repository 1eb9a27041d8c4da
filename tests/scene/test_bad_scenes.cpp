// The bad-scene corpus (tests/bad-scenes): every NAME.json is loaded and its
// diagnostics compared with NAME.expected, which lists lines of the form
//   LINE:COL: SEVERITY: MESSAGE
// Each expected line must begin some reported diagnostic; every reported error
// and warning must be expected; loading must fail exactly when an error is
// expected. Files named strict-*.json are loaded in strict mode.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "scene/loader.h"

namespace pt {
namespace {

namespace fs = std::filesystem;

const std::string kBadScenes = std::string(PT_TEST_DATA_DIR) + "/bad-scenes";

std::vector<std::string> bad_scene_names() {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(kBadScenes, ec))
    if (entry.path().extension() == ".json") names.push_back(entry.path().stem().string());
  std::sort(names.begin(), names.end());
  return names;
}

const char* severity_name(Severity s) {
  switch (s) {
    case Severity::Note: return "note";
    case Severity::Warning: return "warning";
    case Severity::Error: return "error";
  }
  return "?";
}

// "LINE:COL: SEVERITY: MESSAGE", or "SEVERITY: MESSAGE" without a line.
std::string header(const Diagnostic& d) {
  std::string s;
  if (d.where.line > 0) s = std::to_string(d.where.line) + ":" + std::to_string(d.where.col) + ": ";
  return s + severity_name(d.severity) + ": " + d.message;
}

bool starts_with(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0; }

class BadScene : public ::testing::TestWithParam<std::string> {};

TEST_P(BadScene, ReportsExactlyTheExpectedProblems) {
  const std::string name = GetParam();
  std::ifstream in(kBadScenes + "/" + name + ".expected");
  ASSERT_TRUE(in) << name << ".expected is missing";
  std::vector<std::string> expected;
  bool expect_error = false;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    expect_error = expect_error || line.find("error: ") != std::string::npos;
    expected.push_back(line);
  }
  ASSERT_FALSE(expected.empty()) << name << ".expected lists nothing";

  LoadOptions options;
  options.strict = starts_with(name, "strict-");
  Diagnostics diag;
  const auto scene = load_scene(kBadScenes + "/" + name + ".json", options, diag);
  const std::string report = diag.format();

  std::vector<std::string> actual;
  for (const Diagnostic& d : diag.all()) actual.push_back(header(d));
  for (const std::string& e : expected) {
    const bool found = std::any_of(actual.begin(), actual.end(), [&](const std::string& a) { return starts_with(a, e); });
    EXPECT_TRUE(found) << "expected: " << e << "\nreported:\n" << report;
  }
  for (std::size_t i = 0; i < actual.size(); ++i) {
    if (diag.all()[i].severity == Severity::Note) continue;
    const bool wanted = std::any_of(expected.begin(), expected.end(), [&](const std::string& e) { return starts_with(actual[i], e); });
    EXPECT_TRUE(wanted) << "not expected: " << actual[i];
  }
  EXPECT_EQ(scene.has_value(), !expect_error) << report;
  // Every diagnostic with a location is printed with the line and a caret.
  for (const Diagnostic& d : diag.all()) {
    if (!d.where.valid()) continue;
    const std::string quoted = std::to_string(d.where.line) + " | " + d.where.file->line_text(d.where.line);
    EXPECT_NE(report.find(quoted), std::string::npos) << report;
  }
}

INSTANTIATE_TEST_SUITE_P(Corpus, BadScene, ::testing::ValuesIn(bad_scene_names()),
                         [](const ::testing::TestParamInfo<std::string>& param_info) {
                           std::string n = param_info.param;
                           std::replace_if(n.begin(), n.end(), [](char c) { return !std::isalnum(static_cast<unsigned char>(c)); }, '_');
                           return n;
                         });

TEST(BadSceneCorpus, IsLargeAndComplete) {
  const std::vector<std::string> names = bad_scene_names();
  EXPECT_GE(names.size(), 15u);
  for (const std::string& n : names) EXPECT_TRUE(fs::exists(kBadScenes + "/" + n + ".expected")) << n;
}

}  // namespace
}  // namespace pt
