// The OpenMPI launcher (mpi_launch.h). Only the main thread calls MPI.
#include "app/mpi_launch.h"

#include <mpi.h>

#include <algorithm>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <utility>

#include "app/options.h"
#include "app/outputs.h"
#include "app/shard_merge.h"
#include "core/memory_stream.h"
#include "core/stopwatch.h"

namespace pt {
namespace {

constexpr int kTagStatus = 1, kTagData = 2;
constexpr std::size_t kChunk = std::size_t{1} << 30;  // MPI counts are ints

// Whether this rank has reached mpi_gather. MPI itself is one session per
// process (MPI_Init once), and so is this flag.
bool gathered = false;

int rank_of_world() {
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  return rank;
}

int size_of_world() {
  int size = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  return size;
}

// Each rank above 0 sends {status, bytes}, then the bytes if status is 0.
void send_state(int status, const std::string& bytes) {
  const uint64_t header[2] = {static_cast<uint64_t>(status), static_cast<uint64_t>(bytes.size())};
  MPI_Send(header, 2, MPI_UINT64_T, 0, kTagStatus, MPI_COMM_WORLD);
  for (std::size_t at = 0; at < bytes.size(); at += kChunk) {
    const std::size_t n = std::min(kChunk, bytes.size() - at);
    MPI_Send(bytes.data() + at, static_cast<int>(n), MPI_BYTE, 0, kTagData, MPI_COMM_WORLD);
  }
}

// Rank `from`'s status and state (empty unless the status is 0).
int receive_state(int from, std::string& bytes) {
  uint64_t header[2] = {0, 0};
  MPI_Recv(header, 2, MPI_UINT64_T, from, kTagStatus, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  bytes.assign(header[0] == 0 ? header[1] : 0, '\0');
  for (std::size_t at = 0; at < bytes.size(); at += kChunk) {
    const std::size_t n = std::min(kChunk, bytes.size() - at);
    MPI_Recv(bytes.data() + at, static_cast<int>(n), MPI_BYTE, from, kTagData, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  }
  return static_cast<int>(header[0]);
}

// A rank whose run ended before mpi_gather (with `status`): above 0 it tells
// rank 0; rank 0 takes every other rank's answer so that none waits forever.
int fail_gather(int status) {
  if (status == 0) status = kExitFailure;
  if (rank_of_world() > 0) {
    send_state(status, {});
    return status;
  }
  std::string ignored;
  for (int r = 1; r < size_of_world(); ++r) receive_state(r, ignored);
  return status;
}

// Rank 0: rank r's state into the merger. False with `error`.
bool merge_rank(int r, std::string& bytes, ShardMerger& merger, std::string& error) {
  const std::string name = "rank " + std::to_string(r);
  MemoryBuffer buffer(bytes);  // a stream over the bytes, without copying them
  std::istream in(&buffer);
  ShardInfo info;
  return read_shard_info(in, name, info, error) && merger.check(name, info, error) &&
         merger.add(name, info, std::string_view(bytes).substr(buffer.consumed()), error);
}

}  // namespace

bool mpi_built() { return true; }

int run_with_mpi(const Options& o, const std::function<int(const Options&)>& run) {
  MPI_Init(nullptr, nullptr);
  const int rank = rank_of_world(), size = size_of_world();
  Options mine = o;
  mine.shard = std::to_string(rank) + "/" + std::to_string(size);
  if (rank > 0) mine.quiet = true;  // one voice: rank 0 prints progress and the result
  int status = run(mine);
  if (!gathered) status = fail_gather(status);
  MPI_Finalize();
  return status;
}

int mpi_gather(const Options& o, const ShardInfo& info, const Film& film, const ExrSettings& exr,
               OutputStamps& stamps) {
  gathered = true;
  if (rank_of_world() > 0) {
    std::ostringstream out;
    write_shard(out, info, film);
    send_state(0, std::move(out).str());  // C++20: the buffer, not a copy
    return 0;
  }
  const auto t0 = Clock::now();
  ShardMerger merger(false);
  std::string error, bytes;
  bool ok = merger.check("rank 0", info, error) && merger.add("rank 0", info, film, error);
  for (int r = 1; r < size_of_world(); ++r) {  // every rank answers, even after an error
    const int status = receive_state(r, bytes);
    if (ok && status != 0) {
      error = "rank " + std::to_string(r) + " failed (exit status " + std::to_string(status) + ")";
      ok = false;
    }
    if (ok) ok = merge_rank(r, bytes, merger, error);
  }
  ok = ok && merger.finish(error) && write_merged(merger, o.outputs, o.shard_out, "", exr, stamps, error);
  if (!ok) {
    std::cerr << "error: --mpi: " << error << '\n';
    return kExitFailure;
  }
  for (const std::string& w : merger.warnings()) std::cerr << "warning: " << w << '\n';
  if (!o.quiet) {
    std::vector<std::string> files = o.outputs;
    if (!o.shard_out.empty()) files.push_back(o.shard_out);
    std::cout << std::fixed << std::setprecision(3) << "wrote " << join(files, ", ") << " (" << merger.shards()
              << " MPI ranks, " << merger.spp() << " spp; rank 0 rendered " << info.render_seconds
              << " s, gathered, merged and wrote in " << seconds_since(t0) << " s)\n";
  }
  return 0;
}

}  // namespace pt
