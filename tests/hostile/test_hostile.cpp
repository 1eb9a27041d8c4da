// The hostile-input corpus: the pathtracer executable is run on each file the
// way a user would, with a time limit and a memory limit, and must fail
// cleanly: exit status 1 (not a signal, not a timeout), every message fragment
// listed in the sidecar NAME.expected on stderr (with file:line:col where the
// problem has a place), no sanitizer report, and no output file at all.
//
//  - cases/NAME.json: committed scene files (meshes and textures they use are
//    in files/);
//  - generated/NAME.expected: cases whose files are made at run time by the
//    generator of the same name below (large, binary or directory cases that
//    do not belong in git).
// See README.md for how to add a case.
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "run_process.h"

namespace pt {
namespace {

namespace fs = std::filesystem;

const fs::path kHostile = fs::path(PT_TEST_DATA_DIR) / "hostile";

// Limits for one run: generous for a sanitizer build, far below what an
// unbounded allocation or loop would need. The time is CPU time (run_process.h):
// a loaded machine does not make a case fail.
constexpr double kCpuSeconds = 120;
constexpr std::size_t kMemoryMib = 2048;
// Error output beyond this is itself a failure (a megabyte line quoted whole).
constexpr std::size_t kMaxStderrBytes = 64 * 1024;

const char* const kNativeHeader =
    R"({"format": "pathtracer-scene", "version": 1, "camera": {"position": [0, 1, 5], "look_at": [0, 1, 0]}, )";

void write_file(const fs::path& p, const std::string& bytes) {
  std::ofstream out(p, std::ios::binary);
  out << bytes;
}

std::string random_bytes(std::size_t n, uint32_t seed) {
  std::mt19937 gen(seed);
  std::string s(n, '\0');
  for (char& c : s) c = static_cast<char>(gen() & 0xFF);
  return s;
}

std::string scene_with_shapes(const std::string& shapes) { return kNativeHeader + std::string(R"("shapes": [)") + shapes + "]}\n"; }

// Writes dir/scene.json with one mesh shape read from `file` (which the case
// makes beside it); returns the scene argument.
std::string mesh_scene(const fs::path& dir, const std::string& file) {
  write_file(dir / "scene.json", scene_with_shapes(R"({"type": "mesh", "file": ")" + file + R"("})"));
  return "scene.json";
}

// Writes dir/scene.json with a sphere whose material is textured from `file`;
// returns the scene argument.
std::string textured_scene(const fs::path& dir, const std::string& file) {
  write_file(dir / "scene.json", kNativeHeader + std::string(R"("materials": {"wood": {"texture": ")") + file +
                                     R"("}}, "shapes": [{"type": "sphere", "material": "wood", "center": [0, 0, 0], )"
                                     R"("radius": 1}]})");
  return "scene.json";
}

// chmod 000: unreadable, except to root.
void make_unreadable(const fs::path& path) { fs::permissions(path, fs::perms::none); }

// Generators: make the case's files in `dir`; return the scene argument.
using Generator = std::function<std::string(const fs::path& dir)>;

const std::map<std::string, Generator>& generators() {
  static const std::map<std::string, Generator> g = {
      {"binary-garbage",
       [](const fs::path& dir) {
         write_file(dir / "binary-garbage.json", std::string(1, '\0') + random_bytes(64 * 1024, 1));
         return std::string("binary-garbage.json");
       }},
      {"deep-nesting-100000",
       [](const fs::path& dir) {
         write_file(dir / "deep.json", kNativeHeader + std::string(R"("shapes": )") + std::string(100000, '[') +
                                           std::string(100000, ']') + "}\n");
         return std::string("deep.json");
       }},
      {"scene-larger-than-256-mib",
       [](const fs::path& dir) {
         const fs::path p = dir / "huge.json";
         write_file(p, "{");
         fs::resize_file(p, std::uintmax_t{300} << 20);  // sparse: no disk space used
         return std::string("huge.json");
       }},
      {"ten-million-values",
       [](const fs::path& dir) {
         std::string s = kNativeHeader + std::string(R"("shapes": [{"type": "mesh", "positions": [[0, 0, 0], [1, 0, 0], [0, 1, 0]], "indices": [)");
         s.reserve(s.size() + 2 * 10'000'000 + 16);
         for (int i = 0; i < 10'000'000; ++i) s += i ? ",0" : "0";
         s += "]}]}\n";
         write_file(dir / "values.json", s);
         return std::string("values.json");
       }},
      {"minified-megabyte-line",
       [](const fs::path& dir) {
         // One line: a megabyte of valid padding, then a wrong type.
         std::string s = kNativeHeader + std::string(R"("materials": {)");
         for (int i = 0; i < 20000; ++i) s += "\"m" + std::to_string(i) + "\": {\"kd\": 0.5}, ";
         s += R"("bad": {"kd": "high"}}, "shapes": []})";
         write_file(dir / "minified.json", s);
         return std::string("minified.json");
       }},
      {"mesh-is-a-directory",
       [](const fs::path& dir) {
         fs::create_directories(dir / "mesh.ply");  // root can read anything: a directory cannot be read as a file
         return mesh_scene(dir, "mesh.ply");
       }},
      {"texture-is-a-directory",
       [](const fs::path& dir) {
         fs::create_directories(dir / "wood.png");
         return textured_scene(dir, "wood.png");
       }},
      {"scene-is-a-directory",
       [](const fs::path& dir) {
         fs::create_directories(dir / "scene.json");
         return std::string("scene.json");
       }},
      {"scene-file-missing", [](const fs::path&) { return std::string("no-such-scene.json"); }},
      {"ply-random-bytes",
       [](const fs::path& dir) {
         write_file(dir / "mesh.ply", random_bytes(4096, 2));
         return mesh_scene(dir, "mesh.ply");
       }},
      {"obj-random-bytes",
       [](const fs::path& dir) {
         write_file(dir / "mesh.obj", random_bytes(4096, 3));
         return mesh_scene(dir, "mesh.obj");
       }},
      // chmod 000: unreadable, except to root (these cases are skipped as root;
      // the *-is-a-directory cases stand in for them there).
      {"unreadable-mesh-ply",
       [](const fs::path& dir) {
         write_file(dir / "mesh.ply", "ply\nformat ascii 1.0\nelement vertex 0\nend_header\n");
         make_unreadable(dir / "mesh.ply");
         return mesh_scene(dir, "mesh.ply");
       }},
      {"unreadable-mesh-obj",
       [](const fs::path& dir) {
         write_file(dir / "mesh.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
         make_unreadable(dir / "mesh.obj");
         return mesh_scene(dir, "mesh.obj");
       }},
      {"unreadable-texture",
       [](const fs::path& dir) {
         fs::copy_file(kHostile / "files" / "not-an-image.png", dir / "wood.png");
         make_unreadable(dir / "wood.png");
         return textured_scene(dir, "wood.png");
       }},
      {"ply-header-claims-terabytes",
       [](const fs::path& dir) {
         // Counts that would need 2^40 faces of data; the file is a few bytes.
         write_file(dir / "mesh.ply",
                    "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                    "property float z\nelement face 1099511627776\nproperty list uchar uint vertex_indices\nend_header\n" +
                        std::string(36, '\0'));
         return mesh_scene(dir, "mesh.ply");
       }},
      // Special files (issue 20): each is named as what it is, nothing waits
      // for a FIFO's writer or reads /dev/zero without end.
      {"mesh-is-a-fifo",
       [](const fs::path& dir) {
         ::mkfifo((dir / "mesh.ply").c_str(), 0644);
         return mesh_scene(dir, "mesh.ply");
       }},
      {"obj-is-dev-zero",
       [](const fs::path& dir) {
         fs::create_symlink("/dev/zero", dir / "mesh.obj");
         return mesh_scene(dir, "mesh.obj");
       }},
      {"texture-is-a-fifo",
       [](const fs::path& dir) {
         ::mkfifo((dir / "wood.png").c_str(), 0644);
         return textured_scene(dir, "wood.png");
       }},
      {"environment-is-a-symlink-loop",
       [](const fs::path& dir) {
         fs::create_symlink("sky.exr", dir / "sky.exr");
         write_file(dir / "scene.json", kNativeHeader + std::string(R"("environment": {"file": "sky.exr"}, )") +
                                            R"("shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1}]})");
         return std::string("scene.json");
       }},
      {"scene-is-a-fifo",
       [](const fs::path& dir) {
         ::mkfifo((dir / "scene.json").c_str(), 0644);
         return std::string("scene.json");
       }},
  };
  return g;
}

