// ShardMerger::merge_layers and merge_streamed: the band merge of
// `pathtracer merge` (docs/distributed.md, "The merge").
#include <algorithm>
#include <atomic>
#include <future>
#include <cstdint>
#include <memory>

#include <tbb/blocked_range.h>
#include <tbb/concurrent_queue.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_pipeline.h>
#include <tbb/task_arena.h>

#include "app/shard_merge.h"
#include "imagelib/image_library.h"
#include "io/exr_pack.h"
#include "io/exr_uncompressed.h"

namespace pt {
namespace {

// A band film holds about this many bytes of state (it stays in the cache
// while every shard's rows are added into it and it is resolved).
constexpr std::size_t kBandBytes = std::size_t{1} << 20;
// The streamed merge takes a band in blocks of columns of about this many
// bytes of state, so that a block's state, the shards' records and its
// packed pixels stay in the second-level cache while it is set, added to,
// resolved and packed (a band of a 1080p frame with every AOV is one row of
// 2 MiB of state).
constexpr std::size_t kBlockBytes = std::size_t{256} << 10;
// The streamed write hands the file about this many bytes of packed rows at
// a time, in whole blocks of 32 rows (zip's 16, piz's 32), so that
// OpenEXR compresses a chunk's blocks in parallel.
constexpr std::size_t kChunkBytes = std::size_t{8} << 20;
// Chunks the pipeline may make ahead of the file while it is opened.
constexpr int kAheadChunks = 4;

// Pixels resolved at a time before they are packed: their channels stay in
// the first-level cache between the two.
constexpr std::size_t kPackPixels = 32;

// Where the streamed merge packs its pixels: rows `row_bytes` apart, a row's
// pixels packed as `packed` one after another, or, when `lines` has channels
// (an uncompressed file: io/exr_uncompressed.h), in the file's lines.
struct Packing {
  PackedLayout packed;
  LineLayout lines;
  std::size_t row_bytes = 0;
};

// The packing of the merged image of layout `shape` (without values), in the
// file's lines when `lines`.
Packing packing(const LayeredImage& shape, bool lines) {
  Packing to{packed_layout(shape), lines ? uncompressed_exr_lines(shape) : LineLayout{}, 0};
  to.row_bytes = lines ? to.lines.row_bytes : to.packed.pixel_bytes * static_cast<std::size_t>(shape.width);
  return to;
}

// Every pixel of a band film (a block of rows and columns) resolved
// (kPackPixels at a time into `row`, their resolved channels) and packed as
// `to` says into rows from `out` on (the block's first row), the block's
// first pixel being pixel `x` of its row.
void pack_block(const Film& band, const Packing& to, std::vector<float>& row, unsigned char* out, std::size_t x) {
  const auto width = static_cast<std::size_t>(band.crop().width());
  for (int y = 0; y < band.crop().height(); ++y) {
    unsigned char* rows = out + static_cast<std::size_t>(y) * to.row_bytes;
    const std::size_t pixel = static_cast<std::size_t>(y) * width;
    for (std::size_t first = 0; first < width; first += kPackPixels) {
      const std::size_t n = std::min(kPackPixels, width - first);
      band.resolve_channels(pixel + first, n, row.data());
      if (!to.lines.channels.empty()) {
        pack_lines(to.lines, row.data(), x + first, n, rows);
      } else {
        pack_pixels(to.packed, row.data(), n, rows + (x + first) * to.packed.pixel_bytes);
      }
    }
  }
}

// Writes rows [y0, y1) (packed, or the file's lines) to the file once it is
// open (waiting for it): false when it could not be opened (`error` empty:
// its opener has the message) or the write fails.
bool write_chunk(const std::shared_future<ExrBandWriter*>& file, int y0, int y1, unsigned char* rows,
                 const Packing& to, std::string& error) {
  ExrBandWriter* writer = file.get();
  if (writer == nullptr) return false;
  if (!to.lines.channels.empty()) return writer->write_lines(y0, y1, rows, error);
  if (writer->row_bytes() != to.row_bytes) {  // both from packed_layout: not expected
    error = "the EXR writer's rows are " + std::to_string(writer->row_bytes()) + " bytes, the merge's " +
            std::to_string(to.row_bytes);
    return false;
  }
  return writer->write(y0, y1, rows, error);
}

void lower(std::atomic<std::size_t>& lowest, std::size_t value) {
  std::size_t seen = lowest.load();
  while (value < seen && !lowest.compare_exchange_weak(seen, value)) {
  }
}

}  // namespace

struct ShardMerger::Bands {
  Bands(Film shape_, std::vector<AovRequest> aovs_, ChannelType beauty_, std::size_t shards)
      : shape(std::move(shape_)), aovs(std::move(aovs_)), beauty(beauty_), views(shards), bad(shards) {
    for (auto& b : bad) b = SIZE_MAX;
  }
  Film shape;  // the merged film's frame and AOVs, no pixels
  std::vector<AovRequest> aovs;
  ChannelType beauty;
  int rows = 1;     // rows of a band film
  int columns = 1;  // columns of a block of a band (the streamed merge)
  std::vector<StateView> views;
  std::vector<std::map<Key, std::pair<bool, int>>> orders;
  std::vector<std::atomic<std::size_t>> bad;  // per shard: the first pixel it is refused at
};

bool ShardMerger::view_states(const std::vector<std::string_view>& states, std::string& error) {
  if (states.size() != infos_.size() || states.empty()) {
    error = "the merge has " + std::to_string(states.size()) + " film states for " + std::to_string(infos_.size()) +
            " shards";
    return false;
  }
  std::vector<AovRequest> aovs;
  ChannelType beauty;
  if (!merged_.film_aovs(aovs, beauty, error)) return false;
  const PixelRect& w = merged_.window;
  auto b = std::make_shared<Bands>(Film(merged_.width, merged_.height, PixelRect{w.x0, w.y0, w.x1, w.y0}, aovs), aovs,
                                   beauty, states.size());  // the shape: no pixels
  const std::size_t pixel_bytes = sizeof(PixelSum) + static_cast<std::size_t>(b->shape.aov_slots()) * sizeof(ExactSum);
  b->rows = static_cast<int>(std::max<std::size_t>(1, kBandBytes / (pixel_bytes * static_cast<std::size_t>(w.width()))));
  b->columns = static_cast<int>(std::clamp<std::size_t>(kBlockBytes / (pixel_bytes * static_cast<std::size_t>(b->rows)), 1,
                                                         static_cast<std::size_t>(std::max(1, w.width()))));
  // Every state viewed (its size checked) and its precedence taken, in the
  // order checked, before anything is added (as add() would, one by one).
  for (std::size_t i = 0; i < states.size(); ++i) {
    if (std::string why; !b->shape.view_state(states[i], infos_[i].crop, w, b->views[i], why)) {
      error = "'" + names_[i] + "': " + why;
      return false;
    }
    b->orders.push_back(precedence(infos_[i]));
    for (const auto& [key, first] : b->orders.back())
      if (first.first) first_start_[key] = first.second;
  }
  bands_ = std::move(b);
  return true;
}

LayeredImage ShardMerger::layout() const {
  LayeredImage out = bands_->shape.layer_layout(bands_->beauty, PixelRect{});
  const PixelRect& w = merged_.window;
  out.x = w.x0;
  out.y = w.y0;
  out.width = w.width();
  out.height = w.height();
  return out;
}

std::vector<StateRules> ShardMerger::band_rules(const Bands& b, int y0, int y1) const {
  std::vector<StateRules> out(b.views.size());
  for (std::size_t i = 0; i < b.views.size(); ++i) {
    const PixelRect& c = b.views[i].crop;
    const int from = std::max(y0, c.y0), to = std::min(y1, c.y1);
    if (from < to) out[i] = rules(infos_[i], b.orders[i], from, to);
  }
  return out;
}

void ShardMerger::add_band(Bands& b, Film& band, const PixelRect& rect, const std::vector<StateRules>& rules) const {
  // The first state with pixels in the block, when it covers the whole block
  // (a share, or a tile that holds it), sets the block instead of being
  // added to a cleared one: the same bits (Film::set_state_rect).
  bool cleared = false;
  for (std::size_t i = 0; i < b.views.size(); ++i) {
    const PixelRect& c = b.views[i].crop;
    const PixelRect in{std::max(rect.x0, c.x0), std::max(rect.y0, c.y0), std::min(rect.x1, c.x1),
                       std::min(rect.y1, c.y1)};
    if (in.empty()) continue;
    std::size_t refused = SIZE_MAX;
    if (!cleared && in == rect) {
      refused = band.set_state_rect(b.views[i], rules[i], rect);
    } else {
      if (!cleared) band.recrop(rect);
      refused = band.add_state_rect(b.views[i], rules[i], in);
    }
    cleared = true;
    if (refused != SIZE_MAX) lower(b.bad[i], refused);
  }
  if (!cleared) band.recrop(rect);
}

bool ShardMerger::refused(const Bands& b, std::string& error) const {
  for (std::size_t i = 0; i < b.views.size(); ++i) {
    if (b.bad[i] == SIZE_MAX) continue;
    const auto y = b.views[i].crop.y0 + static_cast<int>(b.bad[i] / static_cast<std::size_t>(b.views[i].crop.width()));
    error = "'" + names_[i] + "': " + b.shape.refusal(b.views[i], b.bad[i], rules(infos_[i], b.orders[i], y, y + 1));
    return true;
  }
  return false;
}

bool ShardMerger::merge_layers(const std::vector<std::string_view>& states, LayeredImage& out, std::string& error) {
  if (!view_states(states, error)) return false;
  Bands& b = *bands_;
  const PixelRect& w = merged_.window;
  out = b.shape.layer_layout(b.beauty, w);
  const PixelRect first_band{w.x0, w.y0, w.x1, std::min(w.y1, w.y0 + b.rows)};
  tbb::enumerable_thread_specific<Film> bands([&] { return Film(merged_.width, merged_.height, first_band, b.aovs); });
  // Every pixel is added and resolved by one task, with integer sums: bands
  // in parallel give the bits of add() then layers(), and resolve with the
  // caller's floating-point settings, as layers() does.
  tbb::task_group_context context;
  context.capture_fp_settings();
  tbb::parallel_for(tbb::blocked_range<int>(w.y0, w.y1, b.rows), [&](const tbb::blocked_range<int>& r) {
    Film& band = bands.local();
    add_band(b, band, {w.x0, r.begin(), w.x1, r.end()}, band_rules(b, r.begin(), r.end()));
    band.resolve_into(out);
  }, tbb::simple_partitioner(), context);
  return !refused(b, error);
}

bool ShardMerger::merge_streamed(const std::shared_future<ExrBandWriter*>& file, bool lines, std::string& error,
                                 bool& refusal) {
  refusal = false;
  Bands& b = *bands_;
  const PixelRect& w = merged_.window;
  // Pixels' resolved channels, then packed into their chunk as the file stores them.
  const Packing to = packing(layout(), lines);
  const std::size_t row_bytes = to.row_bytes;
  // Chunks in flight: two per thread, and a few more made while the file is
  // opened (the image module's load), before the first write.
  const int tokens = std::max(2, 2 * tbb::this_task_arena::max_concurrency()) + kAheadChunks;
  // A chunk: about kChunkBytes, and no more than a tokens-th of the window (so
  // that the pipeline overlaps), in whole blocks of 32 rows.
  const int chunk_rows =
      std::max(32, static_cast<int>(std::min<std::size_t>(kChunkBytes / row_bytes,
                                                          static_cast<std::size_t>((w.height() + tokens - 1) / tokens))) /
                       32 * 32);
  const PixelRect first_band{w.x0, w.y0, w.x1, std::min(w.y1, w.y0 + b.rows)};
  tbb::enumerable_thread_specific<Film> bands([&] { return Film(merged_.width, merged_.height, first_band, b.aovs); });
  tbb::enumerable_thread_specific<std::vector<float>> resolved(
      [&] { return std::vector<float>(to.packed.channels * kPackPixels); });
  // Chunks of packed rows, reused: as many as the pipeline holds at once.
  struct Chunk {
    int y0 = 0, y1 = 0;
    std::unique_ptr<unsigned char[]> packed;
  };
  std::vector<Chunk> chunks(static_cast<std::size_t>(tokens));
  tbb::concurrent_queue<Chunk*> spare;
  for (Chunk& c : chunks) spare.push(&c);
  int next = w.y0;
  std::atomic<bool> write_failed = false;  // then no more chunks are made
  std::string why;
  // As merge_layers: each pixel added and resolved by one task, with the
  // caller's floating-point settings. Every band is merged even after a
  // refusal (nothing more is written), so that the refusal reported is
  // merge_layers' (the first shard's first refused pixel). A file that could
  // not be opened or written stops it: its message is the one reported.
  tbb::task_group_context context;
  context.capture_fp_settings();
  tbb::parallel_pipeline(
      static_cast<std::size_t>(tokens),
      tbb::make_filter<void, Chunk*>(tbb::filter_mode::serial_in_order,
                                     [&](tbb::flow_control& fc) -> Chunk* {
                                       Chunk* c = nullptr;
                                       if (next >= w.y1 || write_failed || !spare.try_pop(c)) {
                                         fc.stop();
                                         return nullptr;
                                       }
                                       c->y0 = next;
                                       c->y1 = next = std::min(w.y1, next + chunk_rows);
                                       if (!c->packed) c->packed.reset(new unsigned char[static_cast<std::size_t>(chunk_rows) * row_bytes]);
                                       return c;
                                     }) &
          tbb::make_filter<Chunk*, Chunk*>(tbb::filter_mode::parallel,
                                           [&](Chunk* c) {
                                             tbb::parallel_for(tbb::blocked_range<int>(c->y0, c->y1, b.rows), [&](const tbb::blocked_range<int>& r) {
                                               Film& band = bands.local();
                                               const std::vector<StateRules> rules = band_rules(b, r.begin(), r.end());
                                               unsigned char* rows = c->packed.get() + static_cast<std::size_t>(r.begin() - c->y0) * row_bytes;
                                               for (int x0 = w.x0; x0 < w.x1; x0 += b.columns) {
                                                 add_band(b, band, {x0, r.begin(), std::min(w.x1, x0 + b.columns), r.end()}, rules);
                                                 pack_block(band, to, resolved.local(), rows, static_cast<std::size_t>(x0 - w.x0));
                                               }
                                             }, tbb::simple_partitioner());
                                             return c;
                                           }) &
          tbb::make_filter<Chunk*, void>(tbb::filter_mode::serial_in_order,
                                         [&](Chunk* c) {
                                           const bool any_refused = std::any_of(b.bad.begin(), b.bad.end(), [](const auto& x) { return x != SIZE_MAX; });
                                           if (!any_refused && !write_failed) write_failed = !write_chunk(file, c->y0, c->y1, c->packed.get(), to, why);
                                           spare.push(c);
                                         }),
      context);
  if (refused(b, error)) {
    refusal = true;
    return false;
  }
  if (write_failed) error = why;
  return !write_failed;
}

}  // namespace pt
