#include "render/film/aov.h"

#include <algorithm>

namespace pt {

namespace {

using A = Accumulation;
constexpr ChannelType kHalf = ChannelType::Half, kFloat = ChannelType::Float;

// Defaults: half where 11 bits of mantissa are plenty (albedo, normals, the
// mask); float for positions, depths, ids and radiance-valued layers.
const std::vector<AovInfo> kCatalogue = {
    {AovType::Albedo, "albedo", 3, {"R", "G", "B"}, kHalf, A::FilteredAverage, 3, 0, false},
    {AovType::Normal, "N", 3, {"X", "Y", "Z"}, kHalf, A::FilteredAverage, 3, 0, false},
    {AovType::Position, "P", 3, {"X", "Y", "Z"}, kFloat, A::FirstSample, 0, 4, false},
    {AovType::Depth, "Z", 1, {"", "", ""}, kFloat, A::FirstSample, 0, 2, false},
    {AovType::ObjectId, "IndexOB", 1, {"X", "", ""}, kFloat, A::FirstSample, 0, 2, false},
    {AovType::MaterialId, "IndexMA", 1, {"X", "", ""}, kFloat, A::FirstSample, 0, 2, false},
    {AovType::Emission, "emission", 3, {"R", "G", "B"}, kFloat, A::FilteredAverage, 3, 0, true},
    {AovType::DiffuseDirect, "diffuse_direct", 3, {"R", "G", "B"}, kFloat, A::FilteredAverage, 3, 0, true},
    {AovType::DiffuseIndirect, "diffuse_indirect", 3, {"R", "G", "B"}, kFloat, A::FilteredAverage, 3, 0, true},
    {AovType::SpecularDirect, "specular_direct", 3, {"R", "G", "B"}, kFloat, A::FilteredAverage, 3, 0, true},
    {AovType::SpecularIndirect, "specular_indirect", 3, {"R", "G", "B"}, kFloat, A::FilteredAverage, 3, 0, true},
    {AovType::Variance, "variance", 3, {"R", "G", "B"}, kFloat, A::Sum, 6, 0, false},
    {AovType::Samples, "samples", 1, {"X", "", ""}, kFloat, A::Sum, 0, 0, false},
    {AovType::NonFinite, "nonfinite", 1, {"X", "", ""}, kHalf, A::Max, 0, 1, false},
    {AovType::Ambient, "ambient", 3, {"R", "G", "B"}, kFloat, A::FilteredAverage, 3, 0, true},
    // Ids are 32-bit patterns: float only. Per rank two sums: the id's bits and its weight.
    {AovType::CryptoObject, "CryptoObject", 2, {"", "", ""}, kFloat, A::Ranked, 2, 0, false},
    {AovType::CryptoMaterial, "CryptoMaterial", 2, {"", "", ""}, kFloat, A::Ranked, 2, 0, false},
};

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t");
  if (b == std::string::npos) return {};
  return s.substr(b, s.find_last_not_of(" \t") - b + 1);
}

}  // namespace

const std::vector<AovInfo>& aov_catalogue() { return kCatalogue; }

const AovInfo& aov_info(AovType type) { return kCatalogue[static_cast<std::size_t>(type)]; }

int aov_state_sums(const AovRequest& r) {
  const AovInfo& info = aov_info(r.type);
  return info.accumulation == Accumulation::Ranked ? info.sums * r.ranks : info.sums;
}

int aov_state_values(const AovRequest& r) { return aov_info(r.type).values; }

int aov_channel_count(const AovRequest& r) {
  const AovInfo& info = aov_info(r.type);
  return info.accumulation == Accumulation::Ranked ? 4 * ((r.ranks + 1) / 2) : info.channels;
}

std::vector<std::string> aov_channel_names(const AovRequest& r) {
  const AovInfo& info = aov_info(r.type);
  std::vector<std::string> names;
  if (info.accumulation == Accumulation::Ranked) {
    for (const std::string& layer : cryptomatte_layer_names(info.name, r.ranks))
      for (const char* c : {".r", ".g", ".b", ".a"}) names.push_back(layer + c);
  } else if (info.channels == 1 && info.suffix[0][0] == '\0') {
    names.emplace_back(info.name);
  } else {
    for (int c = 0; c < info.channels; ++c) names.push_back(std::string(info.name) + "." + info.suffix[c]);
  }
  return names;
}

std::vector<std::string> aov_names() {
  std::vector<std::string> names;
  for (const AovInfo& info : kCatalogue) names.emplace_back(info.name);
  return names;
}

bool parse_aov_list(const std::string& list, std::vector<AovRequest>& out, ChannelType& beauty, std::string& error,
                    int ranks) {
  std::vector<AovRequest> result;
  ChannelType beauty_type = ChannelType::Float;
  bool beauty_named = false;
  std::size_t start = 0;
  while (start <= list.size()) {
    const std::size_t comma = std::min(list.find(',', start), list.size());
    const std::string item = trim(list.substr(start, comma - start));
    start = comma + 1;
    if (item.empty()) {
      if (comma == list.size() && (!result.empty() || beauty_named)) break;  // a trailing comma
      error = "empty AOV name in '" + list + "'";
      return false;
    }
    const std::size_t colon = item.find(':');
    const std::string name = trim(item.substr(0, colon));
    const AovInfo* info = nullptr;
    for (const AovInfo& i : kCatalogue)
      if (name == i.name) info = &i;
    if (info == nullptr && name != kBeautyName) {
      error = "unknown AOV '" + name + "'; valid names are:";
      for (const AovInfo& i : kCatalogue) error += std::string(" ") + i.name;
      error += std::string(" (and ") + kBeautyName + ", to choose its type: " + kBeautyName + ":half)";
      return false;
    }
    ChannelType type = info != nullptr ? info->default_type : ChannelType::Float;
    if (colon != std::string::npos) {
      const std::string type_name = trim(item.substr(colon + 1));
      if (type_name == "half") {
        type = ChannelType::Half;
      } else if (type_name == "float") {
        type = ChannelType::Float;
      } else {
        error = "AOV '" + name + "': unknown pixel type '" + type_name + "' (half or float)";
        return false;
      }
    }
    if (info == nullptr) {  // the beauty: only its type
      if (beauty_named) {
        error = std::string("AOV '") + kBeautyName + "' is requested more than once";
        return false;
      }
      beauty_named = true;
      beauty_type = type;
      continue;
    }
    const bool ranked = info->accumulation == Accumulation::Ranked;
    if (ranked && type != ChannelType::Float) {
      error = "AOV '" + name + "' is float only (its ids are 32-bit patterns)";
      return false;
    }
    const AovRequest request{info->type, type, ranked ? ranks : 0};
    for (const AovRequest& r : result)
      if (r.type == request.type) {
        error = "AOV '" + name + "' is requested more than once";
        return false;
      }
    result.push_back(request);
  }
  std::sort(result.begin(), result.end(),
            [](const AovRequest& a, const AovRequest& b) { return a.type < b.type; });
  out = std::move(result);
  beauty = beauty_type;
  return true;
}

}  // namespace pt