struct Case {
  std::string name;
  bool generated = false;
};

void PrintTo(const Case& c, std::ostream* os) { *os << c.name; }

std::vector<Case> cases() {
  std::vector<Case> out;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(kHostile / "cases", ec))
    if (e.path().extension() == ".json") out.push_back({e.path().stem().string(), false});
  for (const auto& e : fs::directory_iterator(kHostile / "generated", ec))
    if (e.path().extension() == ".expected") out.push_back({e.path().stem().string(), true});
  std::sort(out.begin(), out.end(), [](const Case& a, const Case& b) { return a.name < b.name; });
  return out;
}

std::vector<std::string> expected_fragments(const fs::path& sidecar) {
  std::ifstream in(sidecar);
  std::vector<std::string> out;
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty() || line[0] == '#') continue;
    out.push_back(line);
  }
  return out;
}

class Hostile : public ::testing::TestWithParam<Case> {
 protected:
  void SetUp() override {
    std::string name = GetParam().name;
    scratch_ = fs::temp_directory_path() / ("pt_hostile_" + std::to_string(::getpid()) + "_" + name);
    fs::remove_all(scratch_);
    fs::create_directories(scratch_ / "out");
    fs::create_directories(scratch_ / "work");
  }
  void TearDown() override { fs::remove_all(scratch_); }

