// The build and render steps of the job (app/job.h).
#include "accel/accelerator.h"
#include "app/film_options.h"
#include "app/job.h"
#include "app/options.h"
#include "app/progress.h"
#include "core/parallel.h"
#include "render/film/film.h"

namespace pt {

std::unique_ptr<RenderScene> build_job_scene(const Options& o, const Job& job, WorkerPool& pool, Messages& m) {
  AccelKind accel = AccelKind::Bvh;
  parse_accel_kind(o.accel, accel);  // already validated by CLI11
  Diagnostics diag;
  diag.set_warnings_as_errors(o.strict);
  std::unique_ptr<RenderScene> scene = build_render_scene(job.desc, job.settings.build_options(accel), pool, diag);
  m.add(diag, o.quiet);
  if (!scene) return nullptr;
  const RenderSettings& settings = job.settings;
  if (std::string why; !settings.make_integrator(settings.integration)->can_render(*scene, why)) {
    m.error(why);  // e.g. bvh-cost with --accel=embree
    return nullptr;
  }
  return scene;
}

bool resume_film(const Options& o, Film& film, std::string& error) {
  if (o.resume.empty() || o.replaying()) return true;
  CheckpointInfo saved;
  return read_checkpoint(o.resume, saved, film, error);
}

ProgressSettings progress_settings(const Options& o, const Job& job, const Film& film, bool terminal) {
  ProgressSettings progress;
  progress.style = o.quiet || o.replaying() ? ProgressStyle::None
                                            : (terminal ? ProgressStyle::Bar : ProgressStyle::Lines);
  progress.interval_s = o.progress_interval;
  progress.pixels = static_cast<int64_t>(film.crop().width()) * film.crop().height();
  progress.target_spp = job.plan.target_spp > 0 ? job.plan.target_spp - job.plan.start_spp : 0;
  progress.time_budget_s = o.time_budget;
  return progress;
}

// The options are the render's, so the plan is too: the sampler is made for
// the size of the pass that drew the sample (the jittered sampler and the
// pixel grid stratify per pass).
std::string replay_sample(const Options& o, const Job& job, const RenderScene& scene, Film& film, WorkerPool& pool) {
  IntegratorSettings settings = job.settings.integration;
  settings.spp = replay_sampler_spp(job.plan);
  settings.only_sample = o.replay[2];
  job.settings.make_integrator(settings)->render(scene, film, pool);
  return replay_text(film, o.replay[0], o.replay[1], o.replay[2]);
}

Checkpointer::Checkpointer(const Options& o, const Job& job, const Film& film)
    : path_(o.checkpoint),
      stamps_(job.stamps),
      every_(o.checkpoint_every),
      info_(job.identity),
      film_(film),
      last_(Clock::now()) {}

bool Checkpointer::due() const { return !path_.empty() && seconds_since(last_) >= every_; }

bool Checkpointer::write(int spp_done, std::string& error) {
  if (path_.empty()) return true;
  info_.spp_done = spp_done;
  last_ = Clock::now();
  return write_guarded(
      path_, stamps_, [&](const std::string& p, std::string& e) { return write_checkpoint(p, info_, film_, e); },
      error);
}

}  // namespace pt
