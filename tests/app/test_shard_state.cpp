// The film state's records (version 6, docs/distributed.md "Shard files"):
// the layout as documented, records that hold only the slots that differ
// from the state's defaults, the exceptions, and damaged states refused.
#include <gtest/gtest.h>

#include <bit>
#include <cstring>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "render/film/film.h"
#include "shard_test_films.h"

namespace pt {
namespace {

using namespace shard_test;

std::optional<Film> read_back(const Film& shape, const std::string& bytes, std::string& error) {
  Film back(shape.width(), shape.height(), shape.crop(), shape.aovs());
  std::istringstream in(bytes);
  if (!back.read_state(in, error)) return std::nullopt;
  return back;
}

// Slot numbers (StateException::slot) of a film with every AOV.
std::size_t slot_count(const Film& film) {
  std::vector<std::size_t> offset, width;
  state_slots(film, offset, width);
  return width.size();
}
uint32_t crypto_slot(const Film& film, AovType type, int rank, bool weight) {
  std::size_t slot = 6;
  for (const AovRequest& r : film.aovs()) {
    if (r.type == type) return static_cast<uint32_t>(slot + 2 * static_cast<std::size_t>(rank) + (weight ? 1 : 0));
    slot += static_cast<std::size_t>(aov_state_sums(r));
  }
  return 0;
}

// Films of every kind write the layout docs/distributed.md describes (taken
// apart and put together again by the tests' own reading of it, byte for
// byte); a record holds only its slots that differ from the defaults.
TEST(FilmState, RecordsAreLaidOutAsDocumented) {
  constexpr int w = 37, h = 5;  // 185 pixels: five groups of the record index, the last short
  Film empty(w, h, {0, 0, w, h}, all_aovs()), full(w, h, {0, 0, w, h}, all_aovs());
  Film beauty(w, h, {3, 1, 30, 4}), cropped(w, h, {3, 1, 30, 4}, all_aovs());
  render(full, full.crop(), {0, 9});
  AovScratch many = full.make_scratch();  // 8 ids in pixel 0: Cryptomatte's 6 ranks full
  for (int id = 1; id <= 8; ++id) {
    AovSample a;
    a.hit = true;
    a.crypto_object = static_cast<float>(id);
    a.crypto_material = static_cast<float>(id) + 0.5f;
    full.accumulate(many, a, RGB(), 1.0f, false);
  }
  full.add_aovs(0, 0, many);
  render(beauty, beauty.crop(), {0, 3});
  render(cropped, cropped.crop(), {2, 4});
  for (const Film* film : {&empty, &full, &beauty, &cropped}) {
    const std::string bytes = state(*film);
    EXPECT_EQ(pack(expand(*film, bytes)), bytes) << "a film of " << film->aovs().size() << " AOVs";
    std::string error;
    const std::optional<Film> back = read_back(*film, bytes, error);
    ASSERT_TRUE(back) << error;
    EXPECT_EQ(state(*back), bytes);
  }
  // An empty film's records are their masks alone: 185 of ceil(slots / 8) bytes.
  const std::string none = state(empty);
  const std::size_t slots = slot_count(empty), header = 89 + 3 * all_aovs().size();
  EXPECT_EQ(none.size(), header + empty.state_record_bytes() + 8 + 8 * (6 + 1) + 185 * ((slots + 7) / 8));
  EXPECT_EQ(empty.state_record_at(none, 184), none.size() - (slots + 7) / 8);
  // Every pixel of `full` holds 9 samples: the count is a default, in no record.
  const std::string all = state(full);
  const StateParts parts = expand(full, all);
  for (std::size_t p = 0; p < parts.full.size(); ++p) EXPECT_EQ(full.state_slot_at(all, p, 5), std::string::npos);
  EXPECT_EQ(read_at<uint32_t>(all, header + 40), 9u);
  // Full Cryptomatte slots: pixel 0 of `full` holds all 6 ranks of both
  // layers (given 8 ids in each): every rank's weight is in its record, and
  // every id too but those every pixel holds alike (defaults).
  EXPECT_EQ(full.state_record_at(all, 0), header + full.state_record_bytes() + 8 + 28 * parts.exceptions.size() + 8 * 7);
  for (AovType t : {AovType::CryptoObject, AovType::CryptoMaterial})
    for (int k = 0; k < 6; ++k) {
      EXPECT_NE(full.state_slot_at(all, 0, crypto_slot(full, t, k, true)), std::string::npos) << aov_info(t).name << " rank " << k;
      const uint32_t id = crypto_slot(full, t, k, false);
      EXPECT_NE(read_at<uint32_t>(parts.full[0], parts.offset[id]), 0u);
      const bool shared = read_at<uint32_t>(parts.full[0], parts.offset[id]) == read_at<uint32_t>(all, header + parts.offset[id]);
      EXPECT_EQ(full.state_slot_at(all, 0, id) == std::string::npos, shared) << aov_info(t).name << " rank " << k;
    }
  EXPECT_LT(none.size() * 4, all.size());
}

// What a record cannot hold (a firefly's sums beyond 64 bits, a count beyond
// 32, a value that is not a float) is listed with its full value, read back
// exactly and written back byte for byte; anything written otherwise, or
// another version, is refused.
TEST(FilmState, CompactRecordsKeepEveryValueAndRefuseOtherEncodings) {
  constexpr int w = 4, h = 3;
  Film film(w, h, {0, 0, w, h}, all_aovs());
  render(film, film.crop(), {0, 5});  // pixel (1, 0) sample 4 is a firefly
  PixelSum many;
  many.samples = (uint64_t{1} << 32) + 5;
  many.r = ExactSum(-3e6);
  film.add(1, 1, many);
  const std::string written = state(film);
  const std::size_t aovs = all_aovs().size(), list = 89 + 3 * aovs + film.state_record_bytes();
  const auto count = read_at<uint64_t>(written, list);
  EXPECT_GE(count, 4u);  // the firefly's g and its variance's; the count and r of (1, 1)
  std::string error;
  std::optional<Film> back = read_back(film, written, error);
  ASSERT_TRUE(back) << error;
  EXPECT_EQ(state(*back), written);
  EXPECT_EQ(back->sum(1, 1).samples, many.samples + 5);
  EXPECT_EQ(back->sum(1, 1).r, film.sum(1, 1).r);
  // A value that is no float (0.1 in double), in the last pixel's last slot
  // (the non-finite maximum): listed last, its record not holding the slot.
  const std::size_t slots = slot_count(film);
  StateParts parts = expand(film, written);
  const auto exception = [](uint64_t pixel, uint32_t slot, uint64_t lo) {
    std::string e(28, '\0');
    std::memcpy(&e[0], &pixel, 8);
    std::memcpy(&e[8], &slot, 4);
    std::memcpy(&e[12], &lo, 8);
    return e;
  };
  parts.full.back().replace(parts.offset[slots - 1], 4, 4, '\0');
  parts.exceptions.push_back(exception(w * h - 1, static_cast<uint32_t>(slots - 1), std::bit_cast<uint64_t>(0.1)));
  const std::string crafted = pack(parts);
  back = read_back(film, crafted, error);
  ASSERT_TRUE(back) << error;
  EXPECT_EQ(state(*back), crafted);
  EXPECT_EQ(back->aov_value(AovType::NonFinite, w - 1, h - 1)[0], static_cast<float>(0.1));
  // Refused: a listed value its record could hold; the record holding the
  // listed slot; the list out of order; version 5.
  const std::size_t entries = list + 8;
  std::string bad = crafted;
  bad.replace(entries + count * 28, 28, exception(w * h - 1, static_cast<uint32_t>(slots - 1), std::bit_cast<uint64_t>(0.5)));
  EXPECT_FALSE(read_back(film, bad, error));
  EXPECT_EQ(error, "corrupt film state (wide value " + std::to_string(count) + " of " + std::to_string(count + 1) + ")");
  StateParts held = parts;
  held.full.back().replace(held.offset[slots - 1], 4, "\0\0\x80\x3f", 4);  // held: 1.0f
  EXPECT_FALSE(read_back(film, pack(held), error));
  EXPECT_EQ(error, "corrupt film state (pixel 11 of the crop)");
  bad = crafted;
  bad.replace(entries + count * 28, 28, exception(0, static_cast<uint32_t>(slots - 1), std::bit_cast<uint64_t>(0.1)));
  EXPECT_FALSE(read_back(film, bad, error));
  EXPECT_EQ(error, "corrupt film state (wide value " + std::to_string(count) + " of " + std::to_string(count + 1) + ")");
  bad = written;
  bad[8] = 5;
  EXPECT_FALSE(read_back(film, bad, error));
  EXPECT_EQ(error, "film state version 5 is not read by this pathtracer, which reads version 6 (written by an older "
                   "one: render it again with this one)");
}

// Records that are not as write_state writes them are refused, by the
// checkpoint reader and by the merge's reader of mapped states alike, and
// a record or index cut short is caught before it is read past.
TEST(FilmState, DamagedRecordsAreRefused) {
  constexpr int w = 40, h = 3;  // 120 pixels: four groups of the record index
  Film film(w, h, {0, 0, w, h}, all_aovs());
  render(film, film.crop(), {0, 4});
  const std::string good = state(film);
  const std::size_t slots = slot_count(film), mask = (slots + 7) / 8, n = w * h;
  const std::size_t index = 89 + 3 * all_aovs().size() + film.state_record_bytes() + 8 +
                            28 * read_at<uint64_t>(good, 89 + 3 * all_aovs().size() + film.state_record_bytes());
  const StateRules rules{film.crop(), std::vector<uint8_t>(n, 1), std::vector<uint64_t>(n, 4)};
  const auto refused = [&](const std::string& bytes, const std::string& checkpoint, const std::string& merge) {
    std::string error;
    EXPECT_FALSE(read_back(film, bytes, error));
    EXPECT_EQ(error, checkpoint);
    Film merged(w, h, film.crop(), all_aovs());
    EXPECT_FALSE(merged.add_state(std::string_view(bytes), rules, error));
    EXPECT_EQ(error, merge);
    std::istringstream in(bytes);
    EXPECT_FALSE(Film(w, h, film.crop(), all_aovs()).add_state(in, rules, error));
    EXPECT_EQ(error, merge);  // the stream's reader says the same
  };
  // A held slot that holds 0 (pixel 70's red sum).
  std::string bad = good;
  const std::size_t red = film.state_slot_at(good, 70, 0);
  ASSERT_NE(red, std::string::npos);
  std::memset(&bad[red], 0, 8);
  refused(bad, "corrupt film state (pixel 70 of the crop)",
          "corrupt film state (pixel (30, 1): a value not stored as this pathtracer stores it)");
  // A mask that holds a slot past the last one, or one every pixel shares (the count).
  const std::size_t record = film.state_record_at(good, 70);
  if (slots % 8 != 0) {
    bad = good;
    bad[record + mask - 1] = static_cast<char>(bad[record + mask - 1] | 0x80);
    refused(bad, "corrupt film state (pixel 70 of the crop)",
            "corrupt film state (pixel (30, 1): a value not stored as this pathtracer stores it)");
  }
  bad = good;
  bad[record] = static_cast<char>(bad[record] | (1 << 5));
  refused(bad, "corrupt film state (pixel 70 of the crop)",
          "corrupt film state (pixel (30, 1): a value not stored as this pathtracer stores it)");
  // The index's second group beginning a byte late: the first group's last
  // record runs past its group's end.
  bad = good;
  const uint64_t second = read_at<uint64_t>(good, index + 8) + 1;
  std::memcpy(&bad[index + 8], &second, 8);
  refused(bad, "corrupt film state (pixel 31 of the crop)",
          "corrupt film state (pixel (31, 0): its records do not end where the record index says)");
  // The index out of order, or cut inside the last record.
  bad = good;
  const uint64_t past = read_at<uint64_t>(good, index + 32) + 1;
  std::memcpy(&bad[index + 24], &past, 8);
  refused(bad, "corrupt film state (record index)", "corrupt film state (record index)");
  refused(good.substr(0, good.size() - 3), "truncated film state", "truncated film state");
  refused(good.substr(0, index + 12), "truncated film state header", "truncated film state header");
  refused(good + "x", "film state has trailing data", "film state has trailing data");
  // Defaults that are not the slots every pixel shares: the checkpoint
  // reader refuses them (it writes states back byte for byte); the merge
  // decodes the same values from them, so it adds the same bits.
  const std::string odd = pack(expand(film, good), false);
  ASSERT_NE(odd, good);
  std::string error;
  EXPECT_FALSE(read_back(film, odd, error));
  EXPECT_EQ(error, "corrupt film state (defaults not those of its pixels)");
  Film a(w, h, film.crop(), all_aovs()), b(w, h, film.crop(), all_aovs());
  ASSERT_TRUE(a.add_state(std::string_view(good), rules, error)) << error;
  ASSERT_TRUE(b.add_state(std::string_view(odd), rules, error)) << error;
  EXPECT_EQ(state(a), state(b));
  EXPECT_EQ(state(a), good);
}

}  // namespace
}  // namespace pt
