// What the command line puts in the run record (src/io/run_record.h) besides
// the render's own figures: the request (outputs, crop, AOV types, passes,
// checkpoints, display) and the time of each phase (docs/cli.md).
#pragma once

#include "io/layered_image.h"
#include "io/run_record.h"

namespace pt {

class Film;
struct DisplaySettings;
struct Options;
struct PassPlan;
struct RenderScene;
struct SceneDescription;

// Fills the outputs, the crop window and AOV list of `film`, the beauty's
// type, the pass size of `plan`, the checkpoint and resume files and the
// display settings.
void record_request(const Options& o, const Film& film, ChannelType beauty, const PassPlan& plan,
                    const DisplaySettings& display, RunRecord& record);

// The phases from what the driver measured: `parse_s` around load_scene (mesh
// files included), `build_s` around build_render_scene (textures and the
// acceleration structure included); the scene and its description say how
// much of those went to meshes, textures and the accelerator.
PhaseTimings phase_timings(double parse_s, double build_s, double render_s, double write_s,
                           const SceneDescription& desc, const RenderScene& scene);

}  // namespace pt
