// Attributes written into an image's header: EXR header attributes (typed) and,
// for PNG/JPEG, text entries where the format has them (PPM has none).
// Names follow OpenEXR's standard attributes where one exists (worldToCamera,
// worldToNDC, chromaticities, ...) and use the "pathtracer:" prefix otherwise.
// Every EXR also carries chromaticities (Rec.709 / sRGB primaries, D65 white),
// written by the EXR writer itself.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace pt {

// Every EXR's chromaticities attribute: CIE xy of the Rec.709 red, green and
// blue primaries and of D65 (both EXR writers: imagelib/oiio/exr_writer.cpp,
// io/exr_uncompressed.cpp).
inline constexpr std::array<float, 8> kExrChromaticities = {0.64f, 0.33f, 0.30f, 0.60f, 0.15f, 0.06f, 0.3127f, 0.3290f};

struct ImageMetadata {
  using Matrix = std::array<float, 16>;  // row-major, as OpenEXR's M44f
  std::vector<std::pair<std::string, std::string>> strings;
  std::vector<std::pair<std::string, int>> ints;
  std::vector<std::pair<std::string, float>> floats;
  std::vector<std::pair<std::string, Matrix>> matrices;

  void set(const std::string& name, const std::string& value) { strings.emplace_back(name, value); }
  void set(const std::string& name, const char* value) { strings.emplace_back(name, value); }
  void set(const std::string& name, int value) { ints.emplace_back(name, value); }
  void set(const std::string& name, float value) { floats.emplace_back(name, value); }
  void set(const std::string& name, const Matrix& value) { matrices.emplace_back(name, value); }
};

// What the command line knows about a render, for the image headers
// (docs/output.md lists the attribute names). Filled by the application.
struct RenderStamp {
  double render_seconds = 0.0;
  int spp = 0;
  uint64_t seed = 0;
  std::string backend;     // the accelerator's description
  std::string integrator;
  std::string sampler;  // the path integrator's; the classic integrators use the pixel grid (docs/rendering.md)
  std::string filter;   // pixel filter
  std::string light_sampler;  // the path integrator's light choice ("bvh", "power"); "all" (whitted), "none" (views)
  int light_guiding = 0;      // the path integrator's pre-pass paths per pixel (render.light_guiding); 0: off
  int path_guiding = 0;       // the same for its path guiding (render.path_guiding); 0: off
  float shadow_terminator_offset = 0.0f;  // render.shadow_terminator_geometry_offset; 0: off
  int max_depth = 0;
  float clamp = 0.0f;   // firefly clamp on each sample's radiance; 0: off
  bool film_transparent = false;  // the background was left out of the image (alpha 0)
  std::string software_version;
  // A signal (SIGINT, SIGTERM) stopped the render: some pixels have fewer
  // samples than others. Not set when a time budget runs out: that is the
  // requested end, and every pixel has the complete passes.
  bool partial = false;
  bool has_camera = false;
  ImageMetadata::Matrix world_to_camera{};
  std::optional<ImageMetadata::Matrix> world_to_ndc;  // none for a spherical camera
};

// Adds `stamp` to `metadata`: pathtracer:renderTime, pathtracer:clamp
// (float; clamp 0 means off), pathtracer:spp, pathtracer:maxDepth,
// pathtracer:partial and pathtracer:filmTransparent (int 0/1), pathtracer:seed, pathtracer:backend,
// pathtracer:integrator, pathtracer:sampler, pathtracer:filter, pathtracer:lightSampler,
// pathtracer:version (strings), pathtracer:lightGuiding and pathtracer:pathGuiding (int), pathtracer:shadowTerminatorOffset (float), and worldToCamera / worldToNDC when has_camera
// (worldToNDC only for a camera that has one: not the spherical camera).
inline void add_render_stamp(ImageMetadata& metadata, const RenderStamp& stamp) {
  metadata.set("pathtracer:renderTime", static_cast<float>(stamp.render_seconds));
  metadata.set("pathtracer:spp", stamp.spp);
  metadata.set("pathtracer:partial", stamp.partial ? 1 : 0);
  metadata.set("pathtracer:seed", std::to_string(stamp.seed));  // 64 bits: a string
  metadata.set("pathtracer:backend", stamp.backend);
  metadata.set("pathtracer:integrator", stamp.integrator);
  metadata.set("pathtracer:sampler", stamp.sampler);
  metadata.set("pathtracer:filter", stamp.filter);
  metadata.set("pathtracer:lightSampler", stamp.light_sampler);
  metadata.set("pathtracer:lightGuiding", stamp.light_guiding);
  metadata.set("pathtracer:pathGuiding", stamp.path_guiding);
  metadata.set("pathtracer:shadowTerminatorOffset", stamp.shadow_terminator_offset);
  metadata.set("pathtracer:maxDepth", stamp.max_depth);
  metadata.set("pathtracer:clamp", stamp.clamp);
  metadata.set("pathtracer:filmTransparent", stamp.film_transparent ? 1 : 0);
  metadata.set("pathtracer:version", stamp.software_version);
  if (stamp.has_camera) {
    metadata.set("worldToCamera", stamp.world_to_camera);
    if (stamp.world_to_ndc) metadata.set("worldToNDC", *stamp.world_to_ndc);
  }
}

}  // namespace pt
