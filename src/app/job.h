// The render job of the command line (docs/cli.md), the steps main() runs in
// order: prepare (load, settings, passes, display, the memory pre-flight and
// the checkpoint identity), build, render, write, record. Library code: these
// never print; what the user must read comes back as text (Messages) and the
// command line prints it, in order, on stderr.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "app/checkpoint.h"
#include "app/memory_estimate.h"
#include "app/output_checks.h"
#include "app/render_driver.h"
#include "app/render_settings.h"
#include "app/shard.h"
#include "core/diagnostics.h"
#include "core/stopwatch.h"
#include "io/display.h"
#include "io/image_io.h"
#include "io/image_metadata.h"
#include "render/film/aov.h"
#include "scene/scene_description.h"

namespace pt {

class Film;
class WorkerPool;
struct NonFiniteReport;
struct Options;
struct ProgressSettings;
struct RunRecord;

// Messages for the user in the order they arose ("error: ...", "warning:
// ...", diagnostics with their caret): the command line prints `text` on stderr.
struct Messages {
  std::string text;
  void error(const std::string& message) { text += "error: " + message + '\n'; }
  void warning(const std::string& message) { text += "warning: " + message + '\n'; }
  void note(const std::string& message) { text += "note: " + message + '\n'; }
  // The diagnostics, formatted (with `quiet`, only if they hold an error).
  void add(const Diagnostics& diag, bool quiet);
  std::string take() { return std::exchange(text, {}); }
};

// Everything decided before the expensive build.
struct Job {
  SceneDescription desc;
  RenderSettings settings;
  PassPlan plan;
  DisplaySettings display;
  ExrSettings exr;  // --exr-compression, --multipart
  MemoryEstimate memory;
  std::vector<AovRequest> aovs;  // --aov (every AOV for a replay)
  ChannelType beauty_type = ChannelType::Float;  // --aov beauty:half
  CheckpointInfo identity;  // scene hash and settings, for --checkpoint, --resume and shards
  ShardPlan shard;          // a shard of a distributed render (app/shard.h)
  double parse_s = 0;       // load_scene, meshes included
  OutputStamps stamps;      // every output as it was when the run started (two runs, one name)
};

// The seconds of each phase and what the render counted, for the record and the summary.
struct RunFigures {
  double parse_s = 0, build_s = 0, render_s = 0, write_s = 0;
  double render_cpu_s = 0;        // the process's CPU time during the render phase
  int64_t samples = 0, rays = 0;  // pixel samples and rays (the progress monitor's counts)
  int threads = 0;
  int signal = 0;  // the signal that stopped the render, or 0

  double samples_per_second() const { return render_s > 0 ? static_cast<double>(samples) / render_s : 0.0; }
  double rays_per_second() const { return render_s > 0 ? static_cast<double>(rays) / render_s : 0.0; }
};

// The command line's own checks before the scene is read (an output is
// required and supported; every output, checkpoint and run record can be
// written and is a file of its own: app/output_checks.h) and its notes; a
// non-zero status stops.
int check_request(const Options& o, Messages& messages);

// Loads the scene, resolves its settings and plans the render; std::nullopt
// with `status` the exit status after adding why to `messages`.
std::optional<Job> prepare_job(const Options& o, Messages& messages, int& status);

// Builds the render scene on --accel and checks the integrator can render it;
// nullptr after adding why to `messages`. The shapes' geometry moves from
// job.desc into the scene (build_render_scene_taking_geometry: a large mesh is
// held once); nothing after the build reads it from the description.
std::unique_ptr<RenderScene> build_job_scene(const Options& o, Job& job, WorkerPool& pool, Messages& messages);

// Reads --resume's film state into `film` (nothing without --resume or for a
// replay); false with `error`.
bool resume_film(const Options& o, Film& film, std::string& error);

// The progress display of the render of `film` (none when quiet or replaying;
// a bar on a terminal, else lines).
ProgressSettings progress_settings(const Options& o, const Job& job, const Film& film, bool terminal);

// --pixel X,Y --sample N (or --replay X,Y,N): renders only that sample of that
// pixel (the film is cropped to it) and returns its report (replay_text()).
std::string replay_sample(const Options& o, const Job& job, const RenderScene& scene, Film& film, WorkerPool& pool);

// Writes a checkpoint at most every `every` seconds (and at the end).
class Checkpointer {
 public:
  Checkpointer(const Options& o, const Job& job, const Film& film);
  bool due() const;
  // False with `error` when the file could not be written (the render goes on).
  bool write(int spp_done, std::string& error);

 private:
  std::string path_;
  OutputStamps stamps_;
  double every_;
  CheckpointInfo info_;
  const Film& film_;
  Clock::time_point last_;
};

// The warning for samples that were not finite ("...; they were added as
// black; to replay the first, ..."), without "warning: ".
std::string non_finite_warning(const NonFiniteReport& report);

// The EXR metadata of the render: its settings, what it reached, the camera,
// and each Cryptomatte AOV's (render/film/cryptomatte.h).
ImageMetadata render_metadata(const Job& job, const RenderScene& scene, const RenderOutcome& outcome, double render_s);

// The run record (--report).
RunRecord run_record(const Options& o, const Job& job, const RenderScene& scene, const Film& film,
                     const RenderOutcome& outcome, const RunFigures& figures);

// "wrote a.exr, b.png (WxH, integrator, N spp in P passes, T threads): parse ... s, ..." and its newline.
std::string summary_line(const Options& o, const Job& job, const RenderOutcome& outcome, const RunFigures& figures);
// "interrupted (signal N): wrote partial ... with N complete spp (some pixels have more)" and its newline.
std::string interrupted_line(const Options& o, const RenderOutcome& outcome, int signal);

}  // namespace pt
