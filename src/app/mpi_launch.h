// The OpenMPI launcher (`mpirun -np N pathtracer SCENE --mpi ...`;
// docs/distributed.md): rank r of N renders share r/N of every pixel's
// samples, ranks 1..N-1 send their film states to rank 0, which merges them
// exactly (ShardMerger) and writes the outputs. Built with MPI when CMake
// finds it (mpi_launch.cpp); otherwise --mpi says so (mpi_launch_none.cpp).
// Part of the pathtracer executable: it prints.
#pragma once

#include <functional>

namespace pt {

class Film;
class OutputStamps;
struct ExrSettings;
struct Options;
struct ShardInfo;

// True when this build has MPI.
bool mpi_built();

// Initialises MPI, gives `run` the options with --shard set to this rank's
// share (ranks above 0 quiet), and finalises. A rank whose `run` returns
// before mpi_gather (an error) still answers rank 0, which then fails too.
int run_with_mpi(const Options& o, const std::function<int(const Options&)>& run);

// After this rank's render: ranks above 0 send `info` and `film` to rank 0
// and return; rank 0 merges every rank's state in rank order and writes -o
// (with `exr` and `stamps`, as a render's outputs) and --shard-out. Returns
// the exit status.
int mpi_gather(const Options& o, const ShardInfo& info, const Film& film, const ExrSettings& exr,
               OutputStamps& stamps);

}  // namespace pt
