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
// The steps are the pt_app library's (app/job.h); this file prints what they say.
#include <unistd.h>

#include <iostream>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include <CLI/CLI.hpp>

#include "app/distributed.h"
#include "app/film_options.h"
#include "app/job.h"
#include "app/mpi_launch.h"
#include "app/options.h"
#include "app/outputs.h"
#include "app/progress.h"
#include "app/signals.h"
#include "core/parallel.h"
#include "io/run_record.h"
#include "render/film/film.h"

namespace pt {
namespace {

int fail(const std::string& error, int status) {
  std::cerr << "error: " << error << '\n';
  return status;
}

// Progressive passes into `film`, checkpoints at pass boundaries and at the
// end (after the render time is taken).
RenderOutcome render(const Options& o, const Job& job, const RenderScene& scene, Film& film, WorkerPool& pool,
                     ProgressMonitor& monitor, RunFigures& figures) {
  IntegratorSettings settings = job.settings.integration;
  settings.monitor = &monitor;
  Checkpointer checkpointer(o, job, film);
  const auto write_checkpoint = [&](int spp_done) {
    if (std::string error; !checkpointer.write(spp_done, error)) std::cerr << "warning: checkpoint: " << error << '\n';
  };
  DriverCallbacks callbacks;
  callbacks.make_integrator = [&](const IntegratorSettings& s) { return job.settings.make_integrator(s); };
  callbacks.pass_done = [&](int spp_done) {
    monitor.set_spp_done(spp_done - job.plan.start_spp);
    if (checkpointer.due()) write_checkpoint(spp_done);
  };
  const auto t0 = Clock::now();
  const double cpu0 = process_cpu_seconds();
  monitor.start();
  const RenderOutcome outcome = render_passes(scene, film, pool, job.plan, settings, callbacks);
  monitor.stop();
  figures.render_s = seconds_since(t0);
  figures.render_cpu_s = process_cpu_seconds() - cpu0;
  if (!outcome.cancelled && !o.checkpoint.empty()) write_checkpoint(outcome.spp_done);
  return outcome;
}

int run(const Options& o) {
  Messages messages;
  const int request = check_request(o, messages);
  std::cerr << messages.take();
  if (request != 0) return request;

  // Settings and pre-flight checks.
  int status = 0;
  std::optional<Job> job = prepare_job(o, messages, status);
  std::cerr << messages.take();
  if (!job) return status;
  RunFigures figures;
  figures.parse_s = job->parse_s;

  // Build.
  auto t0 = Clock::now();
  WorkerPool pool(o.threads);
  figures.threads = pool.threads();
  const std::unique_ptr<RenderScene> scene = build_job_scene(o, *job, pool, messages);
  std::cerr << messages.take();
  if (!scene) return kExitFailure;
  figures.build_s = seconds_since(t0);

  // Render.
  PixelRect crop;
  std::string error;
  if (!crop_window(o, scene->width, scene->height, crop, error)) return fail(error, kExitUsage);
  Film film(scene->width, scene->height, crop, job->aovs);
  if (!resume_film(o, film, error)) return fail("--resume: " + error, kExitFailure);
  const SignalCancellation signals;
  ProgressMonitor monitor(progress_settings(o, *job, film, ::isatty(STDERR_FILENO)), &signals, std::cerr);
  if (o.replaying()) {  // printed; its one-pixel film is no image, checkpoint or record of the render
    std::cout << replay_sample(o, *job, *scene, film, pool);
    return 0;
  }
  const RenderOutcome outcome = render(o, *job, *scene, film, pool, monitor, figures);
  if (film.non_finite().total() > 0 && !o.quiet) std::cerr << "warning: " << non_finite_warning(film.non_finite()) << '\n';
  // A texture read that failed mid-render (a file changed since the build) leaves black texels: no image.
  if (const std::string why = scene->texture_failure(); !why.empty())
    return fail("a texture could not be read during the render (no image written): " + why, kExitFailure);
  if (job->shard.active) {  // a shard of a distributed render (docs/distributed.md)
    figures.samples = monitor.samples();
    figures.rays = monitor.rays();
    figures.signal = signals.received();
    return finish_shard(o, *job, *scene, film, outcome, figures, signals.received());
  }

  // Write.
  t0 = Clock::now();
  const ImageMetadata metadata = render_metadata(*job, *scene, outcome, figures.render_s);
  LayeredImage image;  // resolved in parallel (Film::layers), on --threads threads
  pool.run([&] { image = film.layers(job->beauty_type); });
  // An output that cannot be written does not stop the others or the record.
  const bool written = write_outputs(o.outputs, image, job->display, job->exr, metadata, job->stamps, error);
  if (!written) std::cerr << "error: " << error << '\n';
  figures.write_s = seconds_since(t0);

  // Record.
  figures.samples = monitor.samples();
  figures.rays = monitor.rays();
  figures.signal = signals.received();
  const RunRecord record = o.report.empty() ? RunRecord{} : run_record(o, *job, *scene, film, outcome, figures);
  if (!o.report.empty() &&
      !write_guarded(
          o.report, job->stamps, [&](const std::string& p, std::string& e) { return write_run_record(p, record, e); },
          error))
    return fail(error, kExitFailure);
  if (!written) return kExitFailure;
  if (outcome.cancelled) {
    std::cerr << interrupted_line(o, outcome, signals.received());
    return exit_status_for_signal(signals.received());
  }
  if (!o.quiet && !o.outputs.empty()) std::cout << summary_line(o, *job, outcome, figures);
  return 0;
}

}  // namespace
}  // namespace pt

int main(int argc, char** argv) {
  if (argc > 1 && std::string(argv[1]) == "merge") {  // a scene file named "merge" is ./merge
    try {
      return pt::merge_main(argc, argv);
    } catch (const std::exception& e) {
      std::cerr << "error: " << e.what() << '\n';
      return pt::kExitFailure;
    }
  }
  CLI::App app{"pathtracer: renders a scene file (native, Path of Light or CGR JSON) to EXR/PNG/PPM"};
  pt::Options options;
  pt::add_options(app, options);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ExtrasError& e) {
    const std::string unknown = pt::unknown_option_message(app, app.remaining());
    if (unknown.empty()) return app.exit(e) == 0 ? 0 : pt::kExitUsage;
    std::cerr << "error: " << unknown << "\n" << "Run with --help for more information.\n";
    return pt::kExitUsage;
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);  // prints help, version or the error
    return code == 0 ? 0 : pt::kExitUsage;
  }
  try {
    if (options.mpi) return pt::run_with_mpi(options, pt::run);
    return pt::run(options);
  } catch (const std::exception& e) {  // e.g. std::bad_alloc for an absurdly large scene
    std::cerr << "error: " << e.what() << '\n';
    return pt::kExitFailure;
  }
}
