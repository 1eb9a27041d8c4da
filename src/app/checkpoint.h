// Render checkpoints (`--checkpoint FILE`, `--resume FILE`; docs/cli.md).
//
// A checkpoint is written atomically at a pass boundary and holds what a later
// run needs to continue exactly where this one stopped:
//   line 1   "pathtracer-checkpoint 1"
//   line 2   one JSON object: the scene path, an FNV-1a hash of the scene file's
//            bytes (and of the --set overrides), the settings that determine the
//            image (integrator, resolution, seed, sampler, ...), and spp_done;
//   then     the film state (Film::write_state: every pixel's sums, bit for bit).
// A resumed render continues with first_sample = spp_done and the same pass
// schedule, so it adds the same samples in the same order as an uninterrupted
// render: the images are bit-identical.
#pragma once

#include <cstddef>
#include <cstdint>
#include <iosfwd>
#include <string>

#include <nlohmann/json.hpp>

namespace pt {

class Film;

struct CheckpointInfo {
  std::string scene;            // the scene path as given
  std::string scene_hash;       // 16 hex digits
  nlohmann::ordered_json settings;  // compared key by key on resume
  int spp_done = 0;
};

// FNV-1a 64 of the file's bytes followed by each extra string (and a separator);
// empty with `error` set when the file cannot be read.
std::string scene_content_hash(const std::string& path, const std::string& extra, std::string& error);

// The largest spp_done a header may hold (the driver's "no target" count).
constexpr int kMaxCheckpointSpp = 1 << 30;

bool write_checkpoint(const std::string& path, const CheckpointInfo& info, const Film& film, std::string& error);
// The same file's bytes, to a stream.
bool write_checkpoint(std::ostream& out, const CheckpointInfo& info, const Film& film);

// Every field of the header is checked: "scene" a string, "scene_hash" 16 hex
// digits, "settings" an object, "spp_done" an integer in [0, kMaxCheckpointSpp].
// Errors name the file: "'<path>': damaged checkpoint header: ...". Nothing
// here throws, whatever the bytes.
//
// Reads the header only (to compare before the scene is built).
bool read_checkpoint_info(const std::string& path, CheckpointInfo& info, std::string& error);
bool read_checkpoint_info(std::istream& in, const std::string& path, CheckpointInfo& info, std::string& error);
// Reads header and film state into `film` (which must have the checkpoint's
// size, crop and AOVs). The film is changed only if the whole file is valid:
// a film state whose pixels hold more samples than spp_done does not belong
// to its header and is refused.
bool read_checkpoint(const std::string& path, CheckpointInfo& info, Film& film, std::string& error);
// The same from a stream; `path` names it in messages.
bool read_checkpoint(std::istream& in, const std::string& path, CheckpointInfo& info, Film& film, std::string& error);

// The first two lines of a checkpoint or shard file: `magic_line`, then one
// JSON object of at most `max_bytes` bytes and 16 levels of nesting. Errors
// name the file and `kind`: "'<path>' is not a pathtracer <kind>", "'<path>':
// damaged <kind> header: ...". Nothing here throws, whatever the bytes.
bool read_json_header(std::istream& in, const std::string& path, const std::string& magic_line, const std::string& kind,
                      nlohmann::ordered_json& out, std::string& error, std::size_t max_bytes);

// Why `saved` cannot be resumed by a run with `current` (scene hash or settings
// differ), or an empty string when it can.
std::string checkpoint_mismatch(const CheckpointInfo& saved, const CheckpointInfo& current);

}  // namespace pt
