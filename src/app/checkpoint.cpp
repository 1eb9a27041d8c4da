#include "app/checkpoint.h"

#include <cstdio>
#include <fstream>
#include <iterator>

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

bool read_header(std::istream& in, const std::string& path, CheckpointInfo& info, std::string& error) {
  std::string magic, json;
  if (!std::getline(in, magic) || magic != kMagicLine) {
    error = "'" + path + "' is not a pathtracer checkpoint";
    return false;
  }
  if (!std::getline(in, json)) {
    error = "'" + path + "': truncated checkpoint header";
    return false;
  }
  const nlohmann::ordered_json j = nlohmann::ordered_json::parse(json, nullptr, false);
  if (j.is_discarded() || !j.is_object() || !j.contains("scene") || !j.contains("scene_hash") ||
      !j.contains("settings") || !j.contains("spp_done") || !j["spp_done"].is_number_integer()) {
    error = "'" + path + "': damaged checkpoint header";
    return false;
  }
  info.scene = j["scene"].get<std::string>();
  info.scene_hash = j["scene_hash"].get<std::string>();
  info.settings = j["settings"];
  info.spp_done = j["spp_done"].get<int>();
  return true;
}

}  // namespace

std::string scene_content_hash(const std::string& path, const std::string& extra, std::string& error) {
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

bool write_checkpoint(const std::string& path, const CheckpointInfo& info, const Film& film, std::string& error) {
  const nlohmann::ordered_json header = {{"scene", info.scene},
                                         {"scene_hash", info.scene_hash},
                                         {"settings", info.settings},
                                         {"spp_done", info.spp_done}};
  return write_atomically(
      path,
      [&](const std::string& tmp, std::string& why) {
        std::ofstream out(tmp, std::ios::binary);
        out << kMagicLine << '\n' << header.dump() << '\n';
        if (!film.write_state(out)) {
          why = "write failed";
          return false;
        }
        out.close();
        if (!out) why = "write failed";
        return static_cast<bool>(out);
      },
      error);
}

bool read_checkpoint_info(const std::string& path, CheckpointInfo& info, std::string& error) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    error = "cannot open checkpoint '" + path + "'";
    return false;
  }
  return read_header(in, path, info, error);
}

bool read_checkpoint(const std::string& path, CheckpointInfo& info, Film& film, std::string& error) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    error = "cannot open checkpoint '" + path + "'";
    return false;
  }
  if (!read_header(in, path, info, error)) return false;
  std::string why;
  if (!film.read_state(in, why)) {
    error = "'" + path + "': " + why;
    return false;
  }
  return true;
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
