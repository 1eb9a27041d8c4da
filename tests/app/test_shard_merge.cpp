// The merge of shards without a process (docs/distributed.md): exact sums,
// Film::add_film, shares and tiles, shard files, and ShardMerger's checks.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <functional>
#include <limits>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <string_view>
#include <tuple>
#include <vector>

#include "app/shard.h"
#include "app/shard_file.h"
#include "app/shard_merge.h"
#include "render/film/exact_sum.h"
#include "render/film/film.h"
#include "shard_test_films.h"

namespace pt {
namespace {

using namespace shard_test;

// ---------------------------------------------------------------- exact sums

TEST(ExactSum, AnyGroupingGivesTheSameBits) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<double> terms;
  for (int i = 0; i < 1000; ++i) {  // products of floats over 20 orders of magnitude
    const float w = u(rng), c = u(rng) * std::pow(10.0f, static_cast<float>(i % 20) - 10.0f);
    terms.push_back(static_cast<double>(w) * c);
  }
  ExactSum forward, backward, grouped;
  for (double t : terms) forward.add(t);
  for (auto it = terms.rbegin(); it != terms.rend(); ++it) backward.add(*it);
  for (std::size_t start = 0; start < terms.size(); start += 37) {  // partial sums of ranges, added up
    ExactSum part;
    for (std::size_t i = start; i < std::min(terms.size(), start + 37); ++i) part.add(terms[i]);
    grouped.add(part);
  }
  EXPECT_EQ(forward, backward);
  EXPECT_EQ(forward, grouped);
  // The exact sum is within half a unit per term of the true sum; a long double
  // sum is within its own rounding (64-bit mantissa) of it.
  long double sum = 0, magnitude = 0;
  for (double t : terms) {
    sum += t;
    magnitude += std::fabs(t);
  }
  const double tolerance = static_cast<double>(terms.size()) * 0.5 * ExactSum::kUnit + 1e-18 * magnitude;
  EXPECT_NEAR(forward.value(), static_cast<double>(sum), tolerance);
}

TEST(ExactSum, RoundsToUnitsAndClampsHugeTerms) {
  EXPECT_EQ(ExactSum(1.0).value(), 1.0);
  EXPECT_EQ(ExactSum(-2.5).value(), -2.5);
  EXPECT_EQ(ExactSum(0x1p-46).value(), 0.0);              // a quarter unit rounds to 0
  EXPECT_EQ(ExactSum(3 * 0x1p-45).value(), 2 * 0x1p-44);  // one and a half units: to even
  EXPECT_EQ(ExactSum(1e30).value(), ExactSum::kMaxTerm);
  EXPECT_EQ(ExactSum(-1e30).value(), -ExactSum::kMaxTerm);
  EXPECT_EQ(ExactSum(1e6 + 0.25).value(), 1e6 + 0.25);  // the slow path keeps the fraction
  ExactSum s(1e15);
  s.add(-1e15);
  s.add(0.5);
  EXPECT_EQ(s.value(), 0.5);  // no cancellation error
  EXPECT_TRUE(ExactSum().is_zero());
}

// ---------------------------------------------------------------- films

std::string state_of_film(const Film& film) { return state(film); }

constexpr int kW = 6, kH = 5, kSpp = 30;

TEST(FilmMerge, SampleRangesAddUpToTheWholeExactly) {
  Film whole(kW, kH, {0, 0, kW, kH}, all_aovs());
  render(whole, whole.crop(), {0, kSpp});
  // Shares added with the earlier range first, and with it last.
  for (bool earlier_first : {true, false}) {
    Film merged(kW, kH, {0, 0, kW, kH}, all_aovs());
    Film a(kW, kH, {0, 0, kW, kH}, all_aovs()), b(kW, kH, {0, 0, kW, kH}, all_aovs());
    render(a, a.crop(), {0, 11});
    render(b, b.crop(), {11, kSpp});
    std::string error;
    const Film& first = earlier_first ? a : b;
    const Film& second = earlier_first ? b : a;
    ASSERT_TRUE(merged.add_film(first, merged.crop(), true, error)) << error;
    ASSERT_TRUE(merged.add_film(second, merged.crop(), !earlier_first, error)) << error;
    merged.add_non_finite(a.non_finite());
    merged.add_non_finite(b.non_finite());
    EXPECT_EQ(state(merged), state(whole)) << "earlier range first: " << earlier_first;
  }
}

TEST(FilmMerge, TilesLandInTheirPixelsAndBadRegionsAreRefused) {
  Film whole(kW, kH, {0, 0, kW, kH}, all_aovs());
  render(whole, whole.crop(), {0, kSpp});
  Film merged(kW, kH, {0, 0, kW, kH}, all_aovs());
  std::string error;
  for (const PixelRect& tile : {PixelRect{0, 0, kW, 2}, PixelRect{0, 2, kW, kH}}) {
    Film part(kW, kH, tile, all_aovs());
    render(part, tile, {0, kSpp});
    ASSERT_TRUE(merged.add_film(part, tile, true, error)) << error;
    merged.add_non_finite(part.non_finite());
  }
  EXPECT_EQ(state(merged), state(whole));
  Film part(kW, kH, {0, 0, kW, 2}, all_aovs());
  EXPECT_FALSE(merged.add_film(part, {0, 0, kW, 3}, true, error));  // the region is not all in `part`
  EXPECT_NE(error.find("not inside"), std::string::npos) << error;
  Film fewer(kW, kH, {0, 0, kW, kH});
  EXPECT_FALSE(merged.add_film(fewer, fewer.crop(), true, error));
  EXPECT_EQ(error, "its AOVs differ");
  EXPECT_EQ(state(merged), state(whole));  // unchanged by the refusals
}

// A film state in memory (a mapped shard file) is added in parallel blocks
// of pixels, from bytes at any alignment: the same bits as the stream's adds,
// and a state that breaks the rules is refused naming its first bad pixel.
TEST(FilmMerge, StatesInMemoryAddInParallelToTheSameBits) {
  constexpr int w = 128, h = 80;  // 10240 pixels: three blocks of the parallel add
  Film whole(w, h, {0, 0, w, h}, all_aovs()), a(w, h, {0, 0, w, h}, all_aovs()), b(w, h, {0, 0, w, h}, all_aovs());
  render(whole, whole.crop(), {0, 5});
  render(a, a.crop(), {0, 2});
  render(b, b.crop(), {2, 5});
  const auto n = static_cast<std::size_t>(w * h);
  const auto rules = [&](bool first, uint64_t samples) {
    return StateRules{whole.crop(), std::vector<uint8_t>(n, first ? 1 : 0), std::vector<uint64_t>(n, samples)};
  };
  const std::string state_b = " " + state(b);  // one byte ahead: the state's sums are misaligned
  const std::string_view view_b = std::string_view(state_b).substr(1);
  for (bool earlier_first : {true, false}) {
    Film merged(w, h, {0, 0, w, h}, all_aovs()), streamed(w, h, {0, 0, w, h}, all_aovs());
    std::string error;
    const std::string state_a = state(a);
    for (int i = 0; i < 2; ++i) {
      const bool is_a = (i == 0) == earlier_first;
      const std::string_view bytes = is_a ? std::string_view(state_a) : view_b;
      ASSERT_TRUE(merged.add_state(bytes, rules(is_a || !earlier_first, is_a ? 2 : 3), error)) << error;
      std::stringstream in{std::string(bytes)};
      ASSERT_TRUE(streamed.add_state(in, rules(is_a || !earlier_first, is_a ? 2 : 3), error)) << error;
    }
    EXPECT_EQ(state(merged), state(whole)) << "earlier range first: " << earlier_first;
    EXPECT_EQ(state(streamed), state(whole)) << "earlier range first: " << earlier_first;
  }
  // Refusals. The body's size is checked before anything is added.
  Film merged(w, h, {0, 0, w, h}, all_aovs());
  std::string error;
  ASSERT_TRUE(merged.add_state(state(a), rules(true, 2), error)) << error;
  const std::string before = state(merged);
  EXPECT_FALSE(merged.add_state(view_b.substr(0, view_b.size() - 1), rules(false, 3), error));
  EXPECT_EQ(error, "truncated film state");
  EXPECT_FALSE(merged.add_state(std::string(view_b) + "x", rules(false, 3), error));
  EXPECT_EQ(error, "film state has trailing data");
  EXPECT_FALSE(merged.add_state(view_b.substr(0, 40), rules(false, 3), error));
  EXPECT_EQ(error, "truncated film state header");
  EXPECT_EQ(state(merged), before);
  // Too many samples in pixels 9000 and 5000 (the third and second blocks): the first is named.
  EXPECT_EQ(whole.state_record_bytes(), 472u);  // every AOV of the catalogue (Cryptomatte at 6 levels): docs/distributed.md
  StateParts parts = expand(b, view_b);
  EXPECT_FALSE(parts.exceptions.empty()) << "the fireflies make exceptions";
  for (std::size_t pixel : {9000u, 5000u}) {
    const uint32_t many = 1000;
    std::memcpy(&parts.full[pixel][parts.offset[5]], &many, sizeof many);
  }
  std::string bad = " " + pack(parts);  // misaligned, as view_b
  ASSERT_EQ(bad.size(), view_b.size() + 1 + 4 * n) << "every record holds its count now";
  bad.erase(0, 1);
  EXPECT_FALSE(merged.add_state(bad, rules(false, 3), error));
  EXPECT_EQ(error, "its film state holds 1000 samples in pixel (8, 39), more than its pieces' 3 "
                   "(the two do not belong together)");
  // A Cryptomatte slot's id that is no id (a float's bits with exponent 0),
  // in the last pixel. CryptoObject's slots follow the plain sums.
  std::size_t crypto = 6;  // CryptoObject's first slot
  for (const AovRequest& r : a.aovs()) {
    if (r.type == AovType::CryptoObject) break;
    crypto += static_cast<std::size_t>(aov_state_sums(r));
  }
  bad = std::string(view_b);
  const std::size_t id_at = b.state_slot_at(bad, n - 1, static_cast<uint32_t>(crypto));
  ASSERT_NE(id_at, std::string::npos);
  const uint32_t not_an_id = 1;
  std::memcpy(&bad[id_at], &not_an_id, sizeof not_an_id);
  EXPECT_FALSE(merged.add_state(bad, rules(false, 3), error));
  EXPECT_EQ(error, "corrupt film state (Cryptomatte slots of pixel (127, 79))");
  std::stringstream in(bad);
  EXPECT_FALSE(Film(w, h, {0, 0, w, h}, all_aovs()).add_state(in, rules(false, 3), error));
  EXPECT_EQ(error, "corrupt film state (Cryptomatte slots of pixel (127, 79))");  // the stream says the same
}

// The band merge sets a band from the first state that covers it instead of
// adding that state to a cleared band (Film::set_state_rect): the same bits,
// also for values that 0 + x would change (a maximum of -0.0, NaN or below
// 0; first-sample values whose flag is -0.0, NaN or 0), over a band film
// that held other rows, and after a refusal.
TEST(FilmMerge, SettingRowsGivesTheBitsOfAddingThemToAClearedFilm) {
  constexpr int w = 6, h = 5, y0 = 1, y1 = 4;
  Film a(w, h, {0, 0, w, h}, all_aovs()), other(w, h, {0, 0, w, h}, all_aovs());
  render(a, a.crop(), {0, 3});
  render(other, other.crop(), {3, 7});
  StateParts parts = expand(a, state(a));
  std::size_t values = 0, max_at = 0;  // a pixel's plain values; NonFinite's among them
  std::vector<std::pair<std::size_t, int>> first;  // first-sample layers: their first value, channels
  for (const AovRequest& r : a.aovs()) {
    const AovInfo& info = aov_info(r.type);
    if (info.accumulation == Accumulation::Max) max_at = values;
    if (info.accumulation == Accumulation::FirstSample) first.emplace_back(values, info.channels);
    values += static_cast<std::size_t>(info.values);
  }
  ASSERT_EQ(first.size(), 4u);
  const std::size_t first_value = parts.width.size() - values;
  const auto put = [&](std::size_t pixel, std::size_t k, float v) {
    std::memcpy(&parts.full[pixel][parts.offset[first_value + k]], &v, 4);
  };
  const float odd[] = {-0.0f, std::nanf(""), -1.5f, std::numeric_limits<float>::infinity(), 0.25f, 0.0f};
  for (std::size_t p = 0; p < static_cast<std::size_t>(w * h); ++p) {
    const float v = odd[p % 6];
    put(p, max_at, v);
    for (const auto& [at, channels] : first) {  // a flag of v, and values that are not 0
      for (int c = 0; c < channels; ++c) put(p, at + static_cast<std::size_t>(c), c == 0 ? -0.0f : 2.0f);
      put(p, at + static_cast<std::size_t>(channels), v);
    }
  }
  const std::string bytes = pack(parts);
  for (uint64_t most : {uint64_t{3}, uint64_t{2}}) {  // 2: pixel 7 refused (it holds 3 samples)
    for (uint8_t other_first : {0, 1}) {
      const std::size_t n = static_cast<std::size_t>(w * (y1 - y0));
      StateRules rules{a.crop(), std::vector<uint8_t>(n, other_first), std::vector<uint64_t>(n, 3), y0 * w};
      if (most == 2) rules.max_samples[7 - w] = 2;
      StateView view;
      std::string error;
      ASSERT_TRUE(a.view_state(bytes, a.crop(), a.crop(), view, error)) << error;
      Film added(w, h, {0, 0, w, h}, all_aovs()), set(w, h, {0, 0, w, h}, all_aovs());
      ASSERT_TRUE(set.add_film(other, other.crop(), true, error)) << error;  // storage that holds other pixels
      added.recrop({0, y0, w, y1});
      const std::size_t refused = added.add_state_rect(view, rules, {view.crop.x0, y0, view.crop.x1, y1});
      EXPECT_EQ(set.set_state_rect(view, rules, {view.crop.x0, y0, view.crop.x1, y1}), refused);
      EXPECT_EQ(refused, most == 2 ? std::size_t{7} : SIZE_MAX);
      EXPECT_EQ(set.crop(), added.crop());
      const std::string want = state(added);
      EXPECT_EQ(state(set), want) << "most samples " << most << ", other first " << int(other_first);
      // Not vacuous: the maximum of -0.0 at pixel 6 (y0 * w) was made +0.0,
      // its first-sample values (flag -0.0) zeros.
      EXPECT_EQ(read_at<uint32_t>(expand(a, want).full[6], parts.offset[first_value + max_at]), 0u);
      EXPECT_EQ(read_at<uint32_t>(parts.full[6], parts.offset[first_value + max_at]), 0x80000000u);
    }
  }
}

// The add of a state keeps a scratch of the state's defaults and adds only
// the slots a record holds (Film::add_records); its Cryptomatte check reads
// the held slots where a layer's defaults are 0, the slots themselves where
// not. Both kinds of state add to add_film's bits: one whose rank-0 ids every
// pixel shares (a default not 0), and one whose ids vary; a shared id made
// out of order (above rank 1's) is refused in the add as in the read.
TEST(FilmMerge, AddingAStateWithSharedCryptomatteIdsGivesAddFilmsBits) {
  constexpr int w = 40, h = 3;
  Film a(w, h, {0, 0, w, h}, all_aovs()), b(w, h, {0, 0, w, h}, all_aovs());
  render(a, a.crop(), {0, 2});
  render(b, b.crop(), {2, 4});
  AovScratch scratch = b.make_scratch();
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {  // an id below every other (0.25 < 0.5, 1): rank 0 of every pixel
      scratch.clear();
      AovSample s;
      s.hit = true;
      s.crypto_object = s.crypto_material = 0.25f;
      b.accumulate(scratch, s, RGB(), 0.5f, false);
      b.add_aovs(x, y, scratch);
    }
  std::size_t id0 = 6;  // CryptoObject's rank-0 id slot
  for (const AovRequest& r : b.aovs()) {
    if (r.type == AovType::CryptoObject) break;
    id0 += static_cast<std::size_t>(aov_state_sums(r));
  }
  const std::string state_b = state(b);
  const StateParts parts = expand(b, state_b);
  const std::size_t defaults = 89 + 3 * b.aovs().size();  // where the state's defaults begin
  ASSERT_EQ(read_at<float>(state_b, defaults + parts.offset[id0]), 0.25f) << "the shared id is the state's default";
  const auto n = static_cast<std::size_t>(w * h);
  const StateRules rules{a.crop(), std::vector<uint8_t>(n, 0), std::vector<uint64_t>(n, 4)};
  Film by_film(w, h, {0, 0, w, h}, all_aovs()), by_state(w, h, {0, 0, w, h}, all_aovs());
  std::string error;
  for (const Film* f : {&a, &b}) {
    ASSERT_TRUE(by_film.add_film(*f, f->crop(), false, error)) << error;
    by_film.add_non_finite(f->non_finite());  // add_state merges the report, add_film does not
    ASSERT_TRUE(by_state.add_state(std::string_view(state(*f)), rules, error)) << error;
  }
  EXPECT_EQ(state(by_state), state(by_film));
  // The shared id made larger than pixel 5's rank-1 id: refused there.
  StateParts bad = parts;
  const float big = 100.0f;
  for (std::string& record : bad.full) std::memcpy(&record[bad.offset[id0]], &big, sizeof big);
  Film refused(w, h, {0, 0, w, h}, all_aovs());
  EXPECT_FALSE(refused.add_state(std::string_view(pack(bad)), rules, error));
  EXPECT_NE(error.find("Cryptomatte slots of pixel (0, 0)"), std::string::npos) << error;
}

// The streamed merge takes a band in blocks of columns (Film::set_state_rect,
// add_state_rect): every block of a band, set from one state and added to
// from another, holds the bits the whole band holds there, and setting a
// block gives the bits of adding it to a cleared block.
TEST(FilmMerge, BlocksOfABandGiveTheBandsBits) {
  constexpr int w = 7, h = 5, y0 = 1, y1 = 4;
  Film a(w, h, {0, 0, w, h}, all_aovs()), b(w, h, {0, 0, w, h}, all_aovs());
  render(a, a.crop(), {0, 3});
  render(b, b.crop(), {3, 7});
  const std::string sa = state(a), sb = state(b);
  StateView va, vb;
  std::string error;
  ASSERT_TRUE(a.view_state(sa, a.crop(), a.crop(), va, error)) << error;
  ASSERT_TRUE(b.view_state(sb, b.crop(), b.crop(), vb, error)) << error;
  const std::size_t n = static_cast<std::size_t>(w * (y1 - y0));
  const StateRules ra{a.crop(), std::vector<uint8_t>(n, 0), std::vector<uint64_t>(n, 3), y0 * w};
  const StateRules rb{b.crop(), std::vector<uint8_t>(n, 0), std::vector<uint64_t>(n, 4), y0 * w};
  Film whole(w, h, {0, y0, w, y1}, all_aovs());
  ASSERT_EQ(whole.set_state_rect(va, ra, {va.crop.x0, y0, va.crop.x1, y1}), SIZE_MAX);
  ASSERT_EQ(whole.add_state_rect(vb, rb, {vb.crop.x0, y0, vb.crop.x1, y1}), SIZE_MAX);
  int blocks = 0;
  for (int x0 = 0; x0 < w; x0 += 3) {
    const PixelRect block{x0, y0, std::min(w, x0 + 3), y1};
    Film set(w, h, {0, 0, w, h}, all_aovs()), added(w, h, {0, 0, w, h}, all_aovs());
    ASSERT_EQ(set.set_state_rect(va, ra, block), SIZE_MAX);
    EXPECT_EQ(set.crop(), block);
    added.recrop(block);
    ASSERT_EQ(added.add_state_rect(va, ra, block), SIZE_MAX);
    EXPECT_EQ(state(set), state(added)) << "block at " << x0;
    ASSERT_EQ(set.add_state_rect(vb, rb, block), SIZE_MAX);
    for (int y = block.y0; y < block.y1; ++y)
      for (int x = block.x0; x < block.x1; ++x) {
        const PixelSum &p = set.sum(x, y), &q = whole.sum(x, y);
        EXPECT_TRUE(p.r == q.r && p.g == q.g && p.b == q.b && p.weight == q.weight && p.coverage == q.coverage &&
                    p.samples == q.samples) << x << ", " << y;
        EXPECT_EQ(p.samples, 7u);
        for (const AovRequest& r : all_aovs()) {
          const std::vector<float> u = set.aov_value(r.type, x, y), v = whole.aov_value(r.type, x, y);
          ASSERT_EQ(u.size(), v.size());
          EXPECT_EQ(std::memcmp(u.data(), v.data(), u.size() * sizeof(float)), 0)
              << aov_info(r.type).name << " at " << x << ", " << y;
        }
      }
    ++blocks;
  }
  EXPECT_EQ(blocks, 3);
}

// ---------------------------------------------------------------- shares and tiles

TEST(Shards, SharesAndTilesCoverEverythingOnce) {
  for (int n : {1, 2, 3, 5, 7}) {
    int next = 0, row = 2;
    for (int k = 0; k < n; ++k) {
      const Range r = share_of({k, n}, 64);
      EXPECT_EQ(r.begin, next);
      EXPECT_LE(r.size() - 64 / n, 1);
      next = r.end;
      const PixelRect t = tile_of({1, 2, 9, 40}, {k, n});
      EXPECT_EQ(t.y0, row);
      EXPECT_EQ(t.x0, 1);
      EXPECT_EQ(t.x1, 9);
      row = t.y1;
    }
    EXPECT_EQ(next, 64);
    EXPECT_EQ(row, 40);
  }
  EXPECT_TRUE(tile_of({0, 0, 8, 3}, {0, 4}).empty());  // fewer rows than tiles
  std::string error;
  EXPECT_FALSE(parse_fraction("4/4", error));
  EXPECT_NE(error.find("K must be in 0..3"), std::string::npos) << error;
  EXPECT_FALSE(parse_fraction("1/0", error));
  EXPECT_FALSE(parse_fraction("1/2x", error));
  EXPECT_FALSE(parse_fraction(" 1/2", error));
  ASSERT_TRUE(parse_fraction("2/3", error));
  EXPECT_EQ(parse_fraction("2/3", error)->k, 2);
}

// ---------------------------------------------------------------- shard files and the merger

ShardInfo info_of(const Film& film, Range share, Range done, std::optional<Fraction> tile = std::nullopt) {
  ShardInfo info;
  info.scene = "scene.json";
  info.scene_hash = "0123456789abcdef";
  info.assets_hash = "fedcba9876543210";
  info.version = "0.1.0";
  info.build = "00000000000000aa";
  info.settings = {{"integrator", "path"}, {"seed", 1}};
  info.width = film.width();
  info.height = film.height();
  info.target_spp = kSpp;
  info.window = {0, 0, kW, kH};
  info.crop = film.crop();
  info.aovs = aov_list_text(film.aovs(), ChannelType::Half);
  info.pieces.push_back({film.crop(), tile, share, done});
  info.metadata.set("pathtracer:seed", "1");
  info.metadata.set("pathtracer:spp", 0);
  info.metadata.set("worldToCamera", ImageMetadata::Matrix{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1});
  info.render_seconds = 1.5;
  return info;
}

struct Shard {
  ShardInfo info;
  Film film;
};

Shard shard(Range share, std::optional<Fraction> tile = std::nullopt, int done_end = -1) {
  const PixelRect crop = tile ? tile_of({0, 0, kW, kH}, *tile) : PixelRect{0, 0, kW, kH};
  const Range done{share.begin, done_end < 0 ? share.end : done_end};
  Film film(kW, kH, crop, all_aovs());
  render(film, crop, done);
  return {info_of(film, share, done, tile), std::move(film)};
}

TEST(ShardFile, RoundTripKeepsEveryFieldAndBit) {
  const Shard s = shard({0, 10}, Fraction{1, 2});
  std::stringstream buffer;
  ASSERT_TRUE(write_shard(buffer, s.info, s.film));
  ShardInfo back;
  std::string error;
  ASSERT_TRUE(read_shard_info(buffer, "s", back, error)) << error;
  EXPECT_EQ(shard_mismatch(s.info, back), "");
  EXPECT_EQ(back.crop, s.film.crop());
  ASSERT_EQ(back.pieces.size(), 1u);
  EXPECT_EQ(back.pieces[0].tile->k, 1);
  EXPECT_EQ(back.pieces[0].done, (Range{0, 10}));
  EXPECT_EQ(back.metadata.matrices, s.info.metadata.matrices);
  const std::optional<Film> film = read_shard_film(buffer, "s", back, error);
  ASSERT_TRUE(film) << error;
  EXPECT_EQ(state(*film), state(s.film));
}

TEST(ShardFile, DamagedHeadersAndStatesAreRefused) {
  const Shard s = shard({0, 10});
  std::stringstream buffer;
  ASSERT_TRUE(write_shard(buffer, s.info, s.film));
  const std::string bytes = buffer.str();
  const std::size_t body = bytes.find('\n', bytes.find('\n') + 1) + 1;
  const auto refused = [&](const std::string& file, const std::string& expected) {
    std::istringstream in(file);
    ShardInfo info;
    std::string error;
    bool ok = read_shard_info(in, "bad.ptshard", info, error);
    if (ok) ok = read_shard_film(in, "bad.ptshard", info, error).has_value();
    EXPECT_FALSE(ok) << expected;
    EXPECT_NE(error.find(expected), std::string::npos) << error;
  };
  auto header = nlohmann::ordered_json::parse(bytes.substr(bytes.find('\n') + 1, body - bytes.find('\n') - 2));
  const auto with = [&](const std::function<void(nlohmann::ordered_json&)>& edit) {
    nlohmann::ordered_json h = header;
    edit(h);
    return "pathtracer-shard 2\n" + h.dump() + "\n" + bytes.substr(body);
  };
  refused("pathtracer-checkpoint 1\n{}\n", "'bad.ptshard' is not a pathtracer shard file");
  refused(with([](auto& h) { h.erase("pieces"); }), "damaged shard header: no \"pieces\"");
  refused(with([](auto& h) { h["x"] = 1; }), "unknown key \"x\"");
  refused(with([](auto& h) { h["pieces"][0]["share"] = {5, 2}; }), "a piece's share must be in [5, 30], got 2");
  refused(with([](auto& h) { h["pieces"][0]["done"] = {1, 2}; }), "done range is not a prefix of its share");
  refused(with([](auto& h) { h["pieces"][0]["crop"] = {0, 0, 99, 1}; }), "a piece's crop must be in [0, 6]");
  refused(with([](auto& h) { h["aovs"] = "glitter"; }), "\"aovs\"");
  refused(with([](auto& h) { h["pieces"][0]["done"] = {0, 3}; }), "more than its pieces' 3");
  refused(bytes.substr(0, bytes.size() - 5), "truncated film state");
}

// How a merge takes its shards: their films, their film states as read from
// a stream, or their film states in memory (as `pathtracer merge` maps them).
enum class Via { Films, Streams, Memory };

// Merges `shards` in the order given; the merged film's state, or "" with `error`.
std::string merge(const std::vector<const Shard*>& shards, std::string& error, bool allow_partial = false,
                  ShardMerger* out = nullptr, Via via = Via::Films) {
  ShardMerger local(allow_partial);
  ShardMerger& merger = out ? *out : local;
  std::vector<std::string> names;
  for (std::size_t i = 0; i < shards.size(); ++i) names.push_back(std::string("s").append(std::to_string(i)));
  for (std::size_t i = 0; i < shards.size(); ++i)
    if (!merger.check(names[i], shards[i]->info, error)) return {};
  for (std::size_t i = 0; i < shards.size(); ++i) {
    const std::string bytes = state_of_film(shards[i]->film);
    std::stringstream state(bytes);
    if (!(via == Via::Streams  ? merger.add(names[i], shards[i]->info, state, error)
          : via == Via::Memory ? merger.add(names[i], shards[i]->info, std::string_view(bytes), error)
                               : merger.add(names[i], shards[i]->info, shards[i]->film, error)))
      return {};
  }
  return merger.finish(error) ? state(merger.film()) : std::string();
}

TEST(ShardMerger, AnyOrderOfAnySplitGivesTheWholeRender) {
  Film whole(kW, kH, {0, 0, kW, kH}, all_aovs());
  render(whole, whole.crop(), {0, kSpp});
  for (int n : {1, 2, 3, 5}) {
    std::vector<Shard> shards;
    for (int k = 0; k < n; ++k) shards.push_back(shard(share_of({k, n}, kSpp)));
    std::vector<const Shard*> order;
    for (const Shard& s : shards) order.push_back(&s);
    std::mt19937 rng(static_cast<unsigned>(n));
    for (int trial = 0; trial < 3; ++trial) {
      std::shuffle(order.begin(), order.end(), rng);
      std::string error;
      EXPECT_EQ(merge(order, error), state(whole)) << n << " shards: " << error;
      EXPECT_EQ(merge(order, error, false, nullptr, Via::Streams), state(whole)) << n << " shards, streamed: " << error;
      EXPECT_EQ(merge(order, error, false, nullptr, Via::Memory), state(whole)) << n << " shards, in memory: " << error;
    }
  }
  // Tiles of sample shares.
  std::vector<Shard> parts;
  for (int t = 0; t < 2; ++t)
    for (int k = 0; k < 3; ++k) parts.push_back(shard(share_of({k, 3}, kSpp), Fraction{t, 2}));
  std::vector<const Shard*> order;
  for (const Shard& s : parts) order.push_back(&s);
  std::reverse(order.begin(), order.end());
  std::string error;
  EXPECT_EQ(merge(order, error), state(whole)) << error;
  EXPECT_EQ(merge(order, error, false, nullptr, Via::Streams), state(whole)) << error;
  EXPECT_EQ(merge(order, error, false, nullptr, Via::Memory), state(whole)) << error;
}

TEST(ShardMerger, StreamedStatesAreCheckedAsTheyAreRead) {
  Shard a = shard({0, 15});
  const Shard b = shard({15, kSpp});
  a.info.pieces[0].done = {0, 14};  // its header claims fewer samples than its film holds
  std::string error;
  for (Via via : {Via::Streams, Via::Memory}) {
    EXPECT_EQ(merge({&a, &b}, error, false, nullptr, via), "");
    EXPECT_EQ(error, "'s0': its film state holds 15 samples in pixel (0, 0), more than its pieces' 14 "
                     "(the two do not belong together)");
  }
  ShardMerger merger(false);
  ASSERT_TRUE(merger.check("b", b.info, error)) << error;
  const std::string whole = state(b.film), cut = whole.substr(0, whole.size() - 100);  // inside its records
  std::stringstream truncated(cut);
  EXPECT_FALSE(merger.add("b", b.info, truncated, error));
  EXPECT_EQ(error, "'b': truncated film state");
  EXPECT_FALSE(merger.add("b", b.info, std::string_view(cut), error));
  EXPECT_EQ(error, "'b': truncated film state");
  // The state of tile 0/5 under the header of tile 1/5 (the same size, another
  // place) is refused, not added in the wrong place.
  const Shard t0 = shard({0, kSpp}, Fraction{0, 5}), t1 = shard({0, kSpp}, Fraction{1, 5});
  ShardMerger tiles(true);
  ASSERT_TRUE(tiles.check("t1", t1.info, error)) << error;
  std::stringstream other_tile(state(t0.film));
  EXPECT_FALSE(tiles.add("t1", t1.info, other_tile, error));
  EXPECT_EQ(error, "'t1': film state covers pixels [0,6)x[0,1), not [0,6)x[1,2) inside [0,6)x[0,5)");
  EXPECT_FALSE(tiles.add("t1", t1.info, std::string_view(state(t0.film)), error));
  EXPECT_EQ(error, "'t1': film state covers pixels [0,6)x[0,1), not [0,6)x[1,2) inside [0,6)x[0,5)");
}

// Merges `shards` band by band (ShardMerger::merge_layers, as `pathtracer
// merge` writes images), their states given as `states` (their films' by default).
bool band_merge(const std::vector<const Shard*>& shards, LayeredImage& out, std::string& error,
                bool allow_partial = false, std::vector<std::string> states = {}) {
  ShardMerger merger(allow_partial);
  for (std::size_t i = 0; i < shards.size(); ++i) {
    std::string name = "s";  // appended, not "s" + ...: that trips GCC 12's -Wrestrict (a false positive)
    name += std::to_string(i);
    if (!merger.check(name, shards[i]->info, error)) return false;
    if (states.size() < shards.size()) states.push_back(state_of_film(shards[i]->film));
  }
  const std::vector<std::string_view> views(states.begin(), states.end());
  return merger.merge_layers(views, out, error) && merger.finish(error);
}

// The same window, layers, channel names, types and value bits.
void expect_same_layers(const LayeredImage& a, const LayeredImage& b, const std::string& what) {
  EXPECT_EQ(std::tie(a.full_width, a.full_height, a.x, a.y, a.width, a.height),
            std::tie(b.full_width, b.full_height, b.x, b.y, b.width, b.height)) << what;
  ASSERT_EQ(a.layers.size(), b.layers.size()) << what;
  for (std::size_t l = 0; l < a.layers.size(); ++l) {
    const ImageLayer &x = a.layers[l], &y = b.layers[l];
    EXPECT_EQ(x.name, y.name) << what;
    EXPECT_EQ(x.channels, y.channels) << what;
    EXPECT_EQ(x.type, y.type) << what;
    ASSERT_EQ(x.values.size(), y.values.size()) << what << ", layer " << x.name;
    EXPECT_EQ(std::memcmp(x.values.data(), y.values.data(), x.values.size() * sizeof(float)), 0)
        << what << ", layer '" << x.name << "' differs";
  }
}

TEST(ShardMerger, BandMergeGivesTheLayersOfTheWholeRender) {
  Film whole(kW, kH, {0, 0, kW, kH}, all_aovs());
  render(whole, whole.crop(), {0, kSpp});
  const LayeredImage expected = whole.layers(ChannelType::Half);
  std::string error;
  for (int n : {1, 2, 3}) {
    std::vector<Shard> shards;
    for (int k = 0; k < n; ++k) shards.push_back(shard(share_of({k, n}, kSpp)));
    std::vector<const Shard*> order;
    for (const Shard& s : shards) order.push_back(&s);
    std::reverse(order.begin(), order.end());
    LayeredImage merged;
    ASSERT_TRUE(band_merge(order, merged, error)) << error;
    expect_same_layers(merged, expected, std::to_string(n) + " shards");
  }
  // Tiles of sample shares, and a partial merge (tile 1/2's last share
  // missing) against the merged film's layers.
  std::vector<Shard> parts;
  for (int t = 0; t < 2; ++t)
    for (int k = 0; k < 3; ++k) parts.push_back(shard(share_of({k, 3}, kSpp), Fraction{t, 2}));
  std::vector<const Shard*> order;
  for (const Shard& s : parts) order.push_back(&s);
  LayeredImage merged;
  ASSERT_TRUE(band_merge(order, merged, error)) << error;
  expect_same_layers(merged, expected, "tiles of shares");
  order.pop_back();
  ShardMerger film_merge(true);
  ASSERT_FALSE(merge(order, error, true, &film_merge).empty()) << error;
  ASSERT_TRUE(band_merge(order, merged, error, true)) << error;
  expect_same_layers(merged, film_merge.film().layers(ChannelType::Half), "a partial merge");
}

TEST(ShardMerger, BandMergeChecksEveryState) {
  Shard a = shard({0, 15});
  const Shard b = shard({15, kSpp});
  a.info.pieces[0].done = {0, 14};  // its header claims fewer samples than its film holds
  std::string error;
  LayeredImage out;
  EXPECT_FALSE(band_merge({&b, &a}, out, error));
  EXPECT_EQ(error, "'s1': its film state holds 15 samples in pixel (0, 0), more than its pieces' 14 "
                   "(the two do not belong together)");
  a.info.pieces[0].done = {0, 15};
  const std::string whole = state(b.film);
  EXPECT_FALSE(band_merge({&a, &b}, out, error, false, {state(a.film), whole.substr(0, whole.size() - 100)}));
  EXPECT_EQ(error, "'s1': truncated film state");
  EXPECT_FALSE(band_merge({&a, &b}, out, error, false, {state(a.film), state(b.film) + "x"}));
  EXPECT_EQ(error, "'s1': film state has trailing data");
  // The state of tile 0/5 under the header of tile 1/5 is refused.
  const Shard t0 = shard({0, kSpp}, Fraction{0, 5}), t1 = shard({0, kSpp}, Fraction{1, 5});
  EXPECT_FALSE(band_merge({&t1}, out, error, true, {state(t0.film)}));
  EXPECT_EQ(error, "'s0': film state covers pixels [0,6)x[0,1), not [0,6)x[1,2) inside [0,6)x[0,5)");
}

TEST(ShardMerger, MergesOfMergesGiveTheSameBits) {
  Film whole(kW, kH, {0, 0, kW, kH}, all_aovs());
  render(whole, whole.crop(), {0, kSpp});
  const Shard a = shard({0, 7}), b = shard({7, 19}), c = shard({19, kSpp});
  ShardMerger ac(true);  // a and c, b missing: a partial merge, merged again with b
  std::string error;
  ASSERT_FALSE(merge({&a, &c}, error, true, &ac).empty()) << error;
  EXPECT_TRUE(ac.info().partial);
  EXPECT_NE(ac.notes().find("no shard holds samples [7,19)"), std::string::npos) << ac.notes();
  Shard merged{ac.info(), ac.film()};
  merged.info.partial = false;  // as if re-read: the merge of it with b is complete
  EXPECT_EQ(merge({&b, &merged}, error), state(whole)) << error;
}

TEST(ShardMerger, RefusesWhatDoesNotBelongTogether) {
  const Shard a = shard({0, 15}), b = shard({15, kSpp});
  std::string error;
  Shard seed = shard({15, kSpp});
  seed.info.settings["seed"] = 2;
  EXPECT_EQ(merge({&a, &seed}, error), "");
  EXPECT_EQ(error, "cannot merge 's1' with 's0': they differ in seed 1 vs 2");
  Shard scene = shard({15, kSpp});
  scene.info.scene_hash = "1111111111111111";
  scene.info.version = "0.2.0";
  EXPECT_EQ(merge({&a, &scene}, error), "");
  EXPECT_NE(error.find("the scene: 'scene.json' (hash 0123456789abcdef) vs 'scene.json' (hash 1111111111111111"),
            std::string::npos)
      << error;
  EXPECT_NE(error.find("version 0.1.0 vs 0.2.0"), std::string::npos) << error;
  EXPECT_EQ(merge({&a, &b, &b}, error), "");
  EXPECT_EQ(error, "'s2' and 's1' are the same shard (samples [15,30) of every pixel)");
  const Shard overlap = shard({10, 20});
  EXPECT_EQ(merge({&a, &overlap}, error), "");
  EXPECT_EQ(error, "'s1' and 's0' overlap: both hold samples [10,15) of every pixel");
  EXPECT_EQ(merge({&b}, error), "");
  EXPECT_EQ(error,
            "the shards are incomplete: no shard holds samples [0,15) of every pixel (of 30 per pixel) "
            "(--allow-partial merges what is there, marked partial)");
  const Shard top = shard({0, kSpp}, Fraction{0, 3});
  EXPECT_EQ(merge({&top}, error), "");
  EXPECT_NE(error.find("no shard holds tile 1/3 (rows [1,3) x columns [0,6)); tile 2/3 (rows [3,5)"),
            std::string::npos)
      << error;
  const Shard other_tiling = shard({0, kSpp}, Fraction{0, 2});
  EXPECT_EQ(merge({&top, &other_tiling}, error), "");
  EXPECT_NE(error.find("overlapping tiles of different tilings"), std::string::npos) << error;
}

TEST(ShardMerger, TimeBudgetSharesWeighTheSamplesTaken) {
  // Shares cut short (done < share) are complete: the pixels average what was taken.
  const Shard a = shard({0, 15}, std::nullopt, 9), b = shard({15, kSpp}, std::nullopt, 20);
  ShardMerger merger(false);
  std::string error;
  ASSERT_FALSE(merge({&b, &a}, error, false, &merger).empty()) << error;
  EXPECT_FALSE(merger.info().partial);
  EXPECT_EQ(merger.spp(), 14);
  EXPECT_EQ(merger.film().sum(2, 3).samples, 14u);
  Film taken(kW, kH, {0, 0, kW, kH}, all_aovs());  // the same samples in one film
  render(taken, taken.crop(), {0, 9});
  render(taken, taken.crop(), {15, 20});
  EXPECT_EQ(state(merger.film()), state(taken));
  const ImageMetadata m = merger.metadata();
  const auto has = [&](const std::string& text) {
    return std::any_of(m.strings.begin(), m.strings.end(), [&](const auto& s) { return s.second == text; });
  };
  EXPECT_TRUE(has("2 shards: [0,15)(done [0,9)) [15,30)(done [15,20))"));
}

}  // namespace
}  // namespace pt
