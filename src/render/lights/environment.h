// An environment map: a latitude-longitude (equirectangular) image of the
// radiance arriving from every direction, importance-sampled.
//
// Orientation (docs/path-tracing.md): with the frame (s, t, up) of
// Frame::from_normal(up), a direction d has theta = angle(d, up) and
// psi = atan2(d . s, d . t); the image row is v = theta / pi (the top row is
// the zenith) and the column u = 1/2 + psi / (2 pi) + rotation / 360. For
// up = +Y that puts -Z at the image centre and +X at u = 3/4; a positive
// rotation turns the environment counter-clockwise seen from above.
//
// Lookups are nearest-texel (the radiance is piecewise constant over texels),
// so the sampling density, a 2D piecewise-constant distribution over texels
// weighted by luminance * sin(theta), is exactly proportional to the radiance's
// luminance wherever it is non-zero (pdf(d) = pdf(u, v) / (2 pi^2 sin theta)).
#pragma once

#include <memory>
#include <string>

#include "core/sampling.h"
#include "render/lights/light.h"
#include "render/textures/texture.h"
#include "scene/scene_description.h"

namespace pt {

class EnvironmentMap {
 public:
  EnvironmentMap(Texture image, Vec3f up, float rotation_deg, float intensity);

  // Reads the image (any format OpenImageIO reads; float images are linear).
  // A texel that is not finite, or that overflows once scaled by the
  // intensity (beyond 1e30), is refused with `error` naming it; negative
  // channels are clamped to 0, and `warning` (if given) then names the first
  // such texel and their count (docs/scene-format.md, "Environment").
  static std::unique_ptr<EnvironmentMap> load(const EnvironmentDesc& desc, std::string& error,
                                              const TextureLimits& limits = {}, std::string* warning = nullptr);

  // Radiance arriving from direction `dir` (pointing away from the scene; any
  // non-zero length: direction_to_uv normalises it).
  RGB radiance(Vec3f dir) const;
  // A direction drawn by the map's density and the radiance arriving along it;
  // s.pdf and s.L are exactly pdf(s.wi) and radiance(s.wi).
  bool sample(Vec2f u, LightSample& s) const;
  // Only the drawn direction (false where the draw has no density), for a
  // caller that evaluates its own density there (the light guide's mixture).
  bool sample_direction(Vec2f u, Vec3f& wi) const;
  float pdf(Vec3f dir) const;
  // The same from image coordinates (direction_to_uv), for a caller that has them:
  // the radiance, and the solid-angle density of sample() there.
  RGB radiance_at(Vec2f uv) const { return texel(uv) * intensity_; }
  float pdf_at(Vec2f uv) const;
  // Starts loading the texel at uv into the cache, for a radiance_at(uv) that
  // follows other work: a hint, no effect on any result. A sample's texel is a
  // random line of a table of megabytes (12 bytes a texel), whose load was most
  // of a guided sky sample's own time (docs/bench/sample-cost.md).
  void prefetch(Vec2f uv) const { __builtin_prefetch(&texel(uv)); }
  float power(float scene_radius) const;

  // The direction <-> image coordinate mapping described above (direction_to_uv
  // takes a direction of any non-zero length; radiance() and pdf() both map through it).
  Vec2f direction_to_uv(Vec3f dir) const;
  Vec3f uv_to_direction(Vec2f uv) const;
  // The image's size in texels (the sampling distribution's grid).
  int width() const { return image_.width(); }
  int height() const { return image_.height(); }
  // The radiance of texel (x, y) (x from the left, y from the top).
  RGB texel_radiance(int x, int y) const { return image_.texel(x, y) * intensity_; }

 private:
  const RGB& texel(Vec2f uv) const;

  Texture image_;
  Frame frame_;
  float u_offset_;
  float intensity_;
  Distribution2D distribution_;
  float mean_luminance_ = 0.0f;
};

// The environment map as a light in the light list (RenderScene owns the map).
struct EnvironmentLight {
  static constexpr bool delta = false;
  static constexpr bool infinite = true;

  const EnvironmentMap* map;

  bool sample(Vec3f, Vec2f u, LightSample& s) const { return map->sample(u, s); }
  float pdf(Vec3f, Vec3f wi, Vec3f, Vec3f) const { return map->pdf(wi); }
  float power(float scene_radius) const { return map->power(scene_radius); }
  RGB radiance(Vec3f dir) const { return map->radiance(dir); }
};

}  // namespace pt
