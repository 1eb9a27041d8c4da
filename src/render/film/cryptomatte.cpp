#include "render/film/cryptomatte.h"

#include <algorithm>
#include <bit>
#include <cstdio>
#include <cstring>

#include <nlohmann/json.hpp>

namespace pt {

namespace {

constexpr uint32_t rotl32(uint32_t x, int r) { return (x << r) | (x >> (32 - r)); }

uint32_t mix_block(uint32_t k) {
  k *= 0xcc9e2d51u;
  k = rotl32(k, 15);
  return k * 0x1b873593u;
}

std::string hex8(uint32_t bits) {
  char text[9];
  std::snprintf(text, sizeof text, "%08x", bits);
  return text;
}

}  // namespace

uint32_t murmurhash3_32(std::string_view bytes, uint32_t seed) {
  const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
  const std::size_t blocks = bytes.size() / 4;
  uint32_t h = seed;
  for (std::size_t i = 0; i < blocks; ++i) {
    const uint32_t k = static_cast<uint32_t>(data[4 * i]) | static_cast<uint32_t>(data[4 * i + 1]) << 8 |
                       static_cast<uint32_t>(data[4 * i + 2]) << 16 | static_cast<uint32_t>(data[4 * i + 3]) << 24;
    h ^= mix_block(k);
    h = rotl32(h, 13);
    h = h * 5u + 0xe6546b64u;
  }
  const unsigned char* tail = data + 4 * blocks;
  uint32_t k = 0;
  switch (bytes.size() & 3u) {
    case 3: k ^= static_cast<uint32_t>(tail[2]) << 16; [[fallthrough]];
    case 2: k ^= static_cast<uint32_t>(tail[1]) << 8; [[fallthrough]];
    case 1: k ^= tail[0]; h ^= mix_block(k); break;
    default: break;
  }
  h ^= static_cast<uint32_t>(bytes.size());
  h ^= h >> 16;
  h *= 0x85ebca6bu;
  h ^= h >> 13;
  h *= 0xc2b2ae35u;
  h ^= h >> 16;
  return h;
}

float cryptomatte_float(uint32_t hash) {
  const uint32_t exponent = std::clamp<uint32_t>((hash >> 23) & 0xffu, 1u, 254u);
  return std::bit_cast<float>((hash & 0x807fffffu) | exponent << 23);
}

float cryptomatte_id(std::string_view name) { return cryptomatte_float(murmurhash3_32(name)); }

std::string cryptomatte_hex(float id) { return hex8(std::bit_cast<uint32_t>(id)); }

std::vector<std::string> cryptomatte_layer_names(const std::string& type, int ranks) {
  std::vector<std::string> names;
  for (int layer = 0; 2 * layer < ranks; ++layer) {
    char index[16];
    std::snprintf(index, sizeof index, "%02d", layer);
    names.push_back(type + index);
  }
  return names;
}

void add_cryptomatte_metadata(ImageMetadata& metadata, const std::string& type, const std::vector<std::string>& names) {
  const std::string prefix = "cryptomatte/" + hex8(murmurhash3_32(type)).substr(0, 7) + "/";
  nlohmann::ordered_json manifest = nlohmann::ordered_json::object();
  for (const std::string& name : names) manifest[name] = cryptomatte_hex(cryptomatte_id(name));
  metadata.set(prefix + "name", type);
  metadata.set(prefix + "hash", "MurmurHash3_32");
  metadata.set(prefix + "conversion", "uint32_to_float32");
  // Names that are not valid UTF-8 are written with replacement characters.
  metadata.set(prefix + "manifest", manifest.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace));
}

}  // namespace pt
