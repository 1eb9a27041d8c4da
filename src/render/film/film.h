// Film: the image being rendered, row 0 at the top. Each pixel holds sums, not
// a final value: the filter-weighted sum of its samples' radiance, the sum of
// their weights and of the weights of those that hit a surface (coverage, the
// alpha), all exact (ExactSum), and the number of samples. The pixel value is
// sum / weight_sum. Because sums add, passes over sample ranges rendered one
// after another (or elsewhere) merge into the same image.
//
// A film covers a frame of width x height pixels but stores only its crop
// window (the whole frame by default); pixel coordinates are always the
// frame's. Requested AOV layers (render/film/aov.h) are stored beside the
// beauty, per pixel, as exact sums and plain doubles; a film without AOVs
// stores nothing for them.
//
// Each pixel is written by exactly one task at a time (the render loop gives
// every pixel to one task), so adding needs no synchronisation and the result
// does not depend on the tile order.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <iosfwd>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/color.h"
#include "core/image.h"
#include "io/layered_image.h"
#include "render/film/aov.h"
#include "render/film/exact_sum.h"

namespace pt {

// The running sums of one pixel. The sums are exact (render/film/exact_sum.h):
// they hold the same bits whatever the grouping of the samples into passes,
// shards or merges.
struct PixelSum {
  ExactSum r, g, b;     // sum of weight * radiance
  ExactSum weight;      // sum of filter weights
  ExactSum coverage;    // sum of the weights of the samples whose camera ray hit a surface
  uint64_t samples = 0; // number of samples (non-finite ones included, as black)

  // One sample: its radiance, filter weight and whether its camera ray hit a surface.
  void add(RGB value, float w, bool hit) {
    r.add(static_cast<double>(w) * value.r);  // a product of two floats: exact in double
    g.add(static_cast<double>(w) * value.g);
    b.add(static_cast<double>(w) * value.b);
    weight.add(w);
    if (hit) coverage.add(w);
    ++samples;
  }
  void add(const PixelSum& o) {
    r.add(o.r);
    g.add(o.g);
    b.add(o.b);
    weight.add(o.weight);
    coverage.add(o.coverage);
    samples += o.samples;
  }
  // sum / weight; black for a pixel without weight.
  RGB value() const {
    if (weight.is_zero()) return {};
    const double inv = 1.0 / weight.value();
    return {static_cast<float>(r.value() * inv), static_cast<float>(g.value() * inv),
            static_cast<float>(b.value() * inv)};
  }
  // The beauty's alpha: coverage / weight, the filter-weighted fraction of
  // the samples whose camera ray hit a surface, clamped to [0, 1] (a filter
  // with negative lobes can take the ratio out of it); 0 without weight.
  float alpha() const {
    if (weight.is_zero()) return 0.0f;
    return static_cast<float>(std::clamp(coverage.value() / weight.value(), 0.0, 1.0));
  }
};
// No padding: the film state writes the pixel sums as they are in memory.
static_assert(sizeof(PixelSum) == 5 * sizeof(ExactSum) + sizeof(uint64_t));

// One pixel's AOV samples of one pass, gathered before they are added to the
// film (Film::make_scratch, accumulate, add_aovs): the AOVs' exact sums and
// their plain values (first-sample values with a set flag, maxima).
struct AovScratch {
  std::vector<ExactSum> sums;
  std::vector<double> values;
  void clear() {
    std::fill(sums.begin(), sums.end(), ExactSum{});
    std::fill(values.begin(), values.end(), 0.0);
  }
};

// Pixels [x0, x1) x [y0, y1) of the frame.
struct PixelRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  int width() const { return x1 - x0; }
  int height() const { return y1 - y0; }
  bool empty() const { return x1 <= x0 || y1 <= y0; }
  bool contains(int x, int y) const { return x >= x0 && x < x1 && y >= y0 && y < y1; }
  bool contains(const PixelRect& r) const { return r.x0 >= x0 && r.y0 >= y0 && r.x1 <= x1 && r.y1 <= y1; }
  bool intersects(const PixelRect& r) const { return r.x0 < x1 && x0 < r.x1 && r.y0 < y1 && y0 < r.y1; }
  // "[x0,x1)x[y0,y1)", for messages.
  std::string text() const;
  bool operator==(const PixelRect&) const = default;
};