  fs::path scratch_;
};

TEST_P(Hostile, FailsCleanlyWithItsLocation) {
  const Case& c = GetParam();
  fs::path cwd = kHostile / "cases";
  std::string scene = c.name + ".json";
  fs::path sidecar = kHostile / "cases" / (c.name + ".expected");
  if (c.name.rfind("unreadable-", 0) == 0 && ::geteuid() == 0)
    GTEST_SKIP() << "running as root, which can read a chmod 000 file; run the suite as another user for this case";
  if (c.generated) {
    const auto it = generators().find(c.name);
    ASSERT_NE(it, generators().end()) << "generated/" << c.name << ".expected has no generator in test_hostile.cpp";
    cwd = scratch_ / "work";
    scene = it->second(cwd);
    sidecar = kHostile / "generated" / (c.name + ".expected");
  }
  const std::vector<std::string> fragments = expected_fragments(sidecar);
  ASSERT_FALSE(fragments.empty()) << sidecar << " is missing or lists nothing";

  const fs::path out = scratch_ / "out";
  const test::ProcessResult r = test::run_process(
      {PT_PATHTRACER_EXE, scene, "-o", (out / "image.exr").string(), "-o", (out / "image.png").string(), "--threads", "2"},
      cwd, scratch_, test::ProcessLimits{kCpuSeconds, kMemoryMib});
  ASSERT_TRUE(r.started);
  EXPECT_FALSE(r.cpu_limit) << "still working after " << kCpuSeconds << " s of CPU time";
  EXPECT_FALSE(r.timed_out) << "blocked (no exit for " << test::ProcessLimits{}.hang_guard_seconds << " s)";
  EXPECT_TRUE(r.exited) << "killed by signal " << r.signal << "\n" << r.err.substr(0, 4000);
  EXPECT_EQ(r.exit_code, 1) << r.err.substr(0, 4000);
  EXPECT_FALSE(test::has_sanitizer_report(r.err)) << r.err.substr(0, 8000);
  EXPECT_LE(r.err.size(), kMaxStderrBytes);
  for (const std::string& f : fragments) {
    EXPECT_NE(r.err.find(f), std::string::npos) << "expected on stderr: " << f << "\nstderr:\n" << r.err.substr(0, 4000);
  }
  std::vector<std::string> left;
  for (const auto& e : fs::directory_iterator(out)) left.push_back(e.path().filename().string());
  EXPECT_TRUE(left.empty()) << "output left behind: " << left.front();
}

INSTANTIATE_TEST_SUITE_P(Corpus, Hostile, ::testing::ValuesIn(cases()), [](const ::testing::TestParamInfo<Case>& p) {
  std::string n = p.param.name;
  std::replace_if(n.begin(), n.end(), [](char ch) { return !std::isalnum(static_cast<unsigned char>(ch)); }, '_');
  return n;
});

TEST(HostileCorpus, EveryCaseHasItsExpectationsAndEveryGeneratorItsCase) {
  std::error_code ec;
  int committed = 0;
  for (const auto& e : fs::directory_iterator(kHostile / "cases", ec)) {
    if (e.path().extension() != ".json") continue;
    ++committed;
    EXPECT_TRUE(fs::exists(kHostile / "cases" / (e.path().stem().string() + ".expected"))) << e.path();
  }
  for (const auto& [name, generator] : generators())
    EXPECT_TRUE(fs::exists(kHostile / "generated" / (name + ".expected"))) << name;
  EXPECT_GE(committed, 15);
}

}  // namespace
}  // namespace pt
