// What shards must share to be merged (shard_mismatch), and the image
// metadata they carry to the merge, as JSON.
#include <cmath>
#include <limits>

#include "app/shard_file.h"

namespace pt {
namespace {

using J = nlohmann::ordered_json;

std::string display_text(const DisplaySettings& d) {
  return std::string(kDisplayTransformNames[static_cast<int>(d.transform)]) + " exposure " +
         std::to_string(d.exposure) + (d.view.empty() ? "" : " view " + d.view) +
         (d.display.empty() ? "" : " display " + d.display) + (d.look.empty() ? "" : " look " + d.look) +
         (d.ocio_config.empty() ? "" : " config " + d.ocio_config);
}

void differ(std::string& out, const std::string& what, const std::string& a, const std::string& b) {
  if (a != b) out += (out.empty() ? "" : ", ") + what + " " + a + " vs " + b;
}

}  // namespace

std::string shard_mismatch(const ShardInfo& a, const ShardInfo& b) {
  std::string d;
  if (a.scene_hash != b.scene_hash)
    d += "the scene: '" + a.scene + "' (hash " + a.scene_hash + ") vs '" + b.scene + "' (hash " + b.scene_hash +
         "; the file's content or the --set overrides differ)";
  differ(d, "the scene's meshes, textures or environment: hash", a.assets_hash, b.assets_hash);
  differ(d, "version", a.version, b.version);
  for (const auto& [key, value] : a.settings.items()) {
    const auto it = b.settings.find(key);
    differ(d, key, value.dump(), it == b.settings.end() ? "(absent)" : it->dump());
  }
  for (const auto& [key, value] : b.settings.items())
    if (!a.settings.contains(key)) differ(d, key, "(absent)", value.dump());
  differ(d, "frame", std::to_string(a.width) + "x" + std::to_string(a.height),
         std::to_string(b.width) + "x" + std::to_string(b.height));
  differ(d, "target spp", std::to_string(a.target_spp), std::to_string(b.target_spp));
  differ(d, "window (the crop the tiles split)", a.window.text(), b.window.text());
  differ(d, "AOVs", a.aovs, b.aovs);
  differ(d, "Cryptomatte levels", std::to_string(a.cryptomatte_levels), std::to_string(b.cryptomatte_levels));
  differ(d, "display", display_text(a.display), display_text(b.display));
  return d;
}

J metadata_json(const ImageMetadata& m) {
  J strings = J::object(), ints = J::object(), floats = J::object(), matrices = J::object();
  for (const auto& [k, v] : m.strings) strings[k] = v;
  for (const auto& [k, v] : m.ints) ints[k] = v;
  for (const auto& [k, v] : m.floats) floats[k] = std::isfinite(v) ? J(v) : J(nullptr);
  for (const auto& [k, v] : m.matrices) matrices[k] = v;
  return {{"strings", strings}, {"ints", ints}, {"floats", floats}, {"matrices", matrices}};
}

bool metadata_from_json(const J& j, ImageMetadata& out) {
  if (!j.is_object() || j.size() != 4) return false;
  const J &strings = j.value("strings", J()), &ints = j.value("ints", J()), &floats = j.value("floats", J()),
          &matrices = j.value("matrices", J());
  if (!strings.is_object() || !ints.is_object() || !floats.is_object() || !matrices.is_object()) return false;
  ImageMetadata m;
  for (const auto& [k, v] : strings.items()) {
    if (!v.is_string()) return false;
    m.set(k, v.get<std::string>());
  }
  for (const auto& [k, v] : ints.items()) {
    if (!v.is_number_integer()) return false;
    m.set(k, v.get<int>());
  }
  for (const auto& [k, v] : floats.items()) {
    if (!v.is_number() && !v.is_null()) return false;
    m.set(k, v.is_null() ? std::numeric_limits<float>::quiet_NaN() : v.get<float>());
  }
  for (const auto& [k, v] : matrices.items()) {
    if (!v.is_array() || v.size() != 16) return false;
    ImageMetadata::Matrix matrix{};
    for (std::size_t i = 0; i < 16; ++i) {
      if (!v[i].is_number()) return false;
      matrix[i] = v[i].get<float>();
    }
    m.set(k, matrix);
  }
  out = std::move(m);
  return true;
}

}  // namespace pt