// Non-finite samples caught before they reach the film (they are added as
// black). Counts are per kind; the first offender is the smallest
// (y, x, sample index), so it does not depend on thread scheduling.
struct NonFiniteReport {
  uint64_t nan = 0, pos_inf = 0, neg_inf = 0;  // a sample with any NaN channel counts as NaN, else +-Inf
  bool has_first = false;
  int x = 0, y = 0, sample = 0;
  RGB value;  // the offending estimate

  uint64_t total() const { return nan + pos_inf + neg_inf; }
  // Counts a non-finite `value` of sample `sample` of pixel (x, y).
  void record(int px, int py, int sample_index, RGB v);
  void merge(const NonFiniteReport& o);
  // "3 non-finite samples (2 NaN, 1 +Inf, 0 -Inf); first at pixel (4, 7) sample 12: (nan, 0, 1)".
  std::string describe() const;
};

// What Film::add_state may take from a film state: the crop it must cover,
// and per pixel of that crop (row-major) whether its first-sample values come
// before the film's, and the most samples it may hold there.
struct StateRules {
  PixelRect crop;  // the state's crop, as its shard's header says
  std::vector<uint8_t> other_first;
  std::vector<uint64_t> max_samples;
  // The vectors hold pixels [first, first + size) of the crop: the whole crop
  // (first 0), or, for Film::add_state_rect, the rows of the block being added.
  std::size_t first = 0;
};

// A slot of a film state that its compact record cannot hold (film_state.cpp):
// a sum beyond 64 bits, a count beyond 32, a value that is not a float. The
// state lists these with their full value, ordered by pixel and slot.
struct StateException {
  uint64_t pixel = 0;  // in the state's crop, row-major
  uint32_t slot = 0;   // 0-4 the beauty's sums, 5 its count, then the AOV sums, then the AOV values
  UInt128 value = 0;   // the sum's integer, the count, or the value's double bits
};

// A film state's record layout (version 6, film_state_codec.cpp): the
// slots every pixel of the state shares (a full record, 0 in the others),
// which slots a record may hold, and where every 32nd record begins.
constexpr std::size_t kStateGroup = 32;  // records per entry of the record index
constexpr std::size_t kStateWords = 2;   // 64-bit words of a record's slot mask (128 slots; 111 at most)
struct StateCodec {
  std::vector<char> defaults;                // a full record (every slot at its type's width)
  std::array<uint64_t, kStateWords> varying{};  // the slots a record may hold: those whose default is 0
  std::vector<uint64_t> index;  // per group of kStateGroup records, its offset among the records; then their size
  // The defaults decoded (a record that holds no slot): what a record's
  // decode starts from.
  PixelSum pixel;
  std::vector<ExactSum> sums;
  std::vector<double> values;
};

// A complete film state in memory (a mapped shard file after its header),
// its header and size checked (Film::view_state): its exceptions, its codec
// and where its pixel records begin, for Film::add_state_rect. The records
// need not be aligned.
struct StateView {
  PixelRect crop;
  NonFiniteReport non_finite;
  std::vector<StateException> exceptions;
  StateCodec codec;
  // The crop's pixels' records, row-major, from the one codec.index puts
  // `records_from` bytes in (0: all of them; a stream's reader holds some).
  const char* records = nullptr;
  uint64_t records_from = 0;
};

class Film {
 public:
  Film(int width, int height);
  // A film of the frame that stores only `crop` (clipped to the frame) and the requested AOVs.
  Film(int width, int height, PixelRect crop, std::vector<AovRequest> aovs = {});
  int width() const { return width_; }    // the frame
  int height() const { return height_; }
  const PixelRect& crop() const { return crop_; }

  // Frame coordinates, inside crop().
  void add(int x, int y, const PixelSum& s) { pixels_[index(x, y)].add(s); }
  const PixelSum& sum(int x, int y) const { return pixels_[index(x, y)]; }
  RGB pixel(int x, int y) const { return pixels_[index(x, y)].value(); }
  // The image of the crop window: every pixel's sum / weight.
  Image image() const;
  void clear();

