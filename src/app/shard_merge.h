// The merge of shards (`pathtracer merge`, the MPI launcher's rank 0;
// docs/distributed.md): their headers checked against each other, their film
// states added up exactly, the coverage checked, the result's provenance.
//
// The result does not depend on the order in which shards are added: the
// sums are exact integers, maxima commute, Cryptomatte keeps the smallest ids
// (a set, whatever the order: render/film/film.cpp), and a first-sample AOV (P, Z, ids)
// takes, per tile, the value of the shard whose samples there start lowest.
// The file merge still adds in a fixed order (tile, then first sample).
#pragma once

#include <future>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <tuple>
#include <vector>

#include "app/shard_file.h"
#include "io/image_io.h"
#include "io/image_metadata.h"
#include "render/film/film.h"

namespace pt {

class ExrBandWriter;  // imagelib/image_library.h
class OutputStamps;

class ShardMerger {
 public:
  explicit ShardMerger(bool allow_partial) : allow_partial_(allow_partial) {}

  // Checks `info` against the shards checked before: the same scene, assets,
  // version, settings, frame, target, window, AOVs and display, and no piece
  // that overlaps one of theirs. False with `error` naming both shards and
  // the difference. A different build only warns (warnings()).
  bool check(const std::string& name, const ShardInfo& info, std::string& error);
  // Adds the film of a checked shard. False with `error`.
  bool add(const std::string& name, const ShardInfo& info, const Film& film, std::string& error);
  // The same from its film state as it is read (read_shard_info has read the
  // header): one block at a time, so that a merge holds one film in memory.
  // Also checks that no pixel holds more samples than the pieces say. After
  // a failure the merged film is unusable.
  bool add(const std::string& name, const ShardInfo& info, std::istream& state, std::string& error);
  // The same from the film state in memory (the rest of a mapped shard file
  // after its header, a received message): its size checked first, then
  // added in parallel (Film::add_state), the same bits.
  bool add(const std::string& name, const ShardInfo& info, std::string_view state, std::string& error);
  // The band merge (`pathtracer merge`; docs/distributed.md, "The merge"):
  // the merged layers straight from the film states of every checked shard,
  // `states[i]` that of the i-th checked (in memory: a mapped shard file
  // after its header), without a merged film: per band of rows, in parallel,
  // every shard's rows are added into a band film, in the order checked, and
  // resolved into `out`, so that only the shards' bytes stream through
  // memory, once. The same bits as add() of each, then film().layers(); the
  // same checks (a state's size before anything is added, samples per pixel,
  // Cryptomatte slots). False with `error` naming the shard.
  bool merge_layers(const std::vector<std::string_view>& states, LayeredImage& out, std::string& error);
  // The band merge in steps, for the streamed write. view_states: every
  // state viewed (its size checked) and its precedence taken, before
  // anything is added; false with `error` naming the shard, as merge_layers.
  bool view_states(const std::vector<std::string_view>& states, std::string& error);
  // After view_states: the merged image's layout (frame, window, layers), without values.
  LayeredImage layout() const;
  // After view_states: merge_layers' bands written as they are made. Every
  // band of rows is added and resolved as merge_layers does, packed for the
  // file (io/exr_pack.h) and handed to the writer `file` gives (one part:
  // io/image_io.h, write_exr_bands) in order, while the next bands are
  // merged (a TBB pipeline), so that the write overlaps the merge and the
  // whole image's layers are never held. The first bands are merged while
  // the file is opened (the image module's load); the first write waits for
  // it (nullptr: it could not be opened). The same bytes as write_exr of
  // merge_layers' image. False with `error`: `refused` says whether a state
  // was refused (the message merge_layers gives, naming the shard; nothing
  // is written after the refused band) or the writer failed (its message;
  // empty if the file could not be opened).
  // `lines`: the file is uncompressed (io/exr_uncompressed.h,
  // writes_uncompressed_exr): the rows are packed as it stores them
  // (uncompressed_exr_lines) and handed to its writer's write_lines.
  bool merge_streamed(const std::shared_future<ExrBandWriter*>& file, bool lines, std::string& error, bool& refused);
  // The merged beauty's half/float type.
  ChannelType beauty_type() const;
  // After the last shard: every tile of the window and every sample of the
  // target present? Missing pieces are an error, unless allowed: then the
  // result is marked partial and notes() says what is missing.
  bool finish(std::string& error);

