// ShardMerger::merge_layers: the band merge of `pathtracer merge`
// (docs/distributed.md, "The merge").
#include <algorithm>
#include <atomic>
#include <cstdint>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "app/shard_merge.h"

namespace pt {
namespace {

// A band film holds about this many bytes of state (it stays in the cache
// while every shard's rows are added into it and it is resolved).
constexpr std::size_t kBandBytes = std::size_t{1} << 20;

void lower(std::atomic<std::size_t>& lowest, std::size_t value) {
  std::size_t seen = lowest.load();
  while (value < seen && !lowest.compare_exchange_weak(seen, value)) {
  }
}

}  // namespace

bool ShardMerger::merge_layers(const std::vector<std::string_view>& states, LayeredImage& out, std::string& error) {
  if (states.size() != infos_.size() || states.empty()) {
    error = "the merge has " + std::to_string(states.size()) + " film states for " + std::to_string(infos_.size()) +
            " shards";
    return false;
  }
  std::vector<AovRequest> aovs;
  ChannelType beauty;
  if (!merged_.film_aovs(aovs, beauty, error)) return false;
  const PixelRect& w = merged_.window;
  const Film shape(merged_.width, merged_.height, PixelRect{w.x0, w.y0, w.x1, w.y0}, aovs);  // no pixels
  const std::size_t pixel_bytes = sizeof(PixelSum) + static_cast<std::size_t>(shape.aov_slots()) * sizeof(ExactSum);
  const int rows = static_cast<int>(std::max<std::size_t>(1, kBandBytes / (pixel_bytes * static_cast<std::size_t>(w.width()))));
  // Every state viewed (its size checked) and its precedence taken, in the
  // order checked, before anything is added (as add() would, one by one).
  std::vector<StateView> views(states.size());
  std::vector<std::map<Key, std::pair<bool, int>>> orders;
  for (std::size_t i = 0; i < states.size(); ++i) {
    if (std::string why; !shape.view_state(states[i], infos_[i].crop, w, views[i], why)) {
      error = "'" + names_[i] + "': " + why;
      return false;
    }
    orders.push_back(precedence(infos_[i]));
    for (const auto& [key, first] : orders.back())
      if (first.first) first_start_[key] = first.second;
  }
  out = shape.layer_layout(beauty, w);
  std::vector<std::atomic<std::size_t>> bad(states.size());  // per shard: the first pixel it is refused at
  for (auto& b : bad) b = SIZE_MAX;
  const PixelRect first_band{w.x0, w.y0, w.x1, std::min(w.y1, w.y0 + rows)};
  tbb::enumerable_thread_specific<Film> bands([&] { return Film(merged_.width, merged_.height, first_band, aovs); });
  // Every pixel is added and resolved by one task, with integer sums: bands
  // in parallel give the bits of add() then layers(), and resolve with the
  // caller's floating-point settings, as layers() does.
  tbb::task_group_context context;
  context.capture_fp_settings();
  tbb::parallel_for(tbb::blocked_range<int>(w.y0, w.y1, rows), [&](const tbb::blocked_range<int>& r) {
    Film& band = bands.local();
    band.recrop({w.x0, r.begin(), w.x1, r.end()});
    for (std::size_t i = 0; i < views.size(); ++i) {
      const int y0 = std::max(r.begin(), views[i].crop.y0), y1 = std::min(r.end(), views[i].crop.y1);
      if (y0 >= y1) continue;
      const std::size_t refused = band.add_state_rows(views[i], rules(infos_[i], orders[i], y0, y1), y0, y1);
      if (refused != SIZE_MAX) lower(bad[i], refused);
    }
    band.resolve_into(out);
  }, tbb::simple_partitioner(), context);
  for (std::size_t i = 0; i < views.size(); ++i) {
    if (bad[i] == SIZE_MAX) continue;
    const auto y = views[i].crop.y0 + static_cast<int>(bad[i] / static_cast<std::size_t>(views[i].crop.width()));
    error = "'" + names_[i] + "': " + shape.refusal(views[i], bad[i], rules(infos_[i], orders[i], y, y + 1));
    return false;
  }
  return true;
}

}  // namespace pt