  // AOVs. A pixel's samples are gathered in a scratch of zeros from
  // make_scratch() (accumulate() per sample, lowest sample index first), then
  // added with add_aovs().
  const std::vector<AovRequest>& aovs() const { return aovs_; }
  bool wants_geometry() const { return wants_geometry_; }  // albedo, N, P, Z or ids
  bool wants_lighting() const { return wants_lighting_; }  // the integrator's lighting split
  // Per-pixel state slots of the AOVs (exact sums and plain values); 0 when
  // no requested AOV keeps a state (none, or "samples" alone).
  int aov_slots() const { return sum_stride_ + value_stride_; }
  AovScratch make_scratch() const;
  void accumulate(AovScratch& scratch, const AovSample& sample, RGB radiance, float weight, bool non_finite) const;
  void add_aovs(int x, int y, const AovScratch& scratch);
  // The final values of AOV `type` at (x, y) (aov_channel_names().size()
  // floats); empty if not requested.
  std::vector<float> aov_value(AovType type, int x, int y) const;

  // Adds the state of `other` (a shard: docs/distributed.md) over `region`,
  // which lies inside both films' crops; the frame and AOVs must match. Sums
  // add exactly, maxima take the larger, and a first-sample AOV takes
  // `other`'s value where this film has none, or wherever `other` has one when
  // `other_first` (its samples there come before this film's). The non-finite
  // report is not added (add_non_finite). Returns false with `error`, this
  // film unchanged, when the frame, the AOVs or the region do not fit.
  bool add_film(const Film& other, const PixelRect& region, bool other_first, std::string& error);

  const NonFiniteReport& non_finite() const { return non_finite_; }
  void add_non_finite(const NonFiniteReport& r) { non_finite_.merge(r); }

  // The beauty (R, G, B, A; RGB premultiplied, A = PixelSum::alpha()), stored
  // as `beauty` (float by default, half with "--aov beauty:half"), and every
  // requested AOV over the crop window, for the image writers (a Ranked AOV
  // becomes one layer per two ranks).
  LayeredImage layers(ChannelType beauty = ChannelType::Float) const;
  // The layers of layers() over `window` (this film's crop, or a window of
  // band films' crops), allocated (zero) but not resolved.
  LayeredImage layer_layout(ChannelType beauty, const PixelRect& window) const;
  // Resolves this film's pixels into `out` (a layer_layout of a film of the
  // same AOVs whose window holds this crop as whole rows): a band of it.
  void resolve_into(LayeredImage& out) const;
  // The channels of a pixel of layer_layout(): the beauty's 4, then each AOV's.
  std::size_t resolved_channels() const;
  // Resolves pixels [first, first + count) of the crop (row-major) into
  // `out`: every channel of layer_layout()'s layers of a pixel, one after
  // another (resolved_channels() floats a pixel), the values of resolve_into.
  void resolve_channels(std::size_t first, std::size_t count, float* out) const;

