#include <sstream>
#include <string>
#include <vector>

#include "fuzz_check.h"
#include "fuzz_targets.h"
#include "render/film/film.h"

namespace pt::fuzz {

namespace {

// The films a state is read into: the shapes of the seeds (4x3, the whole
// frame, without AOVs and with every AOV at its default type) and a crop.
std::vector<Film> target_films() {
  std::vector<AovRequest> all;
  for (const AovInfo& info : aov_catalogue()) all.push_back({info.type, info.default_type});
  std::vector<Film> films;
  films.emplace_back(4, 3);
  films.emplace_back(4, 3, PixelRect{0, 0, 4, 3}, all);
  films.emplace_back(8, 6, PixelRect{2, 1, 6, 4}, std::vector<AovRequest>{{AovType::Albedo, ChannelType::Half}});
  return films;
}

std::string state_of(const Film& film) {
  std::ostringstream out;
  film.write_state(out);
  return out.str();
}

}  // namespace

int film_state_one_input(const uint8_t* data, std::size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  for (Film& film : target_films()) {
    const std::string before = state_of(film);
    std::istringstream in(bytes);
    std::string error;
    if (!film.read_state(in, error)) {
      require(!error.empty(), "a refused film state says why");
      require(state_of(film) == before, "a refused film state leaves the film unchanged");
      continue;
    }
    // Accepted: the film holds exactly these bytes (written back bit for bit)
    // and can be turned into images without trouble.
    require(state_of(film) == bytes, "an accepted film state is written back unchanged");
    const Image image = film.image();
    require(image.width == film.crop().width() && image.height == film.crop().height(),
            "the image of an accepted state has the crop's size");
    const LayeredImage layers = film.layers();
    (void)layers;
  }
  return 0;
}

}  // namespace pt::fuzz
