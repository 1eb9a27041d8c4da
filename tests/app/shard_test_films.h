// Films for the shard and film-state tests (test_shard_merge.cpp,
// test_shard_state.cpp): every AOV, a stand-in renderer, a film's state.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "app/shard.h"
#include "render/film/film.h"

namespace pt::shard_test {

inline std::vector<AovRequest> all_aovs() {
  std::vector<AovRequest> all;
  for (const AovInfo& info : aov_catalogue()) all.push_back({info.type, info.default_type});
  return all;
}

// A stand-in for a renderer: sample s of pixel (x, y) is a function of
// (x, y, s) only, as the render loop's are; a NaN now and then.
inline void render(Film& film, const PixelRect& crop, Range samples) {
  AovScratch scratch = film.make_scratch();
  for (int y = crop.y0; y < crop.y1; ++y)
    for (int x = crop.x0; x < crop.x1; ++x) {
      PixelSum sum;
      scratch.clear();
      NonFiniteReport bad;
      for (int s = samples.begin; s < samples.end; ++s) {
        std::mt19937 rng(static_cast<unsigned>(x * 7919 + y * 104729 + s * 1299709));
        std::uniform_real_distribution<float> u(0.0f, 3.0f);
        RGB c(u(rng), u(rng), u(rng) * 1e-3f);
        if ((x + y + s) % 97 == 0) c.r = std::nanf("");
        // Fireflies: sums beyond the 64 bits of a state's record (exceptions).
        if ((x * 3 + y * 5 + s) % 53 == 7) c.g = 4e6f + c.g;
        const float w = u(rng) - 0.5f;
        AovSample a;
        a.albedo = RGB(u(rng), u(rng), u(rng));
        a.normal = Vec3f(u(rng), u(rng), u(rng));
        a.position = Vec3f(static_cast<float>(s), u(rng), u(rng));
        a.depth = static_cast<float>(s) + 1.0f;
        a.object = static_cast<uint32_t>(s % 5);
        a.emission = RGB(u(rng));
        a.diffuse_direct = RGB(u(rng));
        // Cryptomatte: up to 9 ids in a pixel, more than its 6 ranks, and misses.
        a.hit = (s + x) % 4 != 0;
        a.crypto_object = a.hit ? 1.0f + static_cast<float>((s * 3 + y) % 9) : 0.0f;
        a.crypto_material = a.hit ? 0.5f + static_cast<float>(s % 3) : 0.0f;
        const bool finite = c.is_finite();
        if (!finite) bad.record(x, y, s, c);
        sum.add(finite ? c : RGB(), w, a.hit);
        film.accumulate(scratch, a, c, w, !finite);
      }
      film.add(x, y, sum);
      film.add_aovs(x, y, scratch);
      film.add_non_finite(bad);
    }
}

inline std::string state(const Film& film) {
  std::ostringstream out;
  film.write_state(out);
  return out.str();
}

// A film state (version 6) taken apart as docs/distributed.md lays it out,
// independently of film_state*.cpp: its header (to the non-finite report),
// its exceptions (28 bytes each) and every pixel's full record, a slot of
// a pixel at full[pixel].substr(offset[slot], width[slot]).
struct StateParts {
  std::string header;
  std::vector<std::string> exceptions;
  std::vector<std::string> full;
  std::vector<std::size_t> offset, width;  // per slot
};

// The slots of a state of `film`'s AOVs: the beauty's five sums (8 bytes)
// and count (4), the AOV sums (8; a Cryptomatte rank's id 4 and weight 8),
// the AOV values (4).
inline void state_slots(const Film& film, std::vector<std::size_t>& offset, std::vector<std::size_t>& width) {
  width.assign(5, 8);
  width.push_back(4);
  for (const AovRequest& r : film.aovs()) {
    const AovInfo& info = aov_info(r.type);
    if (info.accumulation == Accumulation::Ranked) {
      for (int k = 0; k < r.ranks; ++k) width.insert(width.end(), {4, 8});
    } else {
      width.insert(width.end(), static_cast<std::size_t>(info.sums), 8);
    }
  }
  for (const AovRequest& r : film.aovs()) width.insert(width.end(), static_cast<std::size_t>(aov_state_values(r)), 4);
  offset.clear();
  std::size_t at = 0;
  for (std::size_t w : width) offset.push_back(at), at += w;
}

template <typename T>
T read_at(std::string_view bytes, std::size_t at) {
  T v;
  std::memcpy(&v, bytes.data() + at, sizeof v);
  return v;
}

inline StateParts expand(const Film& film, std::string_view state) {
  StateParts parts;
  state_slots(film, parts.offset, parts.width);
  const std::size_t slots = parts.width.size(), full = parts.offset.back() + parts.width.back();
  const std::size_t mask = (slots + 7) / 8, header = 89 + 3 * film.aovs().size();
  parts.header = std::string(state.substr(0, header));
  const auto x0 = read_at<int32_t>(state, 20), y0 = read_at<int32_t>(state, 24), x1 = read_at<int32_t>(state, 28),
             y1 = read_at<int32_t>(state, 32);
  const auto pixels = static_cast<std::size_t>(x1 - x0) * static_cast<std::size_t>(y1 - y0);
  const std::string defaults(state.substr(header, full));
  std::size_t at = header + full;
  const auto count = read_at<uint64_t>(state, at);
  at += 8;
  for (uint64_t i = 0; i < count; ++i, at += 28) parts.exceptions.emplace_back(state.substr(at, 28));
  at += 8 * ((pixels + 31) / 32 + 1);  // the record index
  for (std::size_t p = 0; p < pixels; ++p) {
    std::string record = defaults;
    const std::size_t bits = at;
    at += mask;
    for (std::size_t k = 0; k < slots; ++k) {
      if (((static_cast<unsigned char>(state[bits + k / 8]) >> (k % 8)) & 1) == 0) continue;
      record.replace(parts.offset[k], parts.width[k], state.substr(at, parts.width[k]));
      at += parts.width[k];
    }
    parts.full.push_back(record);
  }
  return parts;
}

// The state of `parts` as write_state writes it: the defaults those slots
// every pixel holds alike (or, `with_defaults` false, all 0: a state
// write_state would not write).
inline std::string pack(const StateParts& parts, bool with_defaults = true) {
  const std::size_t slots = parts.width.size(), mask = (slots + 7) / 8;
  std::string defaults(parts.offset.back() + parts.width.back(), '\0');
  for (std::size_t k = 0; with_defaults && !parts.full.empty() && k < slots; ++k) {
    const std::string first = parts.full[0].substr(parts.offset[k], parts.width[k]);
    bool shared = true;
    for (const std::string& f : parts.full) shared = shared && f.compare(parts.offset[k], parts.width[k], first) == 0;
    if (shared) defaults.replace(parts.offset[k], parts.width[k], first);
  }
  std::string records;
  std::vector<uint64_t> index;
  for (std::size_t p = 0; p < parts.full.size(); ++p) {
    if (p % 32 == 0) index.push_back(records.size());
    std::string bits(mask, '\0'), held;
    for (std::size_t k = 0; k < slots; ++k) {
      const std::string v = parts.full[p].substr(parts.offset[k], parts.width[k]);
      if (v == defaults.substr(parts.offset[k], parts.width[k])) continue;
      bits[k / 8] = static_cast<char>(bits[k / 8] | (1 << (k % 8)));
      held += v;
    }
    records += bits + held;
  }
  index.push_back(records.size());
  std::string out = parts.header + defaults;
  const auto count = static_cast<uint64_t>(parts.exceptions.size());
  out.append(reinterpret_cast<const char*>(&count), 8);
  for (const std::string& e : parts.exceptions) out += e;
  out.append(reinterpret_cast<const char*>(index.data()), index.size() * 8);
  return out + records;
}

}  // namespace pt::shard_test
