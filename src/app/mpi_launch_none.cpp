// --mpi in a build without MPI (mpi_launch.h).
#include <iostream>

#include "app/mpi_launch.h"
#include "app/options.h"

namespace pt {

bool mpi_built() { return false; }

int run_with_mpi(const Options&, const std::function<int(const Options&)>&) {
  std::cerr << "error: --mpi: this pathtracer was built without MPI (install libopenmpi-dev, or another MPI, and "
               "configure again; docs/distributed.md)\n";
  return kExitUsage;
}

int mpi_gather(const Options&, const ShardInfo&, const Film&, const ExrSettings&, OutputStamps&) { return kExitFailure; }

}  // namespace pt
