// Hostile checkpoints given to --resume (docs/cli.md, "Checkpoints and
// resume"): wrong types, negative and huge counts, truncated and spliced
// files, checkpoints of another scene or resolution. Each must be refused with
// a message naming the checkpoint file and what is wrong with it, exit status
// 1, no crash or raw library exception text, and nothing written: no image, no
// new checkpoint, no temporary file.
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "app_fixture.h"

namespace pt::test {
namespace {

namespace fs = std::filesystem;

// A checkpoint's three parts: the magic line, the JSON header line, the film state.
struct Parts {
  std::string magic, header, body;
};

Parts split(const std::string& bytes) {
  const std::size_t a = bytes.find('\n');
  const std::size_t b = bytes.find('\n', a + 1);
  return {bytes.substr(0, a + 1), bytes.substr(a + 1, b - a), bytes.substr(b + 1)};
}

class ResumeHostile : public AppTest {
 protected:
  void SetUp() override {
    AppTest::SetUp();
    write("s.json", path_scene(8, 6, 1));
    ASSERT_EQ(run("s.json -o a.exr --spp 2 --checkpoint a.ckpt --quiet").status, 0);
    good_ = split(slurp(path("a.ckpt")));
    ASSERT_FALSE(good_.body.empty());
    fs::remove(path("a.exr"));
  }

  // The good checkpoint's header with `edit` applied to its JSON.
  template <class Edit>
  std::string with_header(Edit edit) const {
    nlohmann::ordered_json j = nlohmann::ordered_json::parse(good_.header);
    edit(j);
    return good_.magic + j.dump() + "\n" + good_.body;
  }

