#include "app/checkpoint.h"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <istream>
#include <iterator>
#include <ostream>
#include <string_view>
#include <utility>

#include "core/file_access.h"
#include "io/atomic_file.h"
#include "render/film/film.h"

namespace pt {
namespace {

constexpr const char* kMagicLine = "pathtracer-checkpoint 1";

uint64_t fnv1a(uint64_t h, const char* data, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) {
    h ^= static_cast<unsigned char>(data[i]);
    h *= 0x100000001b3ull;
  }
  return h;
}

// The header's keys, each required; any other is refused.
constexpr std::string_view kHeaderKeys[] = {"scene", "scene_hash", "settings", "spp_done"};

// Ours nest 2 deep; deeper values are refused before they are parsed and
// printed (printing a JSON value recurses once per level).
constexpr int kMaxHeaderDepth = 16;

// The deepest nesting of arrays and objects in a JSON text (strings skipped).
int nesting_depth(const std::string& text) {
  int depth = 0, deepest = 0;
  bool in_string = false, escaped = false;
  for (char c : text) {
    if (in_string) {
      if (escaped)
        escaped = false;
      else if (c == '\\')
        escaped = true;
      else if (c == '"')
        in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      deepest = std::max(deepest, ++depth);
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  return deepest;
}

bool damaged_file(const std::string& path, const std::string& kind, const std::string& why, std::string& error) {
  error = "'" + path + "': damaged " + kind + " header: " + why;
  return false;
}

bool damaged(const std::string& path, const std::string& why, std::string& error) {
  return damaged_file(path, "checkpoint", why, error);
}

// A JSON value for a message: its type and, shortened, the value.
std::string shown(const nlohmann::ordered_json& v) {
  std::string text = v.dump();
  if (text.size() > 40) text = text.substr(0, 37) + "...";
  return std::string(v.type_name()) + " " + text;
}

bool is_hash(const std::string& s) {
  return s.size() == 16 && std::all_of(s.begin(), s.end(), [](char c) {
           return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f');
         });
}

// Reads up to '\n' (not stored); false at the end of the stream or past `limit` bytes.
bool read_line(std::istream& in, std::string& line, std::size_t limit) {
  line.clear();
  for (int c = in.get(); c != std::char_traits<char>::eof(); c = in.get()) {
    if (c == '\n') return true;
    if (line.size() == limit) return false;
    line.push_back(static_cast<char>(c));
  }
  return false;
}

bool read_header(std::istream& in, const std::string& path, CheckpointInfo& info, std::string& error) {
  nlohmann::ordered_json j;
  // A header line longer than this is not one of ours (they are a few hundred
  // bytes); reading on would let a damaged file claim any amount of memory.
  constexpr std::size_t kMaxHeaderBytes = 64 * 1024;
  if (!read_json_header(in, path, kMagicLine, "checkpoint", j, error, kMaxHeaderBytes)) return false;
  for (const std::string_view key : kHeaderKeys)
    if (!j.contains(std::string(key))) return damaged(path, "no \"" + std::string(key) + "\"", error);
  for (const auto& [key, value] : j.items()) {
    if (std::find(std::begin(kHeaderKeys), std::end(kHeaderKeys), key) == std::end(kHeaderKeys))
      return damaged(path, "unknown key \"" + key + "\"", error);
  }
  const nlohmann::ordered_json &scene = j["scene"], &hash = j["scene_hash"], &settings = j["settings"],
                               &spp = j["spp_done"];
  if (!scene.is_string()) return damaged(path, "\"scene\" must be a string, got " + shown(scene), error);
  if (!hash.is_string() || !is_hash(hash.get<std::string>()))
    return damaged(path, "\"scene_hash\" must be 16 hexadecimal digits, got " + shown(hash), error);
  if (!settings.is_object()) return damaged(path, "\"settings\" must be an object, got " + shown(settings), error);
  if (!spp.is_number_integer())
    return damaged(path, "\"spp_done\" must be an integer, got " + shown(spp), error);
  const bool negative = !spp.is_number_unsigned() && spp.get<int64_t>() < 0;
  if (negative || spp.get<uint64_t>() > static_cast<uint64_t>(kMaxCheckpointSpp))
    return damaged(path, "\"spp_done\" must be in [0, " + std::to_string(kMaxCheckpointSpp) + "], got " + spp.dump(),
                   error);
  info.scene = scene.get<std::string>();
  info.scene_hash = hash.get<std::string>();
  info.settings = settings;
  info.spp_done = static_cast<int>(spp.get<int64_t>());
  return true;
}

}  // namespace

bool read_json_header(std::istream& in, const std::string& path, const std::string& magic_line, const std::string& kind,
                      nlohmann::ordered_json& out, std::string& error, std::size_t max_bytes) {
  std::string magic, json;
  if (!read_line(in, magic, 64) || magic != magic_line) {
    error = "'" + path + "' is not a pathtracer " + kind;
    return false;
  }
  if (!read_line(in, json, max_bytes)) {
    return damaged_file(path, kind,
                        in.eof() ? "the file ends inside its second line (truncated)"
                                 : "its second line is longer than " + std::to_string(max_bytes) + " bytes",
                        error);
  }
  if (nesting_depth(json) > kMaxHeaderDepth)
    return damaged_file(path, kind, "its JSON nests deeper than " + std::to_string(kMaxHeaderDepth) + " levels",
                        error);
  out = nlohmann::ordered_json::parse(json, nullptr, false);
  if (out.is_discarded() || !out.is_object())
    return damaged_file(path, kind, "its second line is not a JSON object", error);
  return true;
}

std::string scene_content_hash(const std::string& path, const std::string& extra, std::string& error) {
  if (const std::string why = why_unreadable(path); !why.empty()) {
    error = "cannot read '" + path + "': " + why;
    return {};
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    error = "cannot read '" + path + "'";
    return {};
  }
  const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  uint64_t h = fnv1a(0xcbf29ce484222325ull, bytes.data(), bytes.size());
  h = fnv1a(h, "\0", 1);
  h = fnv1a(h, extra.data(), extra.size());
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

bool write_checkpoint(std::ostream& out, const CheckpointInfo& info, const Film& film) {
  const nlohmann::ordered_json header = {{"scene", info.scene},
                                         {"scene_hash", info.scene_hash},
                                         {"settings", info.settings},
                                         {"spp_done", info.spp_done}};
  // Replace, not throw, on a scene path that is not UTF-8 (a file name can be any bytes).
  out << kMagicLine << '\n' << header.dump(-1, ' ', false, nlohmann::ordered_json::error_handler_t::replace) << '\n';
  return film.write_state(out);
}

bool write_checkpoint(const std::string& path, const CheckpointInfo& info, const Film& film, std::string& error) {
  return write_atomically(
      path,
      [&](const std::string& tmp, std::string& why) {
        std::ofstream out(tmp, std::ios::binary);
        if (!out) {
          why = stream_write_error();
          return false;
        }
        if (!write_checkpoint(out, info, film)) {
          why = stream_write_error();
          return false;
        }
        out.close();  // flushes: a full disk often shows only here
        if (!out) why = stream_write_error();
        return static_cast<bool>(out);
      },
      error);
}

bool read_checkpoint_info(std::istream& in, const std::string& path, CheckpointInfo& info, std::string& error) {
  CheckpointInfo header;
  if (!read_header(in, path, header, error)) return false;
  info = std::move(header);
  return true;
}

bool read_checkpoint_info(const std::string& path, CheckpointInfo& info, std::string& error) {
  // A FIFO would block the open until a writer comes; a device never ends.
  if (const std::string why = why_unreadable(path); !why.empty()) {
    error = "cannot open checkpoint '" + path + "': " + why;
    return false;
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    error = "cannot open checkpoint '" + path + "'";
    return false;
  }
  return read_checkpoint_info(in, path, info, error);
}

bool read_checkpoint(std::istream& in, const std::string& path, CheckpointInfo& info, Film& film, std::string& error) {
  CheckpointInfo header;
  if (!read_header(in, path, header, error)) return false;
  Film state(film.width(), film.height(), film.crop(), film.aovs());
  std::string why;
  if (!state.read_state(in, why)) {
    error = "'" + path + "': " + why;
    return false;
  }
  // Checkpoints are written between complete passes: no pixel holds more
  // samples than spp_done (the binary view adds one per pass, so fewer).
  const PixelRect& c = state.crop();
  for (int y = c.y0; y < c.y1; ++y)
    for (int x = c.x0; x < c.x1; ++x)
      if (state.sum(x, y).samples > static_cast<uint64_t>(header.spp_done)) {
        error = "'" + path + "': its film state holds " + std::to_string(state.sum(x, y).samples) +
                " samples in pixel (" + std::to_string(x) + ", " + std::to_string(y) + "), more than the header's " +
                "spp_done " + std::to_string(header.spp_done) + " (the two do not belong together)";
        return false;
      }
  film = std::move(state);
  info = std::move(header);
  return true;
}

bool read_checkpoint(const std::string& path, CheckpointInfo& info, Film& film, std::string& error) {
  // A FIFO would block the open until a writer comes; a device never ends.
  if (const std::string why = why_unreadable(path); !why.empty()) {
    error = "cannot open checkpoint '" + path + "': " + why;
    return false;
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    error = "cannot open checkpoint '" + path + "'";
    return false;
  }
  return read_checkpoint(in, path, info, film, error);
}

std::string checkpoint_mismatch(const CheckpointInfo& saved, const CheckpointInfo& current) {
  if (saved.scene_hash != current.scene_hash)
    return "the scene differs: the checkpoint was made from '" + saved.scene + "' (hash " + saved.scene_hash +
           "), this run renders '" + current.scene + "' (hash " + current.scene_hash +
           "); the file's content or the --set overrides changed";
  std::string diffs;
  for (const auto& [key, value] : current.settings.items()) {
    const auto it = saved.settings.find(key);
    const std::string was = it == saved.settings.end() ? "(absent)" : it->dump();
    if (was != value.dump()) diffs += (diffs.empty() ? "" : ", ") + key + " " + was + " -> " + value.dump();
  }
  for (const auto& [key, value] : saved.settings.items())
    if (!current.settings.contains(key)) diffs += (diffs.empty() ? "" : ", ") + key + " " + value.dump() + " -> (absent)";
  return diffs.empty() ? std::string() : "the settings differ from the checkpoint's: " + diffs;
}

}  // namespace pt
