#include <algorithm>
#include <sstream>
#include <string>

#include "app/checkpoint.h"
#include "fuzz_check.h"
#include "fuzz_films.h"
#include "fuzz_targets.h"

namespace pt::fuzz {

namespace {

constexpr const char* kName = "fuzz.ckpt";  // the file name the messages must carry

bool valid(const CheckpointInfo& info) {
  return info.scene_hash.size() == 16 &&
         std::all_of(info.scene_hash.begin(), info.scene_hash.end(),
                     [](char c) { return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'); }) &&
         info.settings.is_object() && info.spp_done >= 0 && info.spp_done <= kMaxCheckpointSpp;
}

bool same(const CheckpointInfo& a, const CheckpointInfo& b) {
  return a.scene == b.scene && a.scene_hash == b.scene_hash && a.settings.dump() == b.settings.dump() &&
         a.spp_done == b.spp_done;
}

bool names_the_file(const std::string& error) {
  return error.find(std::string("'") + kName + "'") != std::string::npos;
}

}  // namespace

int checkpoint_one_input(const uint8_t* data, std::size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  // The header alone, as --resume reads it before the scene is built.
  CheckpointInfo header;
  std::string header_error;
  std::istringstream header_in(bytes);
  const bool header_ok = read_checkpoint_info(header_in, kName, header, header_error);
  if (header_ok) {
    require(valid(header), "an accepted checkpoint header has fields of the right types and ranges");
    // The comparison with a run's identity never fails on the saved values' types.
    const nlohmann::ordered_json current = {{"integrator", "path"}, {"width", 4}, {"height", 3}, {"clamp", 0.0}};
    (void)checkpoint_mismatch(header, CheckpointInfo{"s.json", "0123456789abcdef", current, 0});
    require(checkpoint_mismatch(header, header).empty(), "a checkpoint header matches itself");
  } else {
    require(names_the_file(header_error), "a refused checkpoint header names its file");
  }
  // The whole file, into films of the seeds' shapes.
  for (Film& film : target_films()) {
    const std::string before = state_of(film);
    std::istringstream in(bytes);
    CheckpointInfo info;
    std::string error;
    if (!read_checkpoint(in, kName, info, film, error)) {
      require(names_the_file(error), "a refused checkpoint names its file");
      require(state_of(film) == before, "a refused checkpoint leaves the film unchanged");
      continue;
    }
    require(header_ok && same(info, header), "an accepted checkpoint has the header read alone");
    const PixelRect& c = film.crop();
    for (int y = c.y0; y < c.y1; ++y)
      for (int x = c.x0; x < c.x1; ++x)
        require(film.sum(x, y).samples <= static_cast<uint64_t>(info.spp_done),
                "no pixel of an accepted checkpoint holds more than spp_done samples");
    // Written back and read again: the same header and film state.
    std::ostringstream out;
    require(write_checkpoint(out, info, film), "an accepted checkpoint can be written");
    Film again(film.width(), film.height(), film.crop(), film.aovs());
    CheckpointInfo info_again;
    std::istringstream in_again(out.str());
    require(read_checkpoint(in_again, kName, info_again, again, error), "a checkpoint written back reads again");
    require(same(info_again, info), "a checkpoint written back keeps its header");
    require(state_of(again) == state_of(film), "a checkpoint written back keeps its film state");
  }
  return 0;
}

}  // namespace pt::fuzz
