// Arbitrary output variables (AOVs): the extra layers a render can write
// beside the beauty (docs/output.md). Each has a fixed name, channel names, a
// default storage type and an accumulation kind; none is computed or stored
// unless requested.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/color.h"
#include "core/math.h"
#include "io/layered_image.h"
#include "render/film/cryptomatte.h"

namespace pt {

enum class AovType : uint8_t {
  Albedo,            // albedo.R/G/B: the first hit's diffuse reflectance (see docs/output.md)
  Normal,            // N.X/Y/Z: world-space shading normal of the first hit, facing the camera
  Position,          // P.X/Y/Z: world-space position of the first hit
  Depth,             // Z: camera-space depth of the first hit along the view axis
  ObjectId,          // IndexOB: 1 + shape index of the first hit, 0 for none
  MaterialId,        // IndexMA: 1 + material index of the first hit, 0 for none
  Emission,          // emission.R/G/B (path, whitted): emitters and the background seen directly by the camera
  DiffuseDirect,     // diffuse_direct.R/G/B (path, whitted)
  DiffuseIndirect,   // diffuse_indirect.R/G/B (path)
  SpecularDirect,    // specular_direct.R/G/B (path, whitted)
  SpecularIndirect,  // specular_indirect.R/G/B (path, whitted)
  Variance,          // variance.R/G/B: variance of the pixel mean, per channel
  Samples,           // samples: the pixel's sample count
  NonFinite,         // nonfinite: 1 where a NaN or infinite sample was caught, else 0
  // Last, so the numbers of the others (in checkpoints) stay as they were.
  Ambient,           // ambient.R/G/B (whitted): the classic ambient term at the first hit
  CryptoObject,      // CryptoObject00.r/g/b/a, ...: Cryptomatte of the first hit's object name
  CryptoMaterial,    // CryptoMaterial00.r/g/b/a, ...: Cryptomatte of the first hit's material name
};

// How a layer's samples combine into the pixel value.
enum class Accumulation : uint8_t {
  FilteredAverage,  // sum of weight * value / sum of weights, with the beauty's filter weights
  FirstSample,      // the value of the pixel's first sample (lowest sample index): ids, P, Z
  Sum,              // sums kept as they are (variance: sum and sum of squares; samples)
  Max,              // the largest value seen (the non-finite mask)
  Ranked,           // Cryptomatte: per id, the sum of the weights of the samples that hit it; the ids
                    // ranked by it (render/film/cryptomatte.h); the smallest ids kept (film.cpp: add_ranked)
};

struct AovInfo {
  AovType type;
  const char* name;                    // as given to --aov
  int channels;                        // 1 or 3; Ranked: 2 per rank (aov_channel_names)
  // Channel names after "name."; a single channel with suffix "" is named
  // `name` alone (Z: Blender reads it as its Depth pass, Nuke as depth.Z).
  std::array<const char*, 3> suffix;
  ChannelType default_type;
  Accumulation accumulation;
  // Its state per pixel in the film: exact sums (FilteredAverage, Sum; see
  // render/film/exact_sum.h; Ranked: per rank, the id's bits and its weight)
  // and plain values (FirstSample: the values and a set flag; Max: the value).
  int sums;
  int values;
  bool lighting;                       // a part of the beauty's lighting split, filled by the integrator
                                       // (which integrator fills which: IntegratorInfo::aovs)
};

// Every AOV, in the order the film stores and the EXR lists them.
const std::vector<AovInfo>& aov_catalogue();
const AovInfo& aov_info(AovType type);
std::vector<std::string> aov_names();

// A set of AOV types, one bit per AovType.
using AovSet = uint32_t;
constexpr AovSet aov_bit(AovType type) { return AovSet{1} << static_cast<unsigned>(type); }
template <class... Types>
constexpr AovSet aov_set(Types... types) {
  return (AovSet{0} | ... | aov_bit(types));
}
// What the render loop fills for every integrator: the first hit's geometry
// and the pixel statistics.
// The AOVs that need the camera ray's first hit (render_loop.h: first_hit_aovs).
inline constexpr AovSet kGeometryAovs =
    aov_set(AovType::Albedo, AovType::Normal, AovType::Position, AovType::Depth, AovType::ObjectId,
            AovType::MaterialId, AovType::CryptoObject, AovType::CryptoMaterial);
inline constexpr AovSet kRenderLoopAovs =
    kGeometryAovs | aov_set(AovType::Variance, AovType::Samples, AovType::NonFinite);

struct AovRequest {
  AovType type;
  ChannelType channel_type;
  int ranks = 0;  // Ranked (Cryptomatte) layers: the ids kept per pixel, 1 .. kCryptomatteMaxRanks; else 0
};

// Exact sums per pixel the film keeps for `r` (Ranked: an id and a weight per
// rank), and plain values.
int aov_state_sums(const AovRequest& r);
int aov_state_values(const AovRequest& r);
// The full channel names `r` writes, in order: "albedo.R", ..., "IndexOB.X",
// "Z", and for a Ranked layer "CryptoObject00.r", "CryptoObject00.g", ...
// (lower case, as Blender writes them; DWA compression keeps them lossless).
std::vector<std::string> aov_channel_names(const AovRequest& r);
// aov_channel_names(r).size(): Ranked layers have 4 channels per two ranks (the last pair is 0 for odd ranks).
int aov_channel_count(const AovRequest& r);

// The depth (Z) of a camera ray that hits nothing: Blender's (Cycles writes
// 1e10 for the background), finite so that compositing arithmetic (Z
// combine, defocus, min/max) never meets an infinity.
inline constexpr float kBackgroundDepth = 1e10f;

// The name that sets the beauty's (R, G, B, A) pixel type in an AOV list
// ("beauty:half"); the beauty is always written, as float unless asked.
constexpr const char* kBeautyName = "beauty";

// Parses "--aov" lists: comma-separated names, each optionally followed by
// ":half" or ":float" (e.g. "albedo:half,N,Z:float,beauty:half"). Duplicates are
// an error. The result is sorted in catalogue order; `beauty` gets the type
// given to "beauty" (Float if it is not named). Returns false with `error`
// listing the valid names for an unknown name.
// Ranked layers get `ranks` ranks and are float only.
bool parse_aov_list(const std::string& list, std::vector<AovRequest>& out, ChannelType& beauty, std::string& error,
                    int ranks = kCryptomatteDefaultRanks);

// What one camera sample contributes to the AOVs besides its radiance. The
// render loop fills the geometric part (only when a geometric AOV is
// requested), the integrator the lighting split (only when asked).
struct AovSample {
  bool hit = false;
  RGB albedo;
  Vec3f normal, position;
  float depth = kBackgroundDepth;    // for a ray that hits nothing: kBackgroundDepth
  uint32_t object = 0, material = 0; // 1 + index, 0 = nothing hit
  float crypto_object = 0.0f, crypto_material = 0.0f;  // Cryptomatte ids (cryptomatte.h); 0 = nothing hit
  RGB emission, diffuse_direct, diffuse_indirect, specular_direct, specular_indirect, ambient;
};

}  // namespace pt
