// Cryptomatte (Psyop's specification 1.1.0, as Blender, Nuke's gizmo and
// Arnold read it; docs/output.md): every name a camera ray can hit (an
// object's, a material's) gets an id, the MurmurHash3_x86_32 of the name
// (seed 0) with its bits stored as a 32-bit float whose exponent is kept in
// [1, 254], so that no id is a NaN, an infinity, a denormal or zero (0 means
// "nothing"). The film ranks the ids of each pixel by coverage
// (render/film/film.h) and writes them as layers {type}00, {type}01, ...
// whose channels r, g, b, a are id, coverage, id, coverage; the header names
// each type with its hash, conversion and a manifest (name -> id).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "io/image_metadata.h"

namespace pt {

// The ranks a Cryptomatte type keeps per pixel when none is asked for (the
// specification's suggested default: three layers of two ranks).
constexpr int kCryptomatteDefaultRanks = 6;
constexpr int kCryptomatteMaxRanks = 16;

// MurmurHash3_x86_32 of `bytes` with `seed` (Austin Appleby's public-domain
// algorithm, little-endian blocks).
uint32_t murmurhash3_32(std::string_view bytes, uint32_t seed = 0);

// The specification's uint32_to_float32 conversion: the hash's bits with the
// exponent clamped to [1, 254].
float cryptomatte_float(uint32_t hash);
// The id of `name`: cryptomatte_float(murmurhash3_32(name)). Never 0.
float cryptomatte_id(std::string_view name);
// The 8 lower-case hex digits of the float's bits, as the manifest writes an id.
std::string cryptomatte_hex(float id);

// The layer names of a type with `ranks` ranks: "{type}00", "{type}01", ...
// (two ranks per layer).
std::vector<std::string> cryptomatte_layer_names(const std::string& type, int ranks);

// Adds the header attributes of one Cryptomatte type:
// cryptomatte/<key>/name = `type`, .../hash = MurmurHash3_32,
// .../conversion = uint32_to_float32, .../manifest = {"name": "hex", ...}
// (each of `names` once). The key is the first 7 hex digits of the type's hash
// (as Blender makes it).
void add_cryptomatte_metadata(ImageMetadata& metadata, const std::string& type, const std::vector<std::string>& names);

}  // namespace pt
