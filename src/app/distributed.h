// The pathtracer executable's side of distributed rendering
// (docs/distributed.md): what a shard does after its render, and the
// `pathtracer merge` command. They print; the work is pt_app's (shard.h,
// shard_file.h, shard_merge.h).
#pragma once

namespace pt {

class Film;
struct RenderScene;
struct Job;
struct Options;
struct RenderOutcome;
struct RunFigures;

// After the render of a shard (Job::shard.active): writes -o (the shard's own
// image), --shard-out and --report, or under --mpi hands the state to
// mpi_gather. A shard stopped by a signal writes no state (its last pass is
// incomplete): it is rendered again, or resumed from its --checkpoint.
// Returns the exit status.
int finish_shard(const Options& o, Job& job, const RenderScene& scene, const Film& film,
                 const RenderOutcome& outcome, RunFigures& figures, int signal);

// `pathtracer merge SHARD... -o OUT [-o OUT2] [--shard-out FILE]
// [--allow-partial]`: argv[1] is "merge". Returns the exit status.
int merge_main(int argc, char** argv);

}  // namespace pt