  // The film's complete state (every pixel's sums and counts, the AOV sums,
  // the non-finite report), for checkpoints: written and read back bit for
  // bit, so that a render resumed from it adds up to exactly the image of an
  // uninterrupted one. Binary, little-endian; the layout is in film.cpp.
  // write_state returns false when the stream fails.
  bool write_state(std::ostream& out) const;
  // Replaces this film's state. Returns false, with `error` set and the film
  // unchanged, when the stream does not hold a state of a film of this size,
  // crop and AOV list.
  bool read_state(std::istream& in, std::string& error);
  // Adds a film state (a film of this frame and AOVs whose crop lies inside
  // this one's: a shard) while it is read, a block at a time, as add_film
  // would add that film, so that a merge holds one film in memory. False with
  // `error` when the state does not fit or breaks `rules` (sized for its crop);
  // this film may then hold part of it (the merge discards it).
  bool add_state(std::istream& in, const StateRules& rules, std::string& error);
  // The same from a complete film state in memory (a mapped shard file, a
  // received message): its size is checked before anything is added, and the
  // pixels are added in parallel (TBB, in the caller's arena), which gives the
  // same bits: each pixel is added once, exactly.
  bool add_state(std::string_view state, const StateRules& rules, std::string& error);
  // The band merge's parts (docs/distributed.md, "The merge"): a film state
  // in memory of a film of this frame and AOVs over `crop`, which lies in
  // `inside` (not necessarily in this film's crop), checked as add_state
  // checks it (layout, crop, size), viewed in place.
  bool view_state(std::string_view state, const PixelRect& crop, const PixelRect& inside, StateView& view,
                  std::string& error) const;
  // Adds a block `rect` of a viewed state (a rectangle of the state's crop,
  // not necessarily whole rows, inside this film's crop); `rules` cover its
  // rows (rules.first is their first pixel). One thread; the pixels are taken
  // row by row. The first pixel (of the state's crop) that breaks the rules,
  // or SIZE_MAX; the pixels before it are added.
  std::size_t add_state_rect(const StateView& view, const StateRules& rules, const PixelRect& rect);
  // Moves this film to `rect` and sets it to that block of a viewed state:
  // bit for bit what recrop() then add_state_rect() leave (values as
  // add_values makes them from zeros: max(0, v), first-sample values kept
  // only when flagged), without clearing first. The same return; after a
  // refusal the pixels from the refused one on are cleared, as add_state_rect
  // leaves them in a cleared film.
  std::size_t set_state_rect(const StateView& view, const StateRules& rules, const PixelRect& rect);
  // The message for a pixel add_state_rect refused.
  std::string refusal(const StateView& view, std::size_t pixel, const StateRules& rules) const;
  // The bytes of one pixel's full record in a film state of this film's
  // AOVs (every slot at its type's width: a state's defaults, and the most a
  // record holds besides its mask of ceil(slots / 8) bytes): 448 with every
  // AOV of the path integrator, 44 for the beauty.
  std::size_t state_record_bytes() const { return record_bytes_; }
  // Where pixel number `pixel`'s record (its mask) begins in the film state
  // `state` (of this film's AOVs), or std::string::npos when the state is
  // damaged. For tests and tools that inspect states.
  std::size_t state_record_at(std::string_view state, std::size_t pixel) const;
  // Where slot `slot` (as StateException::slot) of pixel number `pixel` of
  // the film state `state` (of this film's AOVs) is stored: its offset in
  // `state`, or std::string::npos when the pixel's record does not hold it
  // (its value is the state's default) or the state is damaged.
  std::size_t state_slot_at(std::string_view state, std::size_t pixel, uint32_t slot) const;
  // Moves this film to `crop` and clears it: a band film reused for the
  // next band (no allocation unless the crop is larger than any before).
  void recrop(const PixelRect& crop);

