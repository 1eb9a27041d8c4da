// The command line's distributed-rendering options (docs/distributed.md).
#include <CLI/CLI.hpp>

#include "app/options.h"
#include "app/shard.h"

namespace pt {

// Listed in --help as their own group, after "Long renders".
void add_distributed_options(CLI::App& app, Options& o) {
  constexpr const char* kGroup = "Distributed rendering";
  const auto fraction = [](const std::string& text) {
    std::string error;
    return parse_fraction(text, error) ? std::string() : error;
  };
  auto* shard = app.add_option("--shard", o.shard,
                               "Render share K of N (K = 0..N-1) of every pixel's samples; with --shard-out, for "
                               "`pathtracer merge` (docs/distributed.md)")
                    ->check(CLI::Validator(fraction, "K/N"))
                    ->group(kGroup);
  auto* range = app.add_option("--sample-range", o.sample_range,
                               "Render samples [A, B) of every pixel (0 <= A < B <= the render's spp)")
                    ->delimiter(',')
                    ->expected(2)
                    ->excludes(shard)
                    ->group(kGroup);
  app.add_option("--tile", o.tile,
                 "Render tile K of N (K = 0..N-1) of the frame (or of --crop): bands of whole rows, from the top")
      ->check(CLI::Validator(fraction, "K/N"))
      ->group(kGroup);
  app.add_option("--shard-out", o.shard_out,
                 "Write the film's exact state and its provenance to this file, for `pathtracer merge`")
      ->group(kGroup);
  app.add_flag("--mpi", o.mpi,
               "Under mpirun: rank r of N renders share r/N of the samples and rank 0 merges them and writes -o")
      ->excludes(shard)
      ->excludes(range)
      ->group(kGroup);
  for (const char* replay : {"--pixel", "--replay"}) {
    if (CLI::Option* r = app.get_option_no_throw(replay); r != nullptr) {
      r->excludes(shard);
      r->excludes(range);
    }
  }
}

}  // namespace pt
