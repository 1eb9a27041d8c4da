// Cryptomatte's ids and header (render/film/cryptomatte.h): MurmurHash3_x86_32
// against published test vectors and against what Blender 3.4 writes, the
// uint32_to_float32 conversion, the layer names and the manifest.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <map>

#include <nlohmann/json.hpp>

#include "render/film/cryptomatte.h"

namespace pt {
namespace {

TEST(Cryptomatte, MurmurHash3MatchesTheReferenceVectors) {
  // Austin Appleby's MurmurHash3_x86_32; every tail length (0 to 3 bytes after the blocks).
  EXPECT_EQ(murmurhash3_32("", 0), 0u);
  EXPECT_EQ(murmurhash3_32("", 1), 0x514e28b7u);
  EXPECT_EQ(murmurhash3_32("", 0xffffffffu), 0x81f16f39u);
  EXPECT_EQ(murmurhash3_32("abc", 0), 0xb3dd93fau);
  constexpr uint32_t kSeed = 0x9747b28cu;
  EXPECT_EQ(murmurhash3_32("a", kSeed), 0x7fa09ea6u);
  EXPECT_EQ(murmurhash3_32("ab", kSeed), 0x74875592u);
  EXPECT_EQ(murmurhash3_32("abc", kSeed), 0xc84a62ddu);
  EXPECT_EQ(murmurhash3_32("abcd", kSeed), 0xf0478627u);
  EXPECT_EQ(murmurhash3_32("Hello, world!", kSeed), 0x24884cbau);
  EXPECT_EQ(murmurhash3_32("The quick brown fox jumps over the lazy dog", kSeed), 0x2fa826cdu);
}

TEST(Cryptomatte, IdsAndKeysAreBlenders) {
  // Blender 3.4 (Cycles) rendering its default UV sphere "Sphere" writes the
  // manifest {"Sphere":"e5e9b0db"} under the key 542cafa for the type
  // "ViewLayer.CryptoObject" (read with oiiotool from its multilayer EXR).
  EXPECT_EQ(cryptomatte_hex(cryptomatte_id("Sphere")), "e5e9b0db");
  ImageMetadata m;
  add_cryptomatte_metadata(m, "ViewLayer.CryptoObject", {"Sphere"});
  std::map<std::string, std::string> attributes(m.strings.begin(), m.strings.end());
  EXPECT_EQ(attributes["cryptomatte/542cafa/name"], "ViewLayer.CryptoObject");
  EXPECT_EQ(attributes["cryptomatte/542cafa/hash"], "MurmurHash3_32");
  EXPECT_EQ(attributes["cryptomatte/542cafa/conversion"], "uint32_to_float32");
  EXPECT_EQ(attributes["cryptomatte/542cafa/manifest"], R"({"Sphere":"e5e9b0db"})");
  EXPECT_EQ(m.strings.size(), 4u);
}

TEST(Cryptomatte, FloatConversionKeepsTheExponentInRange) {
  // Exponent 0 (zero, denormals) becomes 1 and 255 (infinities, NaN) becomes
  // 254; sign and mantissa are kept.
  EXPECT_EQ(std::bit_cast<uint32_t>(cryptomatte_float(0u)), 0x00800000u);
  EXPECT_EQ(std::bit_cast<uint32_t>(cryptomatte_float(0x807fffffu)), 0x80ffffffu);
  EXPECT_EQ(std::bit_cast<uint32_t>(cryptomatte_float(0x7f800000u)), 0x7f000000u);
  EXPECT_EQ(std::bit_cast<uint32_t>(cryptomatte_float(0xffc00001u)), 0xff400001u);
  EXPECT_EQ(std::bit_cast<uint32_t>(cryptomatte_float(0x3f800000u)), 0x3f800000u);  // in range: unchanged
  for (uint32_t h = 0; h < 0xff000000u; h += 0x00ff0f0fu) {
    const float f = cryptomatte_float(h);
    EXPECT_TRUE(std::isnormal(f)) << std::hex << h;  // never 0, denormal, infinite or NaN
  }
}

TEST(Cryptomatte, LayerNamesAndManifest) {
  EXPECT_EQ(cryptomatte_layer_names("CryptoObject", 6),
            (std::vector<std::string>{"CryptoObject00", "CryptoObject01", "CryptoObject02"}));
  EXPECT_EQ(cryptomatte_layer_names("CryptoMaterial", 3),
            (std::vector<std::string>{"CryptoMaterial00", "CryptoMaterial01"}));
  EXPECT_EQ(cryptomatte_layer_names("X", 16).back(), "X07");
  ImageMetadata m;
  add_cryptomatte_metadata(m, "CryptoMaterial", {"floor \"tiles\"", "glass", "glass"});
  const auto manifest = nlohmann::json::parse(m.strings.back().second);
  ASSERT_EQ(manifest.size(), 2u);  // names once, JSON-escaped
  EXPECT_EQ(manifest["floor \"tiles\""], cryptomatte_hex(cryptomatte_id("floor \"tiles\"")));
  EXPECT_EQ(manifest["glass"], cryptomatte_hex(cryptomatte_id("glass")));
  EXPECT_EQ(m.strings.front().first.substr(0, 12), "cryptomatte/");
  EXPECT_EQ(m.strings.front().first.size(), std::string("cryptomatte/1234567/name").size());
}

}  // namespace
}  // namespace pt