 private:
  // Moves this film to `crop` keeping what its storage holds (recrop's
  // move, without the clear): set_state_rect then sets every pixel.
  void move_to(const PixelRect& crop);
  // Adds another film's (or a scratch's) AOV sums `s` to pixel number `pixel`:
  // exact sums add, Cryptomatte slots merge (add_ranked).
  void add_sums(std::size_t pixel, const ExactSum* s);
  // Whether the Cryptomatte slots among a pixel's AOV sums `s` are as
  // add_ranked leaves them (ids in increasing order, free slots last and
  // empty); a film state read from a file may hold anything.
  bool valid_ranked(const ExactSum* s) const;
  // The same of a decoded record's AOV sums `s`, which held slots `held`
  // (DecodedPixel::held) of a state whose zero defaults are `varying`
  // (StateCodec::varying): where a layer's defaults are all 0, from the
  // slots held alone, without reading its slots but the used ids.
  bool valid_ranked(const ExactSum* s, const std::array<uint64_t, kStateWords>& held,
                    const std::array<uint64_t, kStateWords>& varying) const;
  // add_sums of only the plain sums among state slots `slots` (the others
  // of `s` are 0) and every Cryptomatte layer: a decoded record's.
  void add_sums(std::size_t pixel, const ExactSum* s, const std::array<uint64_t, kStateWords>& slots);
  // Calls `f(k)` for every state slot k in both `a` and `b`, in increasing order.
  template <typename F>
  static void for_each_slot(const std::array<uint64_t, kStateWords>& a, const std::array<uint64_t, kStateWords>& b,
                            F&& f) {
    for (std::size_t w = 0; w < kStateWords; ++w)
      for (uint64_t m = a[w] & b[w]; m != 0; m &= m - 1) f(64 * w + static_cast<std::size_t>(std::countr_zero(m)));
  }
  // Adds another film's plain AOV values `s` (first-sample layers, maxima) to pixel number `pixel`.
  void add_values(std::size_t pixel, const double* s, bool other_first);
  // Where a pixel's record decodes to: its sums, AOV sums and plain values.
  // With `defaults`, the AOV sums and values already hold the state's
  // defaults (a scratch that is cleared back to them: add_records), and
  // decode_record writes only the slots the record and its exceptions hold;
  // it sets `held` to those.
  struct DecodedPixel {
    PixelSum* sum;
    ExactSum* sums;
    double* values;
    bool defaults = false;
    std::array<uint64_t, kStateWords> held{};
  };
  // The film state's records (film_state_codec.cpp; the layout in
  // film_state.cpp). Slots of a pixel: state_slots(), numbered as
  // StateException::slot. A full record holds every slot at its type's
  // width (record_bytes_); a state's record, a mask of the slots that differ
  // from the state's defaults (bitmap_bytes_), then those slots.
  void init_state_layout();
  static constexpr std::size_t kAovSlot = 6;  // a state's first AOV sum slot (after the beauty's 5 sums and count)
  std::size_t state_slots() const { return kAovSlot + static_cast<std::size_t>(sum_stride_ + value_stride_); }
  // Whether `e` is a slot of a state of `pixels` pixels whose value its
  // record could not hold (anything else is not how write_state writes it).
  bool valid_exception(const StateException& e, std::size_t pixels, const StateCodec& codec) const;
  // The full record of this film's pixel number `pixel` into `out`
  // (record_bytes_); the slots it cannot hold are 0 there and appended to
  // `exceptions` (when not null) as pixel `number`.
  void encode_record(std::size_t pixel, uint64_t number, char* out, std::vector<StateException>* exceptions) const;
  // The record of the full record `full` under `codec` into `out` (when not
  // null); its size.
  std::size_t pack_record(const char* full, const StateCodec& codec, char* out) const;
  // This film's state's codec (its defaults and record index) and exceptions.
  StateCodec state_codec(std::vector<StateException>& exceptions) const;
  // The size of the record at `in` under `codec`, which must end by `end`;
  // 0 when its mask is not as pack_record writes it or it passes `end`.
  std::size_t record_size(const char* in, const char* end, const StateCodec& codec) const;
  // The record at `in` (ending by `end`) and its pixel's exceptions [ex,
  // ex_end) into `to` (the defaults first, unless to.defaults), `in` moved
  // past it and to.held set to the slots they hold; false when they are not
  // as pack_record writes them.
  bool decode_record(const char*& in, const char* end, const StateCodec& codec, const StateException* ex,
                     const StateException* ex_end, DecodedPixel& to) const;
  // codec.pixel, sums and values from codec.defaults.
  void decode_defaults(StateCodec& codec) const;
  // The parts of a state's header after the non-finite report: the
  // defaults, the exception list and the record index of a state of
  // `pixels` pixels; false with `error`.
  bool read_codec(std::istream& in, std::size_t pixels, StateCodec& codec, std::vector<StateException>& exceptions,
                  std::string& error) const;
  void write_codec(std::ostream& out, const StateCodec& codec, const std::vector<StateException>& exceptions) const;
  // The record of pixel `pixel` of a viewed state (`at`) and the end of its
  // group (`end`); false when a record before it in its group is damaged.
  bool seek_record(const StateView& view, std::size_t pixel, const char*& at, const char*& end) const;
  // After pixel `pixel`'s record (of `pixels`), `at` past it: false when it
  // ends its group and the records do not end where the index says; `end`
  // moved to the next group's end.
  static bool next_record(const StateView& view, std::size_t pixel, std::size_t pixels, const char* at,
                          const char*& end);
  // The walk over the records of pixels [first, first + count) of a viewed
  // state that read_state, add_records and set_records share: each record
  // (with its exceptions) decoded where `target(i)` says (a DecodedPixel),
  // checked (as written; Cryptomatte slots; where its group ends), then
  // handed to `use(i, decoded)`, which may refuse it (false). The first
  // pixel refused, or SIZE_MAX. Defined in film_state.cpp, its only user.
  template <typename Target, typename Use>
  std::size_t for_each_record(const StateView& view, std::size_t first, std::size_t count, Target&& target,
                              Use&& use) const;
  // add_state's work on pixels [first, first + count) of a viewed state
  // (rules over its crop): the first pixel that breaks the rules (too many
  // samples; corrupt Cryptomatte slots; a record not as written), or
  // SIZE_MAX. The pixels before it are added.
  std::size_t add_records(const StateView& view, std::size_t first, std::size_t count, const StateRules& rules);
  // set_state_rect's work: pixels [first, first + count) of the state
  // decoded straight into this film's pixels to, to + 1, ...; the first
  // refused pixel or SIZE_MAX.
  std::size_t set_records(const StateView& view, std::size_t first, std::size_t count, const StateRules& rules,
                          std::size_t to);
  // A pixel's plain AOV values `v`, decoded from a state, made what
  // add_values makes of them in a cleared pixel.
  void first_values(double* v) const;
  static std::string too_many_samples(std::size_t pixel, uint64_t samples, const StateRules& rules);
  // Resolves pixels [first, first + count) of the crop into `out`'s pixels
  // from `at` on (layers laid out by layer_layout).
  void resolve_pixels(LayeredImage& out, std::size_t first, std::size_t count, std::size_t at) const;
  // Every channel of pixel number `pixel` into `out` (resolved_channels() floats).
  void resolve_pixel(std::size_t pixel, float* out) const;
  // The final values of AOV number `layer` of pixel number `pixel` (in the crop, row-major) into `out`.
  void aov_values(std::size_t layer, std::size_t pixel, float* out) const;
  // aov_values of pixel `p` whose weight is `weight` (p.weight.value(), 0 for
  // none), its AOV sums `s` and values `d` (the layer's own).
  void aov_values(std::size_t layer, const PixelSum& p, double weight, const ExactSum* s, const double* d,
                  float* out) const;
  std::size_t index(int x, int y) const {
    return static_cast<std::size_t>(y - crop_.y0) * static_cast<std::size_t>(crop_.width()) +
           static_cast<std::size_t>(x - crop_.x0);
  }

