// pathtracer: renders a scene file to one or more images (docs/cli.md).
//
//   pathtracer SCENE -o OUT [-o OUT2 ...] [--spp N] [--time-budget S] [--set KEY=VALUE ...]
//              [--checkpoint FILE [--checkpoint-every S]] [--resume FILE] [--report FILE] ...
//
// Exit status: 0 success; 1 the scene, the render or an output failed (nothing
// is written for a bad scene); 2 a bad command line (CLI11's message);
// 128 + N when signal N (SIGINT: 130, SIGTERM: 143) stopped the render: the
// outputs then hold what was rendered, marked partial.
//
// The recipe: parse -> settings -> pre-flight checks -> build -> render -> write -> record.
#include <sys/resource.h>
#include <unistd.h>

#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include <CLI/CLI.hpp>

#include "accel/accelerator.h"
#include "app/checkpoint.h"
#include "app/film_options.h"
#include "app/memory_estimate.h"
#include "app/options.h"
#include "app/outputs.h"
#include "app/progress.h"
#include "app/render_driver.h"
#include "app/run_report.h"
#include "app/signals.h"
#include "app/versions.h"
#include "core/diagnostics.h"
#include "core/stopwatch.h"
#include "core/parallel.h"
#include "io/image_metadata.h"
#include "io/run_record.h"
#include "render/film/film.h"
#include "render/film/filter.h"
#include "render/integrators/integrator.h"
#include "render/render_scene.h"
#include "scene/loader.h"

