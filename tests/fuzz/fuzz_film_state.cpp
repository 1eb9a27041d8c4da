#include <sstream>
#include <string>
#include <vector>

#include "fuzz_check.h"
#include "fuzz_films.h"
#include "fuzz_targets.h"
#include "render/film/film.h"

namespace pt::fuzz {

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