  // A run of a pixel's AOV sums that add alike: `count` plain exact sums
  // from `offset` (ranks 0), or one Cryptomatte layer's `ranks` slots.
  struct SumRun {
    int offset, count, ranks;
  };
  // Adjacent filtered-average layers (most of a pixel's resolved channels):
  // `count` sums from `sum` (in a pixel's AOV sums), resolved into a pixel's
  // resolved channels from `out` (the beauty's 4 first) by one loop.
  struct AverageRun {
    int sum, out, count;
  };
  int width_, height_;
  PixelRect crop_;
  std::vector<PixelSum> pixels_;
  std::vector<AovRequest> aovs_;
  // Per request: its first sum and first value in a pixel's AOV blocks.
  std::vector<int> sum_offset_, value_offset_;
  std::vector<int> channel_count_;  // per request: aov_channel_count()
  std::vector<const AovInfo*> info_;  // per request: aov_info(), looked up once (the adds and resolves are per pixel)
  int sum_stride_ = 0, value_stride_ = 0;  // per pixel, for all AOVs
  bool wants_geometry_ = false, wants_lighting_ = false;
  std::vector<SumRun> sum_runs_;    // the AOV sums, in order, adjacent plain sums in one run
  std::vector<AverageRun> average_runs_;  // the filtered-average layers, in order, adjacent ones in one run
  std::vector<uint8_t> averaged_;         // per request: whether it is in average_runs_
  int albedo_out_ = -1;                   // the albedo's first resolved channel, or -1 (none)
  std::vector<std::size_t> value_layers_;  // the requests with plain values (first-sample, maxima), in order
  std::vector<ExactSum> aov_sums_;  // pixels * sum_stride_
  std::vector<double> aov_values_;  // pixels * value_stride_
  NonFiniteReport non_finite_;
  std::vector<uint8_t> sum_kinds_;  // per AOV sum: how a state's record holds it (film_state_codec.cpp)
  std::vector<uint32_t> slot_offset_;  // per state slot: where a full record holds it
  std::vector<uint8_t> slot_kind_;     // per state slot: what it is and where it decodes to (film_state_codec.cpp)
  std::array<uint64_t, kStateWords> wide_slots_{};  // the state slots held in 8 bytes (the others in 4)
  std::array<uint64_t, kStateWords> aov_sum_slots_{}, value_slots_{};  // the state slots of the AOV sums, of the values
  std::array<uint64_t, kStateWords> plain_sum_slots_{};  // the AOV sums' slots outside Cryptomatte layers
  std::size_t record_bytes_ = 0;    // a full record of one pixel
  std::size_t bitmap_bytes_ = 0;    // a record's mask of the slots it holds
};

}  // namespace pt
