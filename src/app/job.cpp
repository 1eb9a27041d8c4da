#include "app/job.h"

#include <algorithm>
#include <cstdio>

#include "app/film_options.h"
#include "app/options.h"
#include "app/outputs.h"
#include "core/diagnostics.h"
#include "imagelib/image_library.h"
#include "io/image_io.h"
#include "scene/loader.h"

namespace pt {
namespace {

// Pass size when checkpointing a render with a sample target and no
// --pass-spp: checkpoints are written at pass boundaries only.
constexpr int kCheckpointPassSpp = 16;

std::string counted(const std::vector<std::pair<std::string, uint64_t>>& list) {
  std::string text;
  for (const auto& [what, n] : list) text += (text.empty() ? "" : ", ") + std::to_string(n) + " " + what;
  return text;
}

// "imported 'x.gltf' (glTF, 0.12 s): 24 triangles, ...; left out: 1 animations"
std::string describe_import(const ImportSummary& s) {
  char seconds[32];
  std::snprintf(seconds, sizeof(seconds), "%.3g s", s.seconds);
  std::string text = "imported '" + s.file + "' (" + s.format + ", " + seconds + "): " + counted(s.imported);
  text += s.skipped.empty() ? "; nothing left out" : "; left out: " + counted(s.skipped);
  return text;
}

SettingsOverrides settings_overrides(const Options& o) {
  SettingsOverrides s;
  s.integrator = o.integrator;
  s.max_depth = o.max_depth;
  s.seed = o.seed;
  s.filter = o.filter;
  s.sampler = parse_sampler_type(o.sampler).value_or(s.sampler);  // CLI11 checked the name
  s.clamp = o.clamp;
  s.width = o.width;
  s.height = o.height;
  s.film_transparent = o.film_transparent;
  return s;
}

// The scene (with --set) and its settings.
bool load_job(const Options& o, Job& job, Messages& m) {
  const auto t0 = Clock::now();
  Diagnostics diag;
  diag.set_warnings_as_errors(o.strict);
  LoadOptions load_options;
  load_options.strict = o.strict;
  load_options.overrides = o.overrides;
  std::optional<SceneDescription> desc = load_scene(o.scene, load_options, diag);
  m.add(diag, o.quiet);
  if (!desc || diag.has_errors()) return false;
  if (!o.quiet)
    for (const ImportSummary& s : desc->imports) m.note(describe_import(s));
  job.parse_s = seconds_since(t0);
  job.desc = std::move(*desc);
  Diagnostics settings_diag;
  settings_diag.set_warnings_as_errors(o.strict);
  const bool resolved = resolve_render_settings(job.desc, settings_overrides(o), job.settings, settings_diag);
  m.add(settings_diag, o.quiet);  // e.g. an ambient light the integrator leaves out
  return resolved && !settings_diag.has_errors();
}

// Passes, AOVs, the replayed sample and the display images; false with the
// usage status.
bool plan_job(const Options& o, Job& job, Messages& m) {
  // Passes: a time budget alone has no sample target (the scene's spp is ignored).
  PassPlan& plan = job.plan;
  plan.target_spp = o.spp > 0 ? o.spp : (o.time_budget > 0 ? 0 : job.desc.render.spp.value);
  plan.time_budget_s = o.time_budget;
  plan.pass_spp = o.pass_spp;
  if (plan.pass_spp == 0 && plan.time_budget_s == 0 && !(o.checkpoint.empty() && o.resume.empty()))
    plan.pass_spp = kCheckpointPassSpp;
  std::string error;
  if (!film_aovs(o, *job.settings.integrator, job.aovs, job.beauty_type, error)) {
    m.error(error);
    return false;
  }
  // A replay needs the render's pass plan (below), not its length: under a
  // time budget without a sample target any sample index is accepted.
  if (o.replaying() && (o.replay[2] < 0 || (plan.target_spp > 0 && o.replay[2] >= plan.target_spp))) {
    m.error(std::string(o.sample_option()) + ": sample " + std::to_string(o.replay[2]) +
            (o.replay[2] < 0 ? " is negative"
                             : " is not one of the render's " + std::to_string(plan.target_spp) +
                                   " samples per pixel"));
    return false;
  }
  plan.equal_passes = job.settings.equal_passes();

  job.exr = {o.exr_compression, o.multipart, o.threads};
  for (const AovRequest& r : job.aovs)
    if (r.ranks > 0 && exr_compression_rounds_floats(job.exr.compression) && !o.replaying()) {
      m.error("--exr-compression " + job.exr.compression + " rounds 32-bit floats to 24 bits, which destroys " +
              aov_info(r.type).name + "'s ids; choose another compression (zip, piz, dwaa, ...)");
      return false;
    }
  job.display = display_settings(o, job.desc.film);
  job.display.alpha = job.settings.integration.film_transparent;  // PNG: RGBA
  if (job.display.transform != DisplayTransform::Srgb && !(o.view.empty() && o.display.empty() && o.look.empty()))
    m.warning("--view, --display and --look apply to native scenes; this scene's display images use its course's "
              "documented curve (docs/rendering.md)");
  if (!DisplayEncoder::create(job.display, error)) {
    m.error("display images: " + error);
    return false;
  }
  return true;
}

// The pre-flight memory estimate against --max-memory and the physical memory.
bool check_job_memory(const Options& o, Job& job, Messages& m, int& status) {
  status = kExitUsage;
  uint64_t limit = 0;
  if (!o.max_memory.empty()) {
    const std::optional<uint64_t> parsed = parse_byte_size(o.max_memory);
    if (!parsed || *parsed == 0) {
      m.error("--max-memory: '" + o.max_memory + "' is not a size (e.g. 4G, 512M, 65536)");
      return false;
    }
    limit = *parsed;
  }
  const int width = job.settings.width, height = job.settings.height;
  if (std::string error; !estimate_render_memory(o, job.desc, width, height, job.aovs, job.beauty_type, job.memory, error)) {
    m.error(error);  // a bad crop
    return false;
  }
  status = kExitFailure;
  // Sizes beyond the builder's limits get its message (naming the limits) instead.
  const bool within_limits = ResolutionLimits{}.admits(width, height);
  if (const std::string why = check_memory(job.memory, limit, physical_memory_bytes()); within_limits && !why.empty()) {
    m.error(why);
    return false;
  }
  return true;
}

// What a checkpoint must match, and where a resumed render starts.
bool checkpoint_job(const Options& o, Job& job, Messages& m) {
  if (o.checkpoint.empty() && o.resume.empty() && !job.shard.active) return true;
  std::string extra, error;
  for (const std::string& ov : o.overrides) extra += ov + '\n';
  job.identity.scene = o.scene;
  job.identity.scene_hash = scene_content_hash(o.scene, extra, error);
  if (job.identity.scene_hash.empty()) {
    m.error("checkpoint: " + error);
    return false;
  }
  job.identity.settings = job.settings.identity();
  const PassPlan& plan = job.plan;
  const bool adaptive = plan.time_budget_s > 0 && plan.pass_spp <= 0 && !plan.equal_passes;
  job.identity.settings["pass_spp"] = adaptive ? nlohmann::ordered_json("adaptive")
                                               : nlohmann::ordered_json(fixed_pass_size(plan));
  if (job.shard.active) {  // a checkpoint of a shard resumes only that shard
    job.identity.settings["sample_range"] = {job.shard.share.begin, job.shard.share.end};
    job.identity.settings["tile"] = o.tile;
  }
  if (o.resume.empty()) return true;
  CheckpointInfo saved;
  if (!read_checkpoint_info(o.resume, saved, error)) {
    m.error("--resume: " + error);
    return false;
  }
  if (const std::string why = checkpoint_mismatch(saved, job.identity); !why.empty()) {
    m.error("cannot resume from '" + o.resume + "': " + why);
    return false;
  }
  job.plan.start_spp = saved.spp_done;
  return true;
}

// The image module (imagelib/image_library.h), loaded before rendering when
// an output needs it, so that a module that cannot be loaded loses no render,
// and before the memory pre-flight, which measures what is resident (the
// module's libraries are ~125 MiB of it). Not earlier: usage errors, bad
// scenes and refused outputs never load it.
bool load_image_module(const Options& o, Messages& m) {
  if (o.replaying() || std::none_of(o.outputs.begin(), o.outputs.end(), needs_image_library)) return true;
  std::string error;
  if (image_library(error) != nullptr) return true;
  m.error(error);
  return false;
}

}  // namespace

void Messages::add(const Diagnostics& diag, bool quiet) {
  if (diag.all().empty() || (quiet && !diag.has_errors())) return;
  text += diag.format();
}

int check_request(const Options& o, Messages& m) {
  if (o.outputs.empty() && !o.replaying() && o.shard_out.empty()) {
    m.error("--output is required (except for a replay, --pixel or --replay, or a shard's --shard-out)");
    return kExitUsage;
  }
  if (std::string error; !check_outputs(o.outputs, error) || !check_output_files(output_files(o), error)) {
    m.error(error);
    return kExitUsage;
  }
  const bool replay = o.replaying();
  // A shard's AOVs go into its state (--shard-out), whatever its -o are.
  if (!o.aov.empty() && !replay && o.shard_out.empty() &&
      std::none_of(o.outputs.begin(), o.outputs.end(), is_exr_path)) {
    m.error("--aov: AOV layers are written to EXR outputs only, and no -o is an EXR (" + join(o.outputs, ", ") +
            "); add one (-o layers.exr) or leave out --aov");
    return kExitUsage;
  }
  if (o.time_budget > 0 && o.spp == 0 && !o.quiet && !replay && !o.sharded())
    m.note("--time-budget without --spp renders until the time is up (the scene's spp is ignored)");
  if (replay && !o.quiet && !(o.outputs.empty() && o.checkpoint.empty() && o.report.empty()))
    m.note("a replay writes no files (-o, --checkpoint and --report are ignored)");
  return 0;
}

std::optional<Job> prepare_job(const Options& o, Messages& m, int& status) {
  status = kExitFailure;
  Job job;
  job.stamps.take(output_files(o));
  if (!load_job(o, job, m)) return std::nullopt;
  if (std::string error; !check_outputs_are_not_inputs(o, output_files(o), job.desc, error)) {
    m.error(error);
    status = kExitUsage;
    return std::nullopt;
  }
  if (!plan_job(o, job, m)) {
    status = kExitUsage;
    return std::nullopt;
  }
  if (!load_image_module(o, m) || !check_job_memory(o, job, m, status)) return std::nullopt;
  status = kExitUsage;
  if (!plan_shard(o, job, m)) return std::nullopt;
  status = kExitFailure;
  if (!checkpoint_job(o, job, m)) return std::nullopt;
  return job;
}

}  // namespace pt
