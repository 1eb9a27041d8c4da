// Test-only: the films the film_state and checkpoint harnesses read their
// inputs into, of the seeds' shapes: 4x3 without AOVs, 4x3 with every AOV at
// its default type, and an 8x6 frame cropped to [2, 6) x [1, 4) with the
// albedo AOV as half.
#pragma once

#include <sstream>
#include <string>
#include <vector>

#include "render/film/film.h"

namespace pt::fuzz {

inline std::vector<Film> target_films() {
  std::vector<AovRequest> all;
  for (const AovInfo& info : aov_catalogue()) all.push_back({info.type, info.default_type});
  std::vector<Film> films;
  films.emplace_back(4, 3);
  films.emplace_back(4, 3, PixelRect{0, 0, 4, 3}, all);
  films.emplace_back(8, 6, PixelRect{2, 1, 6, 4}, std::vector<AovRequest>{{AovType::Albedo, ChannelType::Half}});
  return films;
}

// The film's state as Film::write_state writes it.
inline std::string state_of(const Film& film) {
  std::ostringstream out;
  film.write_state(out);
  return out.str();
}

}  // namespace pt::fuzz
