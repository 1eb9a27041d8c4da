// Distributed rendering (docs/distributed.md): a render split into shards
// that other machines render and `pathtracer merge` adds back up.
//
// A shard is a share of every pixel's samples (--shard K/N, --sample-range
// A,B), a tile of the frame (--tile K/N), or both. It writes its film's exact
// state (render/film/exact_sum.h) and its provenance to a shard file
// (--shard-out; shard_file.h). Because a sample depends on (seed, pixel,
// index) only and the film's sums are exact, the merge of any complete set of
// shards is bit-identical to the render on one machine.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "render/film/film.h"

namespace pt {

struct Job;
struct Messages;
struct Options;
struct SceneDescription;

// "K/N" with 0 <= K < N (K counts from 0, as Slurm array indices and MPI ranks do).
struct Fraction {
  int k = 0, n = 1;
};
// Parses "K/N"; std::nullopt with `error` ("K must be in 0..N-1", ...).
std::optional<Fraction> parse_fraction(const std::string& text, std::string& error);

// Share k of n of `units` whole units: units [floor(k*units/n), floor((k+1)*units/n)).
// Shares differ in size by at most one unit and together are every unit once.
struct Range {
  int begin = 0, end = 0;
  int size() const { return end - begin; }
  bool operator==(const Range&) const = default;
  std::string text() const;  // "[begin,end)"
};
Range share_of(Fraction share, int units);

// Tile k of n of `window`: bands of whole rows, from the top, of sizes that
// differ by at most one row. Empty when the window has fewer than n rows.
PixelRect tile_of(const PixelRect& window, Fraction tile);

// What a shard render is: set by plan_shard, read by the job's later steps.
struct ShardPlan {
  bool active = false;     // --shard, --sample-range, --tile, --shard-out or --mpi
  int target_spp = 0;      // the whole render's samples per pixel
  int unit = 1;            // shares are whole multiples of this (the pass size of stratified samplers)
  Range share;             // the samples of every pixel this shard renders
  std::optional<Fraction> tile;  // --tile
  PixelRect window;        // the region the tiles split (the crop, or the frame)
  nlohmann::ordered_json identity;  // the settings every shard of the render must share
  std::string assets_hash;          // meshes, textures and environment map (16 hex digits)
};

// The shard's share of samples and its plan (start, target and pass size of
// job.plan); the region comes later, with the crop (film_options.h:
// crop_window). False after adding why to `messages` (a share that does not
// exist, a sampler whose passes cannot be split there, ...).
bool plan_shard(const Options& o, Job& job, Messages& messages);

// A 64-bit hash (16 hex digits) of the files and data the scene reads beyond
// its JSON: mesh data (as loaded), texture files and the environment map.
std::string assets_hash(const SceneDescription& desc);

// The running executable's identity: a hash of its bytes (16 hex digits),
// "unknown" where it cannot be read. Shards of different builds may differ.
std::string build_hash();

}  // namespace pt
