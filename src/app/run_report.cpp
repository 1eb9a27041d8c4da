#include "app/run_report.h"

#include <algorithm>
#include <memory>
#include <string>

#include "accel/accelerator.h"
#include "app/options.h"
#include "app/render_driver.h"
#include "io/display.h"
#include "render/film/film.h"
#include "render/render_scene.h"
#include "scene/scene_description.h"

namespace pt {
namespace {

const char* type_name(ChannelType type) { return type == ChannelType::Half ? "half" : "float"; }

}  // namespace

void record_request(const Options& o, const Film& film, ChannelType beauty, const PassPlan& plan,
                    const DisplaySettings& display, RunRecord& record) {
  record.outputs = o.outputs;
  const PixelRect& crop = film.crop();
  record.crop = {crop.x0, crop.y0, crop.width(), crop.height()};
  record.beauty_type = type_name(beauty);
  record.aovs.clear();
  for (const AovRequest& r : film.aovs()) record.aovs.emplace_back(aov_info(r.type).name, type_name(r.channel_type));
  // As the checkpoint's settings: adaptive passes have no fixed size.
  const bool adaptive = plan.time_budget_s > 0 && plan.pass_spp <= 0 && !plan.equal_passes;
  record.pass_spp = adaptive ? 0 : fixed_pass_size(plan);
  record.checkpoint = o.checkpoint;
  record.checkpoint_every = o.checkpoint.empty() ? 0.0 : o.checkpoint_every;
  record.resumed_from = o.resume;
  RunRecord::Display& d = record.display;
  d.transform = kDisplayTransformNames[static_cast<int>(display.transform)];
  d.exposure = display.exposure;
  d.view = display.view;
  d.display = display.display;
  d.look = display.look;
  d.ocio_config = display.ocio_config;
  std::string error;
  if (const std::unique_ptr<DisplayEncoder> encoder = DisplayEncoder::create(display, error)) d.pipeline = encoder->description();
}

PhaseTimings phase_timings(double parse_s, double build_s, double render_s, double write_s,
                           const SceneDescription& desc, const RenderScene& scene) {
  PhaseTimings t;
  t.mesh_load = std::min(desc.mesh_load_seconds, parse_s);
  t.parse = parse_s - t.mesh_load;
  t.accel_build = std::min(scene.accel->stats().build_seconds, build_s);
  t.texture_load = std::min(scene.texture_load_seconds, build_s - t.accel_build);
  t.scene_build = build_s - t.accel_build - t.texture_load;
  t.render = render_s;
  t.write = write_s;
  t.total = parse_s + build_s + render_s + write_s;
  return t;
}

}  // namespace pt
