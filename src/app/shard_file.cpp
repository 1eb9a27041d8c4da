#include "app/shard_file.h"

#include <algorithm>
#include <fstream>
#include <iterator>
#include <map>
#include <ostream>

#include "app/checkpoint.h"
#include "io/atomic_file.h"

namespace pt {
namespace {

constexpr const char* kMagicLine = "pathtracer-shard 2";
// Headers grow with the pieces of a merged file (about 100 bytes each).
constexpr std::size_t kMaxHeaderBytes = 16 * 1024 * 1024;
constexpr std::string_view kKeys[] = {"scene",  "scene_hash", "assets_hash", "version", "build",   "settings",
                                      "frame",  "target_spp", "window",      "crop",    "aovs",    "cryptomatte_levels", "pieces",
                                      "display", "metadata",  "render_seconds", "partial"};

using J = nlohmann::ordered_json;

J rect_json(const PixelRect& r) { return J::array({r.x0, r.y0, r.x1, r.y1}); }
J range_json(const Range& r) { return J::array({r.begin, r.end}); }

std::string fraction_text(const Fraction& f) { return std::to_string(f.k) + "/" + std::to_string(f.n); }

J display_json(const DisplaySettings& d) {
  return {{"transform", kDisplayTransformNames[static_cast<int>(d.transform)]},
          {"exposure", d.exposure},
          {"view", d.view},
          {"display", d.display},
          {"look", d.look},
          {"ocio_config", d.ocio_config}};
}

J header_json(const ShardInfo& info) {
  J pieces = J::array();
  for (const ShardPiece& p : info.pieces)
    pieces.push_back({{"crop", rect_json(p.crop)},
                      {"tile", p.tile ? J(fraction_text(*p.tile)) : J(nullptr)},
                      {"share", range_json(p.share)},
                      {"done", range_json(p.done)}});
  return {{"scene", info.scene},
          {"scene_hash", info.scene_hash},
          {"assets_hash", info.assets_hash},
          {"version", info.version},
          {"build", info.build},
          {"settings", info.settings},
          {"frame", J::array({info.width, info.height})},
          {"target_spp", info.target_spp},
          {"window", rect_json(info.window)},
          {"crop", rect_json(info.crop)},
          {"aovs", info.aovs},
          {"cryptomatte_levels", info.cryptomatte_levels},
          {"pieces", pieces},
          {"display", display_json(info.display)},
          {"metadata", metadata_json(info.metadata)},
          {"render_seconds", info.render_seconds},
          {"partial", info.partial}};
}

// Reads the fields of a header, stopping at the first problem, which it puts
// in `error` ("'<path>': damaged shard header: ...").
class Fields {
 public:
  Fields(const std::string& path, std::string& error) : path_(path), error_(error) {}

  bool fail(const std::string& why) {
    error_ = "'" + path_ + "': damaged shard header: " + why;
    return false;
  }
  bool string(const J& v, const std::string& what, std::string& out) {
    if (!v.is_string()) return fail(what + " must be a string");
    out = v.get<std::string>();
    return true;
  }
  bool hash(const J& v, const std::string& what, std::string& out) {
    if (!string(v, what, out)) return false;
    const bool hex = out.size() == 16 && std::all_of(out.begin(), out.end(), [](char c) {
                       return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f');
                     });
    return hex || fail(what + " must be 16 hexadecimal digits");
  }
  bool integer(const J& v, const std::string& what, int lo, int hi, int& out) {
    if (!v.is_number_integer()) return fail(what + " must be an integer");
    const int64_t x = v.is_number_unsigned() ? static_cast<int64_t>(std::min<uint64_t>(v.get<uint64_t>(), INT64_MAX))
                                             : v.get<int64_t>();
    if (x < lo || x > hi)
      return fail(what + " must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " + v.dump());
    out = static_cast<int>(x);
    return true;
  }
  bool number(const J& v, const std::string& what, double& out) {
    if (!v.is_number()) return fail(what + " must be a number");
    out = v.get<double>();
    return true;
  }
  // [x0, y0, x1, y1], non-empty, inside a width x height frame.
  bool rect(const J& v, const std::string& what, int width, int height, PixelRect& out) {
    if (!v.is_array() || v.size() != 4) return fail(what + " must be [x0, y0, x1, y1]");
    int c[4];
    for (int i = 0; i < 4; ++i)
      if (!integer(v[static_cast<std::size_t>(i)], what, 0, i % 2 == 0 ? width : height, c[i])) return false;
    out = {c[0], c[1], c[2], c[3]};
    return !out.empty() || fail(what + " is empty");
  }
  bool range(const J& v, const std::string& what, int limit, Range& out) {
    if (!v.is_array() || v.size() != 2) return fail(what + " must be [begin, end]");
    if (!integer(v[0], what, 0, limit, out.begin) || !integer(v[1], what, out.begin, limit, out.end)) return false;
    return true;
  }

