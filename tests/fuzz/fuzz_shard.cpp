#include <sstream>
#include <string>

#include "app/shard_file.h"
#include "app/shard_merge.h"
#include "fuzz_check.h"
#include "fuzz_films.h"
#include "fuzz_targets.h"

namespace pt::fuzz {

namespace {

constexpr const char* kName = "fuzz.ptshard";  // the file name the messages must carry

bool names_the_file(const std::string& error) {
  return error.find(std::string("'") + kName + "'") != std::string::npos;
}

// What read_shard_info promises of an accepted header.
void check_header(const ShardInfo& info) {
  require(info.width >= 1 && info.height >= 1 && info.target_spp >= 1, "an accepted shard has a frame and a target");
  const PixelRect frame{0, 0, info.width, info.height};
  require(frame.contains(info.window) && frame.contains(info.crop) && !info.crop.empty(),
          "an accepted shard's window and crop are inside its frame");
  require(!info.pieces.empty(), "an accepted shard has pieces");
  for (const ShardPiece& p : info.pieces) {
    require(info.crop.contains(p.crop) && !p.crop.empty(), "a piece's pixels are inside the film state's");
    require(0 <= p.share.begin && p.share.begin <= p.share.end && p.share.end <= info.target_spp,
            "a piece's share is inside the target");
    require(p.done.begin == p.share.begin && p.done.end <= p.share.end,
            "a piece's done range is a prefix of its share");
    require(!p.tile || (0 <= p.tile->k && p.tile->k < p.tile->n), "a piece's tile is K/N with K < N");
  }
  require(shard_mismatch(info, info).empty(), "a shard matches itself");
  std::vector<AovRequest> aovs;
  ChannelType beauty;
  std::string error;
  require(info.film_aovs(aovs, beauty, error), "an accepted shard's AOV list parses");
}

}  // namespace

int shard_one_input(const uint8_t* data, std::size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  std::istringstream in(bytes);
  ShardInfo info;
  std::string error;
  if (!read_shard_info(in, kName, info, error)) {
    require(names_the_file(error), "a refused shard header names its file");
    return 0;
  }
  check_header(info);
  // Film states as large as a header may claim are not read here (memory).
  if (static_cast<int64_t>(info.crop.width()) * info.crop.height() > (1 << 16)) return 0;
  const std::streampos state_start = in.tellg();
  const std::optional<Film> film = read_shard_film(in, kName, info, error);
  // The streamed add (what `pathtracer merge` does) takes what the reader takes.
  ShardMerger streamed(true);
  std::istringstream state(bytes);
  state.seekg(state_start);
  std::string why;
  const bool checked = streamed.check(kName, info, why);
  const bool added = checked && streamed.add(kName, info, state, why);
  if (!film) {
    require(names_the_file(error), "a refused shard film state names its file");
    require(!added, "a film state the reader refuses is refused when streamed");
    return 0;
  }
  require(!checked || added, "a film state the reader accepts is accepted when streamed");
  // Written back and read again: the same header and film state.
  std::ostringstream out;
  require(write_shard(out, info, *film), "an accepted shard can be written");
  std::istringstream again(out.str());
  ShardInfo info_again;
  require(read_shard_info(again, kName, info_again, error), "a shard written back reads again");
  const std::optional<Film> film_again = read_shard_film(again, kName, info_again, error);
  require(film_again && state_of(*film_again) == state_of(*film), "a shard written back keeps its film state");
  // The merge of it alone checks, adds, finishes (partial allowed) and describes it.
  ShardMerger merger(true);
  if (merger.check(kName, info, error)) {
    require(merger.add(kName, info, *film, error), "a checked shard is added");
    require(merger.finish(error), "a partial merge is allowed to finish");
    (void)merger.metadata();
    (void)merger.film().layers();
  }
  return 0;
}

}  // namespace pt::fuzz
