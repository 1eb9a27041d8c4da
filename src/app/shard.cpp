#include "app/shard.h"

#include <cstdio>
#include <cstring>
#include <fstream>
#include <type_traits>
#include <variant>

#include "app/film_options.h"
#include "app/job.h"
#include "app/options.h"
#include "app/shard_file.h"

namespace pt {
namespace {

// 64-bit FNV-1a over 8-byte words (the bytes' hash in a fraction of the
// byte-wise time: meshes can be gigabytes).
class WordHash {
 public:
  void add(const void* data, std::size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (; n >= 8; n -= 8, p += 8) {
      uint64_t w;
      std::memcpy(&w, p, 8);
      mix(w);
    }
    uint64_t tail = n;  // the length of the tail, so "a" and "a\0" differ
    for (std::size_t i = 0; i < n; ++i) tail = (tail << 8) | p[i];
    mix(tail);
  }
  template <typename T>
  void add_vector(const std::vector<T>& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    add(v.data(), v.size() * sizeof(T));
  }
  // The bytes of a file; false if it cannot be read.
  bool add_file(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return false;
    std::vector<char> buffer(1 << 20);
    while (in) {
      in.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
      add(buffer.data(), static_cast<std::size_t>(in.gcount()));
    }
    return true;
  }
  std::string hex() const {
    char buf[17];
    std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h_));
    return buf;
  }

 private:
  void mix(uint64_t w) {
    h_ ^= w;
    h_ *= 0x100000001b3ull;
    h_ ^= h_ >> 29;  // the multiply moves bits up only; fold the high ones back
  }
  uint64_t h_ = 0xcbf29ce484222325ull;
};

// The shares: --shard K/N, --sample-range A,B or everything.
bool choose_share(const Options& o, ShardPlan& s, Messages& m) {
  const int units = s.target_spp / s.unit;
  const std::string pass_note = s.unit > 1 ? " (this sampler stratifies each pass of " + std::to_string(s.unit) +
                                                 " samples, so shares are whole passes; --pass-spp sets their size)"
                                           : "";
  s.share = {0, s.target_spp};
  if (!o.shard.empty()) {
    std::string error;
    const Fraction f = *parse_fraction(o.shard, error);  // CLI11 checked it
    if (f.n > units) {
      m.error("--shard " + o.shard + ": the render has " + std::to_string(units) +
              (s.unit > 1 ? " passes" : " samples per pixel") + ", fewer than " + std::to_string(f.n) + " shards" +
              pass_note);
      return false;
    }
    const Range r = share_of(f, units);
    s.share = {r.begin * s.unit, r.end * s.unit};
  } else if (!o.sample_range.empty()) {
    const int a = o.sample_range[0], b = o.sample_range[1];
    if (a < 0 || b <= a || b > s.target_spp) {
      m.error("--sample-range " + std::to_string(a) + "," + std::to_string(b) + ": need 0 <= A < B <= " +
              std::to_string(s.target_spp) + " (the render's samples per pixel)");
      return false;
    }
    if (a % s.unit != 0 || b % s.unit != 0) {
      m.error("--sample-range " + std::to_string(a) + "," + std::to_string(b) + ": A and B must be multiples of " +
              std::to_string(s.unit) + pass_note);
      return false;
    }
    s.share = {a, b};
  }
  return true;
}

}  // namespace

std::optional<Fraction> parse_fraction(const std::string& text, std::string& error) {
  int k = 0, n = 0, used = 0;
  if (std::sscanf(text.c_str(), "%d/%d%n", &k, &n, &used) != 2 || used != static_cast<int>(text.size()) ||
      text.find_first_of(" +") != std::string::npos) {
    error = "'" + text + "' is not K/N (e.g. 0/4: the first of four)";
    return std::nullopt;
  }
  if (n < 1 || n > (1 << 20)) {
    error = "'" + text + "': N must be in 1..1048576";
    return std::nullopt;
  }
  if (k < 0 || k >= n) {
    error = "'" + text + "': K must be in 0.." + std::to_string(n - 1) + " (K counts from 0)";
    return std::nullopt;
  }
  return Fraction{k, n};
}

std::string Range::text() const {
  std::string s = "[";  // appended, not "[" + ...: GCC 12 warns falsely about that (-Wrestrict)
  s += std::to_string(begin) + "," + std::to_string(end) + ")";
  return s;
}