 private:
  const std::string& path_;
  std::string& error_;
};

bool read_piece(const J& p, const ShardInfo& info, Fields& f, ShardPiece& out) {
  if (!p.is_object() || !p.contains("crop") || !p.contains("tile") || !p.contains("share") || !p.contains("done") ||
      p.size() != 4)
    return f.fail("a piece must have exactly \"crop\", \"tile\", \"share\" and \"done\"");
  if (!f.rect(p["crop"], "a piece's crop", info.width, info.height, out.crop)) return false;
  if (!info.crop.contains(out.crop)) return f.fail("a piece's crop is outside the film state's");
  if (!p["tile"].is_null()) {
    std::string text, why;
    if (!f.string(p["tile"], "a piece's tile", text)) return false;
    const std::optional<Fraction> tile = parse_fraction(text, why);
    if (!tile) return f.fail("a piece's tile: " + why);
    out.tile = tile;
  }
  if (!f.range(p["share"], "a piece's share", info.target_spp, out.share) ||
      !f.range(p["done"], "a piece's done range", info.target_spp, out.done))
    return false;
  if (out.done.begin != out.share.begin || out.done.end > out.share.end)
    return f.fail("a piece's done range is not a prefix of its share");
  return true;
}

bool read_display(const J& d, Fields& f, DisplaySettings& out) {
  if (!d.is_object() || d.size() != 6) return f.fail("\"display\" must be an object of 6 settings");
  std::string transform;
  double exposure = 0;
  if (!f.string(d.value("transform", J()), "display.transform", transform) ||
      !f.number(d.value("exposure", J()), "display.exposure", exposure) ||
      !f.string(d.value("view", J()), "display.view", out.view) ||
      !f.string(d.value("display", J()), "display.display", out.display) ||
      !f.string(d.value("look", J()), "display.look", out.look) ||
      !f.string(d.value("ocio_config", J()), "display.ocio_config", out.ocio_config))
    return false;
  const auto* names = std::begin(kDisplayTransformNames);
  const auto* it = std::find(names, std::end(kDisplayTransformNames), transform);
  if (it == std::end(kDisplayTransformNames)) return f.fail("unknown display.transform '" + transform + "'");
  out.transform = static_cast<DisplayTransform>(it - names);
  out.exposure = static_cast<float>(exposure);
  return true;
}

bool read_identity(const J& j, Fields& f, ShardInfo& info) {
  if (!f.string(j["scene"], "\"scene\"", info.scene) || !f.hash(j["scene_hash"], "\"scene_hash\"", info.scene_hash) ||
      !f.hash(j["assets_hash"], "\"assets_hash\"", info.assets_hash) ||
      !f.string(j["version"], "\"version\"", info.version) || !f.string(j["build"], "\"build\"", info.build) ||
      !f.string(j["aovs"], "\"aovs\"", info.aovs))
    return false;
  if (!j["settings"].is_object()) return f.fail("\"settings\" must be an object");
  info.settings = j["settings"];
  const J& frame = j["frame"];
  if (!frame.is_array() || frame.size() != 2) return f.fail("\"frame\" must be [width, height]");
  constexpr int kMaxSide = 1 << 20;
  if (!f.integer(frame[0], "the frame width", 1, kMaxSide, info.width) ||
      !f.integer(frame[1], "the frame height", 1, kMaxSide, info.height) ||
      !f.integer(j["target_spp"], "\"target_spp\"", 1, kMaxCheckpointSpp, info.target_spp) ||
      !f.rect(j["window"], "\"window\"", info.width, info.height, info.window) ||
      !f.rect(j["crop"], "\"crop\"", info.width, info.height, info.crop) ||
      !f.integer(j["cryptomatte_levels"], "\"cryptomatte_levels\"", 1, kCryptomatteMaxRanks, info.cryptomatte_levels))
    return false;
  if (!j["partial"].is_boolean()) return f.fail("\"partial\" must be true or false");
  info.partial = j["partial"].get<bool>();
  return f.number(j["render_seconds"], "\"render_seconds\"", info.render_seconds);
}

bool read_header(const J& j, Fields& f, ShardInfo& info) {
  for (const std::string_view key : kKeys)
    if (!j.contains(std::string(key))) return f.fail("no \"" + std::string(key) + "\"");
  for (const auto& [key, value] : j.items())
    if (std::find(std::begin(kKeys), std::end(kKeys), key) == std::end(kKeys))
      return f.fail("unknown key \"" + key + "\"");
  if (!read_identity(j, f, info) || !read_display(j["display"], f, info.display)) return false;
  if (!metadata_from_json(j["metadata"], info.metadata)) return f.fail("\"metadata\" is not image metadata");
  const J& pieces = j["pieces"];
  if (!pieces.is_array() || pieces.empty()) return f.fail("\"pieces\" must be a non-empty array");
  for (const J& p : pieces) {
    ShardPiece piece;
    if (!read_piece(p, info, f, piece)) return false;
    info.pieces.push_back(piece);
  }
  std::vector<AovRequest> aovs;
  ChannelType beauty;
  std::string why;
  return info.film_aovs(aovs, beauty, why) || f.fail("\"aovs\": " + why);
}

// A pixel may hold at most the samples of the pieces that cover it (the
// binary view adds one per pass, so fewer).
bool samples_fit(const ShardInfo& info, const Film& film, std::string& error) {
  std::map<std::tuple<int, int, int, int>, uint64_t> per_crop;
  for (const ShardPiece& p : info.pieces)
    per_crop[{p.crop.x0, p.crop.y0, p.crop.x1, p.crop.y1}] += static_cast<uint64_t>(p.done.size());
  std::vector<uint64_t> bound(static_cast<std::size_t>(film.crop().width()) * film.crop().height(), 0);
  const PixelRect& c = film.crop();
  for (const auto& [r, n] : per_crop)
    for (int y = std::get<1>(r); y < std::get<3>(r); ++y)
      for (int x = std::get<0>(r); x < std::get<2>(r); ++x)
        bound[static_cast<std::size_t>(y - c.y0) * c.width() + static_cast<std::size_t>(x - c.x0)] += n;
  for (int y = c.y0; y < c.y1; ++y)
    for (int x = c.x0; x < c.x1; ++x) {
      const uint64_t b = bound[static_cast<std::size_t>(y - c.y0) * c.width() + static_cast<std::size_t>(x - c.x0)];
      if (film.sum(x, y).samples > b) {
        error = "its film state holds " + std::to_string(film.sum(x, y).samples) + " samples in pixel (" +
                std::to_string(x) + ", " + std::to_string(y) + "), more than its pieces' " + std::to_string(b) +
                " (the two do not belong together)";
        return false;
      }
    }
  return true;
}

}  // namespace

bool ShardInfo::film_aovs(std::vector<AovRequest>& out, ChannelType& beauty, std::string& error) const {
  return parse_aov_list(aovs, out, beauty, error, cryptomatte_levels);
}

bool write_shard(std::ostream& out, const ShardInfo& info, const Film& film) {
  out << kMagicLine << '\n' << header_json(info).dump(-1, ' ', false, J::error_handler_t::replace) << '\n';
  return film.write_state(out);
}

bool write_shard(const std::string& path, const ShardInfo& info, const Film& film, std::string& error) {
  return write_atomically(
      path,
      [&](const std::string& tmp, std::string& why) {
        std::ofstream out(tmp, std::ios::binary);
        if (!write_shard(out, info, film)) {
          why = "write failed";
          return false;
        }
        out.close();
        if (!out) why = "write failed";
        return static_cast<bool>(out);
      },
      error);
}

bool read_shard_info(std::istream& in, const std::string& path, ShardInfo& info, std::string& error) {
  J j;
  if (!read_json_header(in, path, kMagicLine, "shard file", j, error, kMaxHeaderBytes)) return false;
  ShardInfo read;
  Fields fields(path, error);
  try {
    if (!read_header(j, fields, read)) return false;
  } catch (const nlohmann::json::exception& e) {  // a value of an unexpected type somewhere
    return fields.fail(e.what());
  }
  info = std::move(read);
  return true;
}

std::optional<Film> read_shard_film(std::istream& in, const std::string& path, const ShardInfo& info,
                                    std::string& error) {
  std::vector<AovRequest> aovs;
  ChannelType beauty;
  if (!info.film_aovs(aovs, beauty, error)) return std::nullopt;
  std::optional<Film> state(std::in_place, info.width, info.height, info.crop, aovs);
  std::string why;
  if (!state->read_state(in, why) || !samples_fit(info, *state, why)) {
    error = "'" + path + "': " + why;
    return std::nullopt;
  }
  return state;
}

}  // namespace pt
