// Replays through the fuzzing harnesses (fuzz_targets.h) every seed in
// tests/fuzz/seeds/<harness>/ and every input that ever crashed one of them,
// kept in tests/hostile/fuzz-regressions/<harness>/ (tools/dev/fuzz.sh copies new
// crashes there). Each harness checks its parser's invariants and aborts when
// one breaks, so a regression fails this test (under the sanitizer build too).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "app/checkpoint.h"
#include "fuzz_films.h"
#include "fuzz_targets.h"

namespace pt::fuzz {
namespace {

namespace fs = std::filesystem;

std::vector<fs::path> files_in(const fs::path& dir) {
  std::vector<fs::path> out;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec))
    if (e.is_regular_file() && e.path().filename() != "README.md") out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

std::string read(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

class Replay : public ::testing::TestWithParam<Harness> {};

TEST_P(Replay, SeedsAndPastCrashesKeepEveryInvariant) {
  const Harness h = GetParam();
  const fs::path tests(PT_TEST_DATA_DIR);
  std::vector<fs::path> inputs = files_in(tests / "fuzz" / "seeds" / h.name);
  const std::vector<fs::path> crashes = files_in(tests / "hostile" / "fuzz-regressions" / h.name);
  inputs.insert(inputs.end(), crashes.begin(), crashes.end());
  EXPECT_FALSE(inputs.empty()) << "no seeds for the " << h.name << " harness";
  for (const fs::path& p : inputs) {
    // Named before it runs: an invariant that breaks aborts the process.
    std::cerr << "[ replay   ] " << h.name << ": " << p.filename().string() << '\n';
    const std::string bytes = read(p);
    EXPECT_EQ(h.run(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size()), 0) << p;
  }
}

// Each seed in the folder is read by one of the target films (the
// fuzzer starts past the version and catalogue checks).
template <typename ReadFn>
void expect_each_read_by_one(const fs::path& folder, ReadFn read_fn) {
  const std::vector<fs::path> seeds = files_in(folder);
  ASSERT_FALSE(seeds.empty()) << folder;
  for (const fs::path& p : seeds) {
    const std::string bytes = read(p);
    bool read_by_one = false;
    std::string errors;
    for (Film& film : target_films()) {
      std::istringstream in(bytes);
      std::string error;
      read_by_one = read_by_one || read_fn(in, p, film, error);
      errors += error + "; ";
    }
    EXPECT_TRUE(read_by_one) << p << ": " << errors;
  }
}

// The film-state seeds are states this build reads (a new state version
// converts them: tools/dev/film_state_v5_to_v6.py).
TEST(Seeds, FilmStatesAreReadByOneOfTheTargetFilms) {
  expect_each_read_by_one(fs::path(PT_TEST_DATA_DIR) / "fuzz" / "seeds" / "film_state",
                          [](std::istream& in, const fs::path&, Film& film, std::string& error) {
                            return film.read_state(in, error);
                          });
}

// So are the checkpoint seeds (all.ckpt was one of a film with an older
// AOV catalogue, which no target film read, until session 17).
TEST(Seeds, CheckpointsAreReadByOneOfTheTargetFilms) {
  expect_each_read_by_one(fs::path(PT_TEST_DATA_DIR) / "fuzz" / "seeds" / "checkpoint",
                          [](std::istream& in, const fs::path& p, Film& film, std::string& error) {
                            CheckpointInfo info;
                            return read_checkpoint(in, p.filename().string(), info, film, error);
                          });
}

INSTANTIATE_TEST_SUITE_P(Harnesses, Replay, ::testing::ValuesIn(harnesses()),
                         [](const ::testing::TestParamInfo<Harness>& p) { return std::string(p.param.name); });

}  // namespace
}  // namespace pt::fuzz