namespace pt {
namespace {

// Pass size when checkpointing a render with a sample target and no
// --pass-spp: checkpoints are written at pass boundaries only.
constexpr int kCheckpointPassSpp = 16;

void print_diagnostics(const Diagnostics& diag, bool quiet) {
  if (diag.all().empty() || (quiet && !diag.has_errors())) return;
  std::cerr << diag.format();
}

uint64_t peak_rss_bytes() {
  rusage usage{};
  if (::getrusage(RUSAGE_SELF, &usage) != 0) return 0;
  return static_cast<uint64_t>(usage.ru_maxrss) * 1024;  // KiB on Linux
}

// Everything decided before the expensive build.
struct Job {
  SceneDescription desc;
  IntegratorSettings settings;
  std::string integrator;
  PassPlan plan;
  DisplaySettings display;
  int width = 0, height = 0;
  MemoryEstimate memory;
  std::vector<AovRequest> aovs;  // --aov (every AOV for a replay)
  ChannelType beauty_type = ChannelType::Float;  // --aov beauty:half
  CheckpointInfo identity;  // scene hash and settings, for --checkpoint and --resume
};

// Returns std::nullopt after printing why, with `status` the exit status.
std::optional<Job> prepare(const Options& o, double& parse_s, int& status) {
  status = kExitFailure;
  const auto t0 = Clock::now();
  Diagnostics diag;
  diag.set_warnings_as_errors(o.strict);
  LoadOptions load_options;
  load_options.strict = o.strict;
  load_options.overrides = o.overrides;
  std::optional<SceneDescription> desc = load_scene(o.scene, load_options, diag);
  print_diagnostics(diag, o.quiet);
  if (!desc || diag.has_errors()) return std::nullopt;
  parse_s = seconds_since(t0);

  Job job;
  job.desc = std::move(*desc);
  IntegratorSettings& s = job.settings;
  s.max_depth = o.max_depth >= 0 ? o.max_depth : job.desc.render.max_depth.value;
  s.seed = o.seed;
  s.filter = job.desc.render.filter;
  if (o.filter == "gaussian") s.filter = PixelFilterType::Gaussian;
  if (o.filter == "mitchell") s.filter = PixelFilterType::Mitchell;
  if (o.filter == "box") s.filter = PixelFilterType::Box;
  s.sampler = parse_sampler_type(o.sampler).value_or(SamplerType::Sobol);
  s.clamp = o.clamp >= 0.0f ? o.clamp : job.desc.render.clamp.value;
  job.integrator = o.integrator.empty() ? job.desc.render.integrator.value : o.integrator;
  std::string error;
  if (!make_integrator(job.integrator, s, error)) {
    Diagnostics d;
    d.error(o.integrator.empty() ? job.desc.render.integrator.where : SourceLocation{}, error);
    std::cerr << d.format();
    return std::nullopt;
  }

  // Passes: a time budget alone has no sample target (the scene's spp is ignored).
  PassPlan& plan = job.plan;
  plan.target_spp = o.spp > 0 ? o.spp : (o.time_budget > 0 ? 0 : job.desc.render.spp.value);
  plan.time_budget_s = o.time_budget;
  plan.pass_spp = o.pass_spp;
  if (plan.pass_spp == 0 && plan.time_budget_s == 0 && !(o.checkpoint.empty() && o.resume.empty()))
    plan.pass_spp = kCheckpointPassSpp;
  if (!film_aovs(o, job.aovs, job.beauty_type)) {
    status = kExitUsage;
    return std::nullopt;
  }
  // A replay needs the render's pass plan (below), not its length: under a
  // time budget without a sample target any sample index is accepted.
  if (o.replaying() && (o.replay[2] < 0 || (plan.target_spp > 0 && o.replay[2] >= plan.target_spp))) {
    std::cerr << "error: " << o.sample_option() << ": sample " << o.replay[2];
    if (o.replay[2] < 0)
      std::cerr << " is negative\n";
    else
      std::cerr << " is not one of the render's " << plan.target_spp << " samples per pixel\n";
    status = kExitUsage;
    return std::nullopt;
  }
  // Samplers that stratify over the pass's sample count need equal passes.
  plan.equal_passes = !(job.integrator == "path" && s.sampler != SamplerType::Jittered);

  job.display = display_settings(o, job.desc.film);
  if (job.display.transform != DisplayTransform::Srgb && !(o.view.empty() && o.display.empty() && o.look.empty()))
    std::cerr << "warning: --view, --display and --look apply to native scenes; this scene's display images "
                 "use its course's documented curve (docs/rendering.md)\n";
  if (!DisplayEncoder::create(job.display, error)) {
    std::cerr << "error: display images: " << error << '\n';
    status = kExitUsage;
    return std::nullopt;
  }

  // Pre-flight memory estimate.
  BuildOptions resolution;
  resolution.width_override = o.width;
  resolution.height_override = o.height;
  resolve_resolution(job.desc.film, resolution, job.width, job.height);
  uint64_t limit = 0;
  if (!o.max_memory.empty()) {
    const std::optional<uint64_t> parsed = parse_byte_size(o.max_memory);
    if (!parsed || *parsed == 0) {
      std::cerr << "error: --max-memory: '" << o.max_memory << "' is not a size (e.g. 4G, 512M, 65536)\n";
      status = kExitUsage;
      return std::nullopt;
    }
    limit = *parsed;
  }
  if (!estimate_render_memory(o, job.desc, job.width, job.height, job.aovs, job.memory)) {  // a bad crop
    status = kExitUsage;
    return std::nullopt;
  }
  // Sizes beyond the builder's limits get its message (naming the limits) instead.
  const bool within_limits = resolution.limits.admits(job.width, job.height);
  if (const std::string why = check_memory(job.memory, limit, physical_memory_bytes());
      within_limits && !why.empty()) {
    std::cerr << "error: " << why << '\n';
    return std::nullopt;
  }

  // What a checkpoint must match.
  if (o.checkpoint.empty() && o.resume.empty()) return job;
  std::string extra;
  for (const std::string& ov : o.overrides) extra += ov + '\n';
  job.identity.scene = o.scene;
  job.identity.scene_hash = scene_content_hash(o.scene, extra, error);
  if (job.identity.scene_hash.empty()) {
    std::cerr << "error: checkpoint: " << error << '\n';
    return std::nullopt;
  }
  job.identity.settings = {{"integrator", job.integrator}, {"width", job.width}, {"height", job.height},
                           {"max_depth", s.max_depth}, {"seed", s.seed}, {"sampler", sampler_type_name(s.sampler)},
                           {"filter", pixel_filter_name(s.filter)}, {"clamp", s.clamp}};
  const bool adaptive = plan.time_budget_s > 0 && plan.pass_spp <= 0 && !plan.equal_passes;
  job.identity.settings["pass_spp"] = adaptive ? nlohmann::ordered_json("adaptive")
                                               : nlohmann::ordered_json(fixed_pass_size(plan));
  if (!o.resume.empty()) {
    CheckpointInfo saved;
    if (!read_checkpoint_info(o.resume, saved, error)) {
      std::cerr << "error: --resume: " << error << '\n';
      return std::nullopt;
    }
    if (const std::string why = checkpoint_mismatch(saved, job.identity); !why.empty()) {
      std::cerr << "error: cannot resume from '" << o.resume << "': " << why << '\n';
      return std::nullopt;
    }
    plan.start_spp = saved.spp_done;
  }
  return job;
}

// Writes a checkpoint at most every `every` seconds (and when asked to force).
class Checkpointer {
 public:
  Checkpointer(const Options& o, const Job& job, const Film& film)
      : path_(o.checkpoint), every_(o.checkpoint_every), info_(job.identity), film_(film), last_(Clock::now()) {}
  bool due() const { return !path_.empty() && seconds_since(last_) >= every_; }
  bool write(int spp_done) {
    if (path_.empty()) return true;
    info_.spp_done = spp_done;
    std::string error;
    last_ = Clock::now();
    if (write_checkpoint(path_, info_, film_, error)) return true;
    std::cerr << "warning: checkpoint: " << error << '\n';
    return false;
  }