  // Resumes from `bytes` (written as bad.ckpt) and checks the refusal.
  void expect_refused(const std::string& bytes, const std::string& message, const std::string& extra = "") {
    write("bad.ckpt", bytes);
    const RunResult r = run("s.json -o out.exr --spp 4 --resume bad.ckpt --checkpoint next.ckpt" + extra);
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_NE(r.err.find("'bad.ckpt'"), std::string::npos) << "the file is not named:\n" << r.err;
    EXPECT_NE(r.err.find(message), std::string::npos) << "expected: " << message << "\nstderr:\n" << r.err;
    EXPECT_EQ(r.err.find("exception"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("wrote"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(path("out.exr")));
    EXPECT_FALSE(fs::exists(path("next.ckpt")));
    EXPECT_FALSE(has_temporary_files());
  }

  Parts good_;
};

TEST_F(ResumeHostile, HeaderFieldsOfTheWrongTypeAreRefused) {
  using J = nlohmann::ordered_json;
  expect_refused(with_header([](J& j) { j["scene"] = 5; }), "\"scene\" must be a string, got number 5");
  expect_refused(with_header([](J& j) { j["scene"] = nullptr; }), "\"scene\" must be a string, got null");
  expect_refused(with_header([](J& j) { j["scene_hash"] = 123; }), "\"scene_hash\" must be 16 hexadecimal digits");
  expect_refused(with_header([](J& j) { j["scene_hash"] = "not-a-hash"; }),
                 "\"scene_hash\" must be 16 hexadecimal digits, got string \"not-a-hash\"");
  expect_refused(with_header([](J& j) { j["settings"] = "path"; }), "\"settings\" must be an object, got string");
  expect_refused(with_header([](J& j) { j["settings"] = J::array({1, 2}); }), "\"settings\" must be an object");
  expect_refused(with_header([](J& j) { j["spp_done"] = "2"; }), "\"spp_done\" must be an integer, got string \"2\"");
  expect_refused(with_header([](J& j) { j["spp_done"] = 2.5; }), "\"spp_done\" must be an integer, got number 2.5");
  expect_refused(with_header([](J& j) { j["spp_done"] = true; }), "\"spp_done\" must be an integer, got boolean");
}

TEST_F(ResumeHostile, NegativeAndHugeCountsAreRefused) {
  using J = nlohmann::ordered_json;
  expect_refused(with_header([](J& j) { j["spp_done"] = -1; }), "\"spp_done\" must be in [0, 1073741824], got -1");
  expect_refused(with_header([](J& j) { j["spp_done"] = 1000000000000LL; }), "got 1000000000000");
  expect_refused(with_header([](J& j) { j["spp_done"] = 18446744073709551615ULL; }), "got 18446744073709551615");
  // In range, but fewer than the film state holds: the header and the body do not belong together.
  expect_refused(with_header([](J& j) { j["spp_done"] = 1; }), "more than the header's spp_done 1");
}

TEST_F(ResumeHostile, DamagedHeadersAreRefused) {
  using J = nlohmann::ordered_json;
  expect_refused(with_header([](J& j) { j.erase("spp_done"); }), "damaged checkpoint header: no \"spp_done\"");
  expect_refused(with_header([](J& j) { j["extra"] = 1; }), "unknown key \"extra\"");
  expect_refused(good_.magic + "{\"scene\": \n" + good_.body, "its second line is not a JSON object");
  expect_refused(good_.magic + "[1, 2]\n" + good_.body, "its second line is not a JSON object");
  expect_refused(good_.magic + good_.header.substr(0, 20), "the file ends inside its second line (truncated)");
  expect_refused(good_.magic + std::string(100000, ' ') + "\n", "its second line is longer than 65536 bytes");
  // 5000 nested arrays, spliced in as text: building and printing them with
  // nlohmann::json would recurse 5000 deep in the test itself (a stack
  // overflow under AddressSanitizer's larger frames).
  std::string deep = with_header([&](J& j) { j["settings"]["deep"] = "DEEP"; });
  deep.replace(deep.find("\"DEEP\""), 6, std::string(5000, '[') + std::string(5000, ']'));
  expect_refused(deep, "its JSON nests deeper than 16 levels");
  expect_refused("", "'bad.ckpt' is not a pathtracer checkpoint");
  expect_refused(std::string("\0\1\2\3binary", 10), "'bad.ckpt' is not a pathtracer checkpoint");
}

TEST_F(ResumeHostile, DamagedFilmStatesAreRefused) {
  expect_refused(good_.magic + good_.header, "not a film state");                                // header only
  expect_refused(good_.magic + good_.header + good_.body.substr(0, good_.body.size() / 2), "truncated film state");
  expect_refused(good_.magic + good_.header + good_.body + "x", "film state has trailing data");
  // A sample count beyond the header's spp_done (the sums are exact
  // integers: any bits are some sum, none is non-finite): every pixel holds
  // the same count, so it is the state's default, after its header (89
  // bytes, no AOVs) and the default record's five sums.
  std::string body = good_.body;
  const std::size_t first_count = 89 + 5 * 8;
  const uint32_t many = 1000;
  body.replace(first_count, sizeof many, reinterpret_cast<const char*>(&many), sizeof many);
  expect_refused(good_.magic + good_.header + body, "holds 1000 samples in pixel (0, 0)");
  // A checkpoint of an older pathtracer (film state version 5), refused naming the version.
  body = good_.body;
  ASSERT_EQ(body.substr(0, 8), "PTFILM\r\n");
  body[8] = 5;
  expect_refused(good_.magic + good_.header + body, "film state version 5 is not read by this pathtracer");
}

TEST_F(ResumeHostile, CheckpointsOfAnotherSceneOrResolutionAreRefused) {
  // Another resolution, as written: its settings say so.
  ASSERT_EQ(run("s.json -o b.exr --spp 2 --width 16 --checkpoint b.ckpt --quiet").status, 0);
  const Parts other = split(slurp(path("b.ckpt")));
  expect_refused(slurp(path("b.ckpt")), "the settings differ from the checkpoint's: width 16 -> 8, height 12 -> 6");
  // Spliced: this run's header on the other film state.
  expect_refused(good_.magic + good_.header + other.body, "film state is 16x12, the render is 8x6");
  // Another scene.
  write("t.json", path_scene(8, 6, 3));
  ASSERT_EQ(run("t.json -o c.exr --spp 2 --checkpoint c.ckpt --quiet").status, 0);
  expect_refused(slurp(path("c.ckpt")), "the scene differs: the checkpoint was made from 't.json'");
  // A missing checkpoint.
  const RunResult r = run("s.json -o out.exr --spp 4 --resume missing.ckpt");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("cannot open checkpoint 'missing.ckpt'"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(path("out.exr")));
}

// The good checkpoint itself resumes (the refusals above are not refusals of everything).
TEST_F(ResumeHostile, TheUndamagedCheckpointResumes) {
  const RunResult r = run("s.json -o out.exr --spp 4 --resume a.ckpt --checkpoint next.ckpt --quiet");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(fs::exists(path("out.exr")));
  EXPECT_TRUE(fs::exists(path("next.ckpt")));
}

}  // namespace
}  // namespace pt::test