Range share_of(Fraction f, int units) {
  const auto at = [&](int k) { return static_cast<int>(static_cast<int64_t>(k) * units / f.n); };
  return {at(f.k), at(f.k + 1)};
}

PixelRect tile_of(const PixelRect& window, Fraction tile) {
  if (window.height() < tile.n) return {};
  const Range rows = share_of(tile, window.height());
  return {window.x0, window.y0 + rows.begin, window.x1, window.y0 + rows.end};
}

bool plan_shard(const Options& o, Job& job, Messages& m) {
  ShardPlan& s = job.shard;
  s.active = o.sharded();
  if (!s.active) return true;
  PassPlan& plan = job.plan;
  // The whole render's target, even under a time budget: shards split it.
  s.target_spp = o.spp > 0 ? o.spp : job.desc.render.spp.value;
  PassPlan whole = plan;
  whole.target_spp = s.target_spp;
  s.unit = plan.equal_passes ? fixed_pass_size(whole) : 1;
  if (!choose_share(o, s, m)) return false;
  std::string error;
  if (!o.tile.empty()) s.tile = parse_fraction(o.tile, error);  // CLI11 checked it
  if (!region_window(o, job.settings.width, job.settings.height, s.window, error)) {
    m.error(error);
    return false;
  }
  plan.start_spp = s.share.begin;
  plan.target_spp = s.share.end;
  if (plan.equal_passes) plan.pass_spp = s.unit;
  s.identity = job.settings.identity();
  s.identity["accel"] = o.accel;  // the backends agree to rounding, not to the bit
  if (plan.equal_passes) s.identity["pass_spp"] = s.unit;
  s.assets_hash = assets_hash(job.desc);
  return true;
}

std::string aov_list_text(const std::vector<AovRequest>& aovs, ChannelType beauty) {
  std::string s;
  const auto type = [](ChannelType t) { return t == ChannelType::Half ? ":half" : ":float"; };
  for (const AovRequest& r : aovs) s += std::string(aov_info(r.type).name) + type(r.channel_type) + ",";
  return s + kBeautyName + type(beauty);
}

ShardInfo shard_info(const Job& job, const Film& film, const RenderOutcome& outcome, const ImageMetadata& metadata,
                     double render_seconds) {
  const ShardPlan& s = job.shard;
  ShardInfo info;
  info.scene = job.identity.scene;
  info.scene_hash = job.identity.scene_hash;
  info.assets_hash = s.assets_hash;
  info.version = PT_VERSION;
  info.build = build_hash();
  info.settings = s.identity;
  info.width = film.width();
  info.height = film.height();
  info.target_spp = s.target_spp;
  info.window = s.window;
  info.crop = film.crop();
  info.aovs = aov_list_text(job.aovs, job.beauty_type);
  for (const AovRequest& r : job.aovs)
    if (r.ranks > 0) info.cryptomatte_levels = r.ranks;
  info.pieces.push_back({film.crop(), s.tile, s.share, {s.share.begin, outcome.spp_done}});
  info.display = job.display;
  info.metadata = metadata;
  info.render_seconds = render_seconds;
  return info;
}

std::string assets_hash(const SceneDescription& desc) {
  WordHash h;
  for (const ShapeDesc& shape : desc.shapes) {
    if (shape.file.empty()) continue;
    if (const auto* mesh = std::get_if<TriangleMesh>(&shape.geometry)) {
      h.add(shape.file.data(), shape.file.size());
      h.add_vector(mesh->positions);
      h.add_vector(mesh->normals);
      h.add_vector(mesh->uvs);
      h.add_vector(mesh->indices);
    }
  }
  for (const TextureDesc& t : desc.textures) {
    h.add(t.written.data(), t.written.size());
    if (!h.add_file(t.resolved)) h.add("unreadable", 10);
  }
  if (desc.environment) {
    h.add(desc.environment->file.value.data(), desc.environment->file.value.size());
    if (!h.add_file(desc.environment->resolved)) h.add("unreadable", 10);
  }
  return h.hex();
}

std::string build_hash() {
  WordHash h;
  return h.add_file("/proc/self/exe") ? h.hex() : "unknown";
}

}  // namespace pt