 private:
  std::string path_;
  double every_;
  CheckpointInfo info_;
  const Film& film_;
  Clock::time_point last_;
};

// --pixel X,Y --sample N (or --replay X,Y,N): renders only that sample of that
// pixel (the film is cropped to it) and prints its radiance and AOVs. The
// options are the render's, so the plan is too: the sampler is made for the
// size of the pass that drew the sample (the jittered sampler and the pixel
// grid stratify per pass).
RenderOutcome replay_sample(const Options& o, const Job& job, const RenderScene& scene, Film& film, WorkerPool& pool) {
  IntegratorSettings settings = job.settings;
  settings.spp = replay_sampler_spp(job.plan);
  settings.only_sample = o.replay[2];
  std::string error;
  make_integrator(job.integrator, settings, error)->render(scene, film, pool);
  print_replay(film, o.replay[0], o.replay[1], o.replay[2]);
  RenderOutcome outcome;
  outcome.spp_done = 1;
  outcome.passes = 1;
  return outcome;
}

int run(const Options& o) {
  if (o.outputs.empty() && !o.replaying()) {
    std::cerr << "error: --output is required (except for a replay, --pixel or --replay)\n";
    return kExitUsage;
  }
  if (!check_outputs(o.outputs)) return kExitUsage;
  const bool replay = o.replaying();
  if (o.time_budget > 0 && o.spp == 0 && !o.quiet && !replay)
    std::cerr << "note: --time-budget without --spp renders until the time is up (the scene's spp is ignored)\n";
  if (replay && !o.quiet && !(o.outputs.empty() && o.checkpoint.empty() && o.report.empty()))
    std::cerr << "note: a replay writes no files (-o, --checkpoint and --report are ignored)\n";
  double parse_s = 0;
  int status = 0;
  std::optional<Job> job = prepare(o, parse_s, status);
  if (!job) return status;

  // Build.
  auto t0 = Clock::now();
  AccelKind accel = AccelKind::Bvh;
  parse_accel_kind(o.accel, accel);  // already validated by CLI11
  WorkerPool pool(o.threads);
  Diagnostics build_diag;
  build_diag.set_warnings_as_errors(o.strict);
  BuildOptions build_options;
  build_options.accel = accel;
  build_options.width_override = o.width;
  build_options.height_override = o.height;
  const std::unique_ptr<RenderScene> scene = build_render_scene(job->desc, build_options, pool, build_diag);
  print_diagnostics(build_diag, o.quiet);
  if (!scene) return kExitFailure;
  if (std::string why; !make_integrator(job->integrator, job->settings, why)->can_render(*scene, why)) {
    std::cerr << "error: " << why << '\n';  // e.g. bvh-cost with --accel=embree
    return kExitFailure;
  }
  const double build_s = seconds_since(t0);

  PixelRect crop;
  if (!crop_window(o, scene->width, scene->height, crop)) return kExitUsage;

  // Render.
  Film film(scene->width, scene->height, crop, job->aovs);
  if (!o.resume.empty() && !replay) {
    CheckpointInfo saved;
    std::string error;
    if (!read_checkpoint(o.resume, saved, film, error)) {
      std::cerr << "error: --resume: " << error << '\n';
      return kExitFailure;
    }
  }
  const SignalCancellation signals;
  ProgressSettings progress;
  progress.style = o.quiet || replay ? ProgressStyle::None : (::isatty(STDERR_FILENO) ? ProgressStyle::Bar : ProgressStyle::Lines);
  progress.interval_s = o.progress_interval;
  progress.pixels = static_cast<int64_t>(crop.width()) * crop.height();
  progress.target_spp = job->plan.target_spp > 0 ? job->plan.target_spp - job->plan.start_spp : 0;
  progress.time_budget_s = o.time_budget;
  ProgressMonitor monitor(progress, &signals, std::cerr);
  IntegratorSettings settings = job->settings;
  settings.monitor = &monitor;
  Checkpointer checkpointer(o, *job, film);
  DriverCallbacks callbacks;
  callbacks.make_integrator = [&](const IntegratorSettings& s) {
    std::string error;
    return make_integrator(job->integrator, s, error);
  };
  callbacks.pass_done = [&](int spp_done) {
    monitor.set_spp_done(spp_done - job->plan.start_spp);
    if (checkpointer.due()) checkpointer.write(spp_done);
  };
  t0 = Clock::now();
  monitor.start();
  const RenderOutcome outcome = replay ? replay_sample(o, *job, *scene, film, pool)
                                      : render_passes(*scene, film, pool, job->plan, settings, callbacks);
  monitor.stop();
  if (replay) return 0;  // printed; its one-pixel film is no image, checkpoint or record of the render
  const double render_s = seconds_since(t0);
  if (!outcome.cancelled && !o.checkpoint.empty()) checkpointer.write(outcome.spp_done);
  const NonFiniteReport& non_finite = film.non_finite();
  if (non_finite.total() > 0 && !o.quiet)
    std::cerr << "warning: " << non_finite.describe() << "; they were added as black" << replay_hint(non_finite) << '\n';

  // What took the samples, for the EXR and the run record alike: the path
  // integrator's sampler and filter; the classic integrators' pixel grid and box.
  const bool path_integrator = job->integrator == "path";
  const std::string sampler_name = path_integrator ? sampler_type_name(settings.sampler) : "pixel-grid";
  const std::string filter_name = path_integrator ? pixel_filter_name(settings.filter) : "box";

  // Write.
  t0 = Clock::now();
  RenderStamp stamp;
  stamp.render_seconds = render_s;
  stamp.spp = outcome.spp_done;
  stamp.seed = settings.seed;
  stamp.backend = scene->accel->stats().backend;
  stamp.integrator = job->integrator;
  stamp.sampler = sampler_name;
  stamp.filter = filter_name;
  stamp.max_depth = settings.max_depth;
  stamp.clamp = settings.clamp;
  stamp.software_version = PT_VERSION;
  stamp.partial = outcome.cancelled;
  stamp.has_camera = true;
  stamp.world_to_camera = scene->camera.world_to_camera();
  stamp.world_to_ndc = scene->camera.world_to_ndc();
  ImageMetadata metadata;
  add_render_stamp(metadata, stamp);
  if (!write_outputs(o.outputs, film.layers(job->beauty_type), job->display, metadata)) return kExitFailure;
  const double write_s = seconds_since(t0);

  const int64_t samples = monitor.samples();
  const double samples_per_s = render_s > 0 ? static_cast<double>(samples) / render_s : 0.0;
  const double rays_per_s = render_s > 0 ? static_cast<double>(monitor.rays()) / render_s : 0.0;
  if (!o.report.empty()) {
    RunRecord record;
    record.scene = o.scene;
    record.overrides = o.overrides;
    record.integrator = job->integrator;
    record.sampler = sampler_name;
    record.width = scene->width;
    record.height = scene->height;
    record.spp = outcome.spp_done;
    record.target_spp = job->plan.target_spp;
    record.time_budget = o.time_budget;
    record.passes = outcome.passes;
    record.resumed_spp = job->plan.start_spp;
    record.partial = outcome.cancelled;
    record.signal = signals.received();
    record.max_depth = settings.max_depth;
    record.seed = settings.seed;
    record.filter = filter_name;
    record.clamp = settings.clamp;
    record.threads = pool.threads();
    const AccelStats stats = scene->accel->stats();
    record.accel_backend = stats.backend;
    record.accel_memory_bytes = stats.memory_bytes;
    record.primitive_count = stats.primitive_count;
    record.timings = phase_timings(parse_s, build_s, render_s, write_s, job->desc, *scene);
    record.pixel_samples = samples;
    record.samples_per_second = samples_per_s;
    record.rays = monitor.rays();
    record.rays_per_second = rays_per_s;
    record.memory_estimate_bytes = job->memory.total();
    record.peak_memory_bytes = peak_rss_bytes();
    record.versions = software_versions();
    record.non_finite = {non_finite.nan, non_finite.pos_inf, non_finite.neg_inf, non_finite.has_first,
                         non_finite.x,   non_finite.y,       non_finite.sample};
    record_request(o, film, job->beauty_type, job->plan, job->display, record);
    if (std::string error; !write_run_record(o.report, record, error)) {
      std::cerr << "error: " << error << '\n';
      return kExitFailure;
    }
  }

  if (outcome.cancelled) {
    std::cerr << "interrupted (signal " << signals.received() << "): wrote partial " << join(o.outputs, ", ")
              << " with " << outcome.spp_done << " complete spp (some pixels have more)\n";
    return exit_status_for_signal(signals.received());
  }
  if (!o.quiet && !o.outputs.empty()) {
    std::cout << std::fixed << std::setprecision(3) << "wrote " << join(o.outputs, ", ") << " (" << scene->width
              << "x" << scene->height << ", " << job->integrator << ", " << outcome.spp_done << " spp in "
              << outcome.passes << (outcome.passes == 1 ? " pass, " : " passes, ") << pool.threads() << " threads"
              << (settings.clamp > 0.0f ? ", clamp " + std::to_string(settings.clamp) : std::string())
              << "): parse " << parse_s << " s, build " << build_s << " s, render " << render_s << " s ("
              << std::setprecision(0) << samples_per_s << " samples/s, " << rays_per_s << " rays/s), write " << std::setprecision(3) << write_s
              << " s\n";
  }
  return 0;
}

}  // namespace
}  // namespace pt

int main(int argc, char** argv) {
  CLI::App app{"pathtracer: renders a scene file (native, Path of Light or CGR JSON) to EXR/PNG/PPM"};
  pt::Options options;
  pt::add_options(app, options);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);  // prints help, version or the error
    return code == 0 ? 0 : pt::kExitUsage;
  }
  try {
    return pt::run(options);
  } catch (const std::exception& e) {  // e.g. std::bad_alloc for an absurdly large scene
    std::cerr << "error: " << e.what() << '\n';
    return pt::kExitFailure;
  }
}
