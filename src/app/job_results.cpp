// What the job reports once rendered (app/job.h): the EXR metadata, the run
// record and the last line.
#include <iomanip>
#include <sstream>

#include "accel/accelerator.h"
#include "app/film_options.h"
#include "app/job.h"
#include "app/options.h"
#include "app/outputs.h"
#include "app/run_report.h"
#include "app/versions.h"
#include "io/run_record.h"
#include "render/film/film.h"

namespace pt {
std::string non_finite_warning(const NonFiniteReport& report) {
  return report.describe() + "; they were added as black" + replay_hint(report);
}

ImageMetadata render_metadata(const Job& job, const RenderScene& scene, const RenderOutcome& outcome, double render_s) {
  RenderStamp stamp = job.settings.stamp();
  stamp.render_seconds = render_s;
  stamp.spp = outcome.spp_done;
  stamp.backend = scene.accel->stats().backend;
  stamp.partial = outcome.cancelled;
  stamp.has_camera = true;
  stamp.world_to_camera = scene.camera.world_to_camera();
  stamp.world_to_ndc = scene.camera.world_to_ndc();
  ImageMetadata metadata;
  add_render_stamp(metadata, stamp);
  for (const AovRequest& r : job.aovs)  // Cryptomatte: its name, hash, conversion and manifest
    if (r.ranks > 0)
      add_cryptomatte_metadata(metadata, aov_info(r.type).name,
                               r.type == AovType::CryptoObject ? scene.names.objects : scene.names.materials);
  return metadata;
}

RunRecord run_record(const Options& o, const Job& job, const RenderScene& scene, const Film& film,
                     const RenderOutcome& outcome, const RunFigures& f) {
  RunRecord record;
  record.scene = o.scene;
  record.overrides = o.overrides;
  job.settings.describe(record);
  record.spp = outcome.spp_done;
  record.target_spp = job.plan.target_spp;
  record.time_budget = o.time_budget;
  record.passes = outcome.passes;
  record.resumed_spp = job.plan.start_spp;
  record.last_pass_seconds = outcome.last_pass_seconds;
  record.partial = outcome.cancelled;
  record.signal = f.signal;
  record.threads = f.threads;
  const AccelStats stats = scene.accel->stats();
  record.accel_backend = stats.backend;
  record.accel_memory_bytes = stats.memory_bytes;
  record.accel_build_peak_bytes = stats.build_peak_bytes;
  record.primitive_count = stats.primitive_count;
  record.timings = phase_timings(f.parse_s, f.build_s, f.render_s, f.write_s, job.desc, scene);
  record.pixel_samples = f.samples;
  record.samples_per_second = f.samples_per_second();
  record.rays = f.rays;
  record.rays_per_second = f.rays_per_second();
  record.render_cpu_seconds = f.render_cpu_s;
  for (const ImportSummary& i : job.desc.imports)
    record.imports.push_back({i.file, i.format, i.seconds, i.imported, i.skipped});
  record.memory_estimate_bytes = job.memory.total();
  record.peak_memory_bytes = peak_resident_bytes();
  const MemoryEstimate& m = job.memory;
  record.memory_estimate_parts = {{"baseline", m.baseline}, {"peak_so_far", m.peak_so_far},
                                  {"reusable", m.reusable}, {"film", m.film},
                                  {"images", m.images},     {"textures", m.textures},
                                  {"geometry", m.geometry}, {"runtime", m.runtime}};
  record.versions = software_versions();
  const NonFiniteReport& nf = film.non_finite();
  record.non_finite = {nf.nan, nf.pos_inf, nf.neg_inf, nf.has_first, nf.x, nf.y, nf.sample};
  record_request(o, film, job.beauty_type, job.plan, job.display, record);
  return record;
}

std::string summary_line(const Options& o, const Job& job, const RenderOutcome& outcome, const RunFigures& f) {
  const float clamp = job.settings.integration.clamp;
  std::ostringstream out;
  out << std::fixed << std::setprecision(3) << "wrote " << join(o.outputs, ", ") << " (" << job.settings.width << "x"
      << job.settings.height << ", " << job.settings.integrator_name() << ", " << outcome.spp_done << " spp in "
      << outcome.passes << (outcome.passes == 1 ? " pass, " : " passes, ") << f.threads << " threads"
      << (clamp > 0.0f ? ", clamp " + std::to_string(clamp) : std::string()) << "): parse " << f.parse_s
      << " s, build " << f.build_s << " s, render " << f.render_s << " s (" << std::setprecision(0)
      << f.samples_per_second() << " samples/s, " << f.rays_per_second() << " rays/s), write " << std::setprecision(3) << f.write_s << " s\n";
  return out.str();
}

std::string interrupted_line(const Options& o, const RenderOutcome& outcome, int signal) {
  return "interrupted (signal " + std::to_string(signal) + "): wrote partial " + join(o.outputs, ", ") + " with " +
         std::to_string(outcome.spp_done) + " complete spp (some pixels have more)\n";
}

}  // namespace pt
