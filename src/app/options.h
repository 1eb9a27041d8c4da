// The pathtracer command line: its options and their parsing (CLI11).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace pt {

struct Options {
  std::string scene;
  std::vector<std::string> outputs;
  std::string accel = "bvh";  // the faster in path tracing (docs/performance.md)
  int threads = 0;     // 0: all hardware threads
  int spp = 0;         // 0: the scene's value (unless a time budget alone is given)
  uint64_t seed = 0;
  std::string integrator;  // empty: the scene's value
  int max_depth = -1;      // < 0: the scene's value
  std::string filter;      // empty: the scene's value
  std::string sampler = "sobol";  // the path integrator's sampler (docs/samplers.md)
  float clamp = -1.0f;     // < 0: the scene's value; 0 = off
  int width = 0, height = 0;
  bool strict = false;
  bool quiet = false;
  std::string report;  // run record (JSON); empty: none
  // Display images (PNG, JPEG, PPM); see src/io/display.h.
  std::optional<float> exposure;  // stops; unset: the scene's
  std::string view, display, look;
  std::string ocio_config;  // unset: $OCIO
  // Long renders (docs/cli.md).
  double time_budget = 0;          // seconds of rendering; 0: none
  int pass_spp = 0;                // samples per progressive pass; 0: automatic
  std::string checkpoint;          // checkpoint file; empty: none
  double checkpoint_every = 60;    // seconds between checkpoints
  std::string resume;              // checkpoint to continue from
  double progress_interval = 10;   // seconds between progress lines when stderr is not a terminal
  std::vector<std::string> overrides;  // --set key=value
  std::string max_memory;          // e.g. "4G"; empty: physical memory only
  std::string texture_cache;       // --texture-cache, e.g. "512M"; empty: TextureCache::kDefaultBytes
  // AOVs, crops and replays (docs/output.md).
  std::string aov;                 // --aov list; empty: beauty only
  int cryptomatte_levels = 6;      // ranks per Cryptomatte AOV (kCryptomatteDefaultRanks)
  bool film_transparent = false;   // the scene's render.film_transparent, or true
  std::string exr_compression = "zip";
  bool multipart = false;          // EXR: one part per layer
  std::vector<double> crop;        // fractions x0, y0, x1, y1; empty: the full frame
  std::vector<int> crop_px;        // pixels x, y, w, h; empty: the full frame
  // The replay of one sample: --pixel X,Y [--sample N], or the shorthand
  // --replay X,Y,N. Parsing folds both into `replay` (x, y, sample), which the
  // rest of the program reads; `replay_option` is the spelling used.
  std::vector<int> pixel;          // --pixel X,Y as given
  int sample = 0;                  // --sample N (with --pixel)
  std::vector<int> replay;         // x, y, sample; empty: a normal render
  std::string replay_option;       // "--pixel" or "--replay"; empty: a normal render

  // Distributed rendering (docs/distributed.md; the options: shard_options.cpp).
  std::string shard;               // "K/N": share K of N of every pixel's samples; empty: all
  std::vector<int> sample_range;   // A,B: samples [A, B) of every pixel; empty: all
  std::string tile;                // "K/N": band K of N of the region; empty: all of it
  std::string shard_out;           // the film state and its provenance, for `pathtracer merge`
  bool mpi = false;                // under mpirun: rank r renders shard r/size, rank 0 merges

  bool replaying() const { return !replay.empty(); }
  // A shard of a distributed render (any of the options above).
  bool sharded() const { return !shard.empty() || !sample_range.empty() || !tile.empty() || !shard_out.empty() || mpi; }
  // The option that gave the replayed sample's index (for messages).
  const char* sample_option() const { return replay_option == "--pixel" ? "--sample" : "--replay"; }
};

// Exit statuses (docs/cli.md); a render stopped by a signal exits with 128 + its number.
constexpr int kExitFailure = 1;
constexpr int kExitUsage = 2;

void add_options(CLI::App& app, Options& o);
// The distributed-rendering group (shard_options.cpp), called by add_options.
void add_distributed_options(CLI::App& app, Options& o);
// For CLI11's "arguments were not expected": one line per unknown option in
// `extras` (app.remaining()), "unknown option '--samples'; did you mean
// '--spp'?" (a table of other tools' names, then the edit distance), or ""
// when none of them looks like an option (then CLI11's message stands).
std::string unknown_option_message(const CLI::App& app, const std::vector<std::string>& extras);
std::string version_text();

}  // namespace pt
