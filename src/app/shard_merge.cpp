#include "app/shard_merge.h"

#include <algorithm>
#include <istream>
#include <set>

#include "app/output_checks.h"
#include "app/outputs.h"

namespace pt {
namespace {

// At most this many missing pieces are listed in a message.
constexpr std::size_t kListed = 8;

std::string rows_text(const PixelRect& r) {
  return "rows [" + std::to_string(r.y0) + "," + std::to_string(r.y1) + ") x columns [" + std::to_string(r.x0) + "," +
         std::to_string(r.x1) + ")";
}

std::string tile_text(const ShardPiece& p) {
  return p.tile ? "tile " + std::to_string(p.tile->k) + "/" + std::to_string(p.tile->n) + " (" + rows_text(p.crop) + ")"
                : "every pixel";
}

template <typename T>
void replace(std::vector<std::pair<std::string, T>>& list, const std::string& name, const T& value) {
  std::erase_if(list, [&](const auto& item) { return item.first == name; });
  list.emplace_back(name, value);
}

// "a; b; c; and 5 more".
std::string listed(const std::vector<std::string>& items) {
  std::string s;
  for (std::size_t i = 0; i < items.size() && i < kListed; ++i) s += (i == 0 ? "" : "; ") + items[i];
  if (items.size() > kListed) s += "; and " + std::to_string(items.size() - kListed) + " more";
  return s;
}

}  // namespace

bool ShardMerger::check_pieces(const std::string& name, const ShardInfo& info, std::string& error) const {
  const auto clash = [&](const ShardPiece& p, const ShardPiece& q, const std::string& other) {
    if (!p.crop.intersects(q.crop)) return false;
    const std::string pair = "'" + name + "' and '" + other + "'";
    if (p.crop != q.crop) {
      error = pair + " hold overlapping tiles of different tilings (" + tile_text(p) + ", " + tile_text(q) +
              "); merge the shards of one tiling";
    } else if (p.share == q.share) {
      error = pair + " are the same shard (samples " + p.share.text() + " of " + tile_text(p) + ")";
    } else if (p.share.begin < q.share.end && q.share.begin < p.share.end) {
      error = pair + " overlap: both hold samples " +
              Range{std::max(p.share.begin, q.share.begin), std::min(p.share.end, q.share.end)}.text() + " of " +
              tile_text(p);
    } else {
      return false;
    }
    return true;
  };
  for (std::size_t i = 0; i < info.pieces.size(); ++i) {
    const ShardPiece& p = info.pieces[i];
    if (!merged_.window.contains(p.crop)) {
      error = "'" + name + "': its " + tile_text(p) + " is outside the window";
      return false;
    }
    for (std::size_t j = 0; j < i; ++j)
      if (clash(p, info.pieces[j], name)) return false;
    for (const Placed& q : placed_)
      if (clash(p, q.piece, q.name)) return false;
  }
  return true;
}

bool ShardMerger::check(const std::string& name, const ShardInfo& info, std::string& error) {
  if (names_.empty()) {
    merged_ = info;
    merged_.pieces.clear();
    merged_.render_seconds = 0;
    merged_.partial = false;
    merged_.crop = info.window;
  } else if (const std::string d = shard_mismatch(merged_, info); !d.empty()) {
    error = "cannot merge '" + name + "' with '" + names_.front() + "': they differ in " + d;
    return false;
  }
  if (!check_pieces(name, info, error)) return false;
  if (info.build != merged_.build)
    warnings_.push_back("'" + name + "' comes from another build of pathtracer (" + info.build + ", not " +
                        merged_.build + "): its samples may differ from the others' in the last bits");
  names_.push_back(name);
  infos_.push_back(info);
  for (const ShardPiece& p : info.pieces) {
    placed_.push_back({p, name});
    merged_.pieces.push_back(p);
  }
  std::sort(merged_.pieces.begin(), merged_.pieces.end(), [](const ShardPiece& a, const ShardPiece& b) {
    return std::tie(a.crop.y0, a.crop.x0, a.share.begin) < std::tie(b.crop.y0, b.crop.x0, b.share.begin);
  });
  merged_.render_seconds += info.render_seconds;
  merged_.partial = merged_.partial || info.partial;  // a merge of partial merges is partial
  return true;
}

bool ShardMerger::make_film(std::string& error) {
  if (film_) return true;
  std::vector<AovRequest> aovs;
  ChannelType beauty;
  if (!merged_.film_aovs(aovs, beauty, error)) return false;
  film_.emplace(merged_.width, merged_.height, merged_.window, aovs);
  return true;
}

std::map<ShardMerger::Key, std::pair<bool, int>> ShardMerger::precedence(const ShardInfo& info) const {
  std::map<Key, int> starts;  // per crop of this shard: its lowest first sample
  for (const ShardPiece& p : info.pieces) {
    const Key key{p.crop.x0, p.crop.y0, p.crop.x1, p.crop.y1};
    const auto it = starts.find(key);
    starts[key] = it == starts.end() ? p.done.begin : std::min(it->second, p.done.begin);
  }
  std::map<Key, std::pair<bool, int>> out;
  for (const auto& [key, start] : starts) {
    const auto it = first_start_.find(key);
    out[key] = {it == first_start_.end() || start < it->second, start};
  }
  return out;
}

bool ShardMerger::add(const std::string& name, const ShardInfo& info, const Film& film, std::string& error) {
  if (!make_film(error)) return false;
  for (const auto& [key, first] : precedence(info)) {
    const PixelRect crop{std::get<0>(key), std::get<1>(key), std::get<2>(key), std::get<3>(key)};
    if (std::string why; !film_->add_film(film, crop, first.first, why)) {
      error = "'" + name + "': " + why;
      return false;
    }
    if (first.first) first_start_[key] = first.second;
  }
  film_->add_non_finite(film.non_finite());
  return true;
}

StateRules ShardMerger::rules(const ShardInfo& info, const std::map<Key, std::pair<bool, int>>& order) const {
  return rules(info, order, info.crop.y0, info.crop.y1);
}

StateRules ShardMerger::rules(const ShardInfo& info, const std::map<Key, std::pair<bool, int>>& order, int y0,
                              int y1) const {
  const PixelRect& c = info.crop;
  const auto width = static_cast<std::size_t>(c.width());
  StateRules rules;
  rules.crop = c;
  rules.first = static_cast<std::size_t>(y0 - c.y0) * width;
  rules.other_first.assign(width * static_cast<std::size_t>(y1 - y0), 0);
  rules.max_samples.assign(rules.other_first.size(), 0);
  const auto at = [&](int x, int y) { return static_cast<std::size_t>(y - y0) * width + static_cast<std::size_t>(x - c.x0); };
  std::map<Key, uint64_t> done;  // the samples each crop's pixels may hold
  for (const ShardPiece& p : info.pieces)
    done[{p.crop.x0, p.crop.y0, p.crop.x1, p.crop.y1}] += static_cast<uint64_t>(p.done.size());
  for (const auto& [key, n] : done)
    for (int y = std::max(y0, std::get<1>(key)); y < std::min(y1, std::get<3>(key)); ++y)
      for (int x = std::get<0>(key); x < std::get<2>(key); ++x) rules.max_samples[at(x, y)] += n;
  for (const auto& [key, first] : order)
    for (int y = std::max(y0, std::get<1>(key)); first.first && y < std::min(y1, std::get<3>(key)); ++y)
      for (int x = std::get<0>(key); x < std::get<2>(key); ++x) rules.other_first[at(x, y)] = 1;
  return rules;
}

template <typename State>
bool ShardMerger::add_state(const std::string& name, const ShardInfo& info, State&& state, std::string& error) {
  if (!make_film(error)) return false;
  const std::map<Key, std::pair<bool, int>> order = precedence(info);
  if (std::string why; !film_->add_state(std::forward<State>(state), rules(info, order), why)) {
    error = "'" + name + "': " + why;
    return false;
  }
  for (const auto& [key, first] : order)
    if (first.first) first_start_[key] = first.second;
  return true;
}

bool ShardMerger::add(const std::string& name, const ShardInfo& info, std::istream& state, std::string& error) {
  return add_state(name, info, state, error);
}

bool ShardMerger::add(const std::string& name, const ShardInfo& info, std::string_view state, std::string& error) {
  return add_state(name, info, state, error);
}

std::string ShardMerger::missing_tiles() const {
  std::set<Key> crops;
  std::set<int> tilings;
  int64_t area = 0;
  for (const Placed& p : placed_) {
    const PixelRect& c = p.piece.crop;
    if (crops.insert({c.x0, c.y0, c.x1, c.y1}).second) area += static_cast<int64_t>(c.width()) * c.height();
    if (p.piece.tile) tilings.insert(p.piece.tile->n);
  }
  const PixelRect& w = merged_.window;
  if (area == static_cast<int64_t>(w.width()) * w.height()) return {};
  std::vector<std::string> missing;
  for (int n : tilings)
    for (int k = 0; k < n; ++k) {
      const PixelRect t = tile_of(w, {k, n});
      const bool covered = std::any_of(placed_.begin(), placed_.end(),
                                       [&](const Placed& p) { return p.piece.crop.intersects(t); });
      if (!covered)
        missing.push_back("tile " + std::to_string(k) + "/" + std::to_string(n) + " (" + rows_text(t) + ")");
    }
  if (missing.empty()) return "some pixels of " + rows_text(w) + " are in no shard";
  return "no shard holds " + listed(missing);
}

std::string ShardMerger::missing_samples() const {
  std::map<Key, std::vector<const ShardPiece*>> by_crop;
  for (const Placed& p : placed_)
    by_crop[{p.piece.crop.x0, p.piece.crop.y0, p.piece.crop.x1, p.piece.crop.y1}].push_back(&p.piece);
  std::vector<std::string> missing;
  for (auto& [key, pieces] : by_crop) {
    std::sort(pieces.begin(), pieces.end(),
              [](const ShardPiece* a, const ShardPiece* b) { return a->share.begin < b->share.begin; });
    int next = 0;
    for (const ShardPiece* p : pieces) {
      if (p->share.begin > next) missing.push_back(Range{next, p->share.begin}.text() + " of " + tile_text(*p));
      next = std::max(next, p->share.end);
    }
    if (next < merged_.target_spp)
      missing.push_back(Range{next, merged_.target_spp}.text() + " of " + tile_text(*pieces.front()));
  }
  if (missing.empty()) return {};
  return "no shard holds samples " + listed(missing) + " (of " + std::to_string(merged_.target_spp) + " per pixel)";
}

bool ShardMerger::finish(std::string& error) {
  if (names_.empty()) {
    error = "no shards to merge";
    return false;
  }
  std::string missing = missing_tiles();
  if (const std::string samples = missing_samples(); !samples.empty())
    missing += (missing.empty() ? "" : "; ") + samples;
  if (missing.empty()) return true;
  if (!allow_partial_) {
    error = "the shards are incomplete: " + missing + " (--allow-partial merges what is there, marked partial)";
    return false;
  }
  notes_ = "partial merge: " + missing;
  merged_.partial = true;
  return true;
}

int ShardMerger::spp() const {
  std::map<Key, int> done;
  for (const Placed& p : placed_)
    done[{p.piece.crop.x0, p.piece.crop.y0, p.piece.crop.x1, p.piece.crop.y1}] += p.piece.done.size();
  int fewest = done.empty() ? 0 : done.begin()->second;
  for (const auto& [key, n] : done) fewest = std::min(fewest, n);
  return fewest;
}

ImageMetadata ShardMerger::metadata() const {
  ImageMetadata m = merged_.metadata;
  std::string shards = std::to_string(names_.size()) + " shard" + (names_.size() == 1 ? "" : "s") + ":";
  for (const ShardPiece& p : merged_.pieces) {
    shards += " " + (p.tile ? std::to_string(p.tile->k) + "/" + std::to_string(p.tile->n) + ":" : std::string()) +
              p.share.text();
    if (p.done != p.share) shards += "(done " + p.done.text() + ")";
  }
  replace(m.floats, "pathtracer:renderTime", static_cast<float>(merged_.render_seconds));
  replace(m.ints, "pathtracer:spp", spp());
  replace(m.ints, "pathtracer:partial", merged_.partial ? 1 : 0);
  replace(m.strings, "pathtracer:shards", shards);
  return m;
}

ChannelType ShardMerger::beauty_type() const {
  std::vector<AovRequest> aovs;
  ChannelType beauty = ChannelType::Float;
  std::string error;
  merged_.film_aovs(aovs, beauty, error);  // checked by make_film / merge_layers before any layers exist
  return beauty;
}

bool write_merged_images(const ShardMerger& merger, const LayeredImage& layers, const std::vector<std::string>& outputs,
                         const std::string& ocio_config, const ExrSettings& exr, OutputStamps& stamps,
                         std::string& error) {
  const ShardInfo& info = merger.info();
  DisplaySettings display = info.display;
  if (!ocio_config.empty()) display.ocio_config = ocio_config;
  display.alpha = info.settings.value("film_transparent", false);  // PNG: RGBA, as the render's
  return write_outputs(outputs, layers, display, exr, merger.metadata(), stamps, error);
}

bool write_merged(const ShardMerger& merger, const std::vector<std::string>& outputs, const std::string& shard_out,
                  const std::string& ocio_config, const ExrSettings& exr, OutputStamps& stamps, std::string& error) {
  if (!outputs.empty() && !write_merged_images(merger, merger.film().layers(merger.beauty_type()), outputs,
                                               ocio_config, exr, stamps, error))
    return false;
  return shard_out.empty() || write_shard(shard_out, merger.info(), merger.film(), error);
}

}  // namespace pt