  const Film& film() const { return *film_; }
  // The merged provenance: the pieces of every shard, their render times
  // summed, partial when pieces are missing.
  const ShardInfo& info() const { return merged_; }
  // The samples every rendered pixel has: the fewest over the tiles.
  int spp() const;
  // The image metadata of the merged render (the shards' own, with the
  // render time summed, spp, partial, and pathtracer:shards describing them).
  ImageMetadata metadata() const;
  const std::vector<std::string>& warnings() const { return warnings_; }
  const std::string& notes() const { return notes_; }
  int shards() const { return static_cast<int>(names_.size()); }

 private:
  using Key = std::tuple<int, int, int, int>;  // a piece's crop
  struct Placed {
    ShardPiece piece;
    std::string name;
  };
  bool check_pieces(const std::string& name, const ShardInfo& info, std::string& error) const;
  bool make_film(std::string& error);
  // What a film state of `info` may add (Film::add_state), with `order` its precedence().
  // Rows [y0, y1) of its crop only, when given (a band).
  StateRules rules(const ShardInfo& info, const std::map<Key, std::pair<bool, int>>& order) const;
  StateRules rules(const ShardInfo& info, const std::map<Key, std::pair<bool, int>>& order, int y0, int y1) const;
  template <typename State>
  bool add_state(const std::string& name, const ShardInfo& info, State&& state, std::string& error);
  // Per crop of `info`'s pieces: whether its first-sample values come first
  // there (its lowest first sample is below every earlier shard's), and that
  // first sample; the caller records the ones that come first.
  std::map<Key, std::pair<bool, int>> precedence(const ShardInfo& info) const;
  // The band merge's state (shard_band_merge.cpp): the viewed states, their
  // precedence, and per shard the first pixel refused.
  struct Bands;
  // Per shard, what its state may add in rows [y0, y1) of a band (rules();
  // an empty crop where it has none of them).
  std::vector<StateRules> band_rules(const Bands& b, int y0, int y1) const;
  // Adds every shard's pixels of `rect`, a block of a band's rows whose
  // band_rules are `rules`, into `band` (moved to `rect`).
  void add_band(Bands& b, Film& band, const PixelRect& rect, const std::vector<StateRules>& rules) const;
  // The refusal of the first shard (in order) that had a pixel refused; false if none.
  bool refused(const Bands& b, std::string& error) const;
  std::string missing_tiles() const;
  std::string missing_samples() const;

  bool allow_partial_;
  std::vector<std::string> names_;
  std::vector<ShardInfo> infos_;  // as checked
  ShardInfo merged_;
  std::vector<Placed> placed_;
  std::optional<Film> film_;
  std::shared_ptr<Bands> bands_;  // after view_states
  std::map<Key, int> first_start_;  // per crop: the lowest first sample added so far
  std::vector<std::string> warnings_;
  std::string notes_;
};

// Writes the merged images (`outputs`: EXR with every AOV at its recorded
// type, display images through the shards' display settings, with
// `ocio_config` replacing theirs when not empty) and, if `shard_out` is not
// empty, the merged state (a shard file of all the pieces, to merge again).
// False with the first error; files written before it stay.
// `exr` and `stamps` as for a render's outputs (app/outputs.h).
// The images alone, from the merged layers (film().layers() or merge_layers()).
bool write_merged_images(const ShardMerger& merger, const LayeredImage& layers, const std::vector<std::string>& outputs,
                         const std::string& ocio_config, const ExrSettings& exr, OutputStamps& stamps,
                         std::string& error);
bool write_merged(const ShardMerger& merger, const std::vector<std::string>& outputs, const std::string& shard_out,
                  const std::string& ocio_config, const ExrSettings& exr, OutputStamps& stamps, std::string& error);

}  // namespace pt
