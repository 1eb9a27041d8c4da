// Shard files (--shard-out; docs/distributed.md): a film's exact state and
// where it came from, for `pathtracer merge`.
//
//   line 1   "pathtracer-shard 2" (1: film states before coverage and exact Cryptomatte)
//   line 2   one JSON object (ShardInfo): the scene path and hashes, the
//            version and build, the settings every shard must share, the
//            target, the window, the pieces (which samples of which pixels
//            this state holds), the AOV list, the display settings and the
//            image metadata of the render;
//   then     the film state (Film::write_state), over `crop`.
// A merge writes the same format, its pieces the union of its inputs', so
// merges can be merged again (a tree of merges gives the same bits).
#pragma once

#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/shard.h"
#include "io/display.h"
#include "io/image_metadata.h"
#include "render/film/film.h"

namespace pt {

// Samples `done` (a prefix of `share`: a time budget may stop a shard early)
// of every pixel of `crop`, which is tile `tile` of the window (none: the window).
struct ShardPiece {
  PixelRect crop;
  std::optional<Fraction> tile;
  Range share, done;
};

struct ShardInfo {
  std::string scene;        // the scene path as given
  std::string scene_hash;   // the scene file and --set overrides (as checkpoints)
  std::string assets_hash;  // meshes, textures, environment map
  std::string version;      // PT_VERSION
  std::string build;        // the executable's hash
  nlohmann::ordered_json settings;  // ShardPlan::identity
  int width = 0, height = 0;        // the frame
  int target_spp = 0;
  PixelRect window;          // the region the tiles split
  PixelRect crop;            // the film state's pixels
  std::string aovs;          // --aov syntax, beauty type included: "albedo:half,beauty:float"
  int cryptomatte_levels = kCryptomatteDefaultRanks;  // the ranks of its Cryptomatte AOVs (--cryptomatte-levels)
  std::vector<ShardPiece> pieces;
  DisplaySettings display;   // for the merge's display images
  ImageMetadata metadata;    // the render's image metadata (camera, settings, backend)
  double render_seconds = 0;  // summed over the pieces
  bool partial = false;       // a merge of an incomplete set (--allow-partial)

  // The AOVs and beauty type of `aovs` (false with `error` if damaged).
  bool film_aovs(std::vector<AovRequest>& out, ChannelType& beauty, std::string& error) const;
};

// The header of the shard `job` rendered into `film` (the samples up to
// outcome.spp_done), with the render's image metadata.
struct Job;
struct RenderOutcome;
ShardInfo shard_info(const Job& job, const Film& film, const RenderOutcome& outcome, const ImageMetadata& metadata,
                     double render_seconds);
// The --aov spelling of a film's AOVs and beauty type: "albedo:half,Z:float,beauty:float".
std::string aov_list_text(const std::vector<AovRequest>& aovs, ChannelType beauty);

// Writes atomically; false with `error`.
bool write_shard(const std::string& path, const ShardInfo& info, const Film& film, std::string& error);
bool write_shard(std::ostream& out, const ShardInfo& info, const Film& film);

// Reads the header; every field is checked (types, ranges, pieces inside
// the frame and the target). Errors name `path`.
bool read_shard_info(std::istream& in, const std::string& path, ShardInfo& info, std::string& error);
// Reads the film state that follows the header (a film made from the
// header); checks that no pixel holds more samples than the pieces say.
// std::nullopt with `error`.
std::optional<Film> read_shard_film(std::istream& in, const std::string& path, const ShardInfo& info,
                                    std::string& error);

// The settings of two shards that differ ("seed 1 vs 2, width 64 vs 32"; the
// scene, assets, version, target, frame, window, AOVs and display included),
// or "" when they may be merged.
std::string shard_mismatch(const ShardInfo& a, const ShardInfo& b);

// ImageMetadata as JSON and back (every attribute and its type).
nlohmann::ordered_json metadata_json(const ImageMetadata& metadata);
bool metadata_from_json(const nlohmann::ordered_json& j, ImageMetadata& out);

}  // namespace pt
