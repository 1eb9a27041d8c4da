// pt-converge SCENE --reference REF.exr --checkpoints N1,N2,... [--rect X,Y,W,H]
//             [--accel embree|bvh] [--sampler random|jittered|sobol] [--seeds S1,S2,...]
//             [--threads N] [--width W] [--height H] [--max-depth D] [--max-seconds T] --csv OUT.csv
//
// Error checkpoints during a render (docs/report/README.md, docs/samplers.md):
// renders SCENE with the path integrator in this one process and, at every
// checkpoint sample count, writes a CSV row with the render's wall time, the
// spp and the error against REF (MSE, relative MSE, RMSE as pt-imgerr and
// pt::compute_image_error define them), over the frame or the rectangle.
//
// random and sobol: one progressive render per seed; samples [0, n) of every
// pixel are exactly the render at n spp, so each checkpoint adds the passes
// [previous, n) to the same film, and the time is cumulative.
// jittered stratifies over the total sample count (a pass of n samples is
// stratified on its own), so every checkpoint is its own render of n spp from
// an empty film, and its time is that render's.
// Wall time counts integrator->render() only: not the scene build, not the
// film resolve nor the error computation.
//
// Exit status: 0 success, 1 bad input (scene, reference, size or rectangle
// mismatch, unwritable CSV: no CSV is left behind), 2 bad arguments.
#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "accel/accelerator.h"
#include "app/render_settings.h"
#include "core/parallel.h"
#include "core/stopwatch.h"
#include "io/atomic_file.h"
#include "io/image_error.h"
#include "io/image_io.h"
#include "render/film/film.h"
#include "render/integrators/integrator.h"
#include "render/render_scene.h"
#include "scene/loader.h"

namespace {

constexpr int kExitFailure = 1;
constexpr int kExitUsage = 2;

using pt::Clock;
using pt::seconds_since;

struct Options {
  std::string scene, reference, csv, rect, accel = "bvh", sampler = "random";
  std::string checkpoints, seeds = "1";
  int threads = 0, width = 0, height = 0, max_depth = -1;
  double max_seconds = 0.0;
};

// "a,b,c" of integers; false on anything else.
bool parse_list(const std::string& text, std::vector<long long>& out) {
  out.clear();
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    if (item.empty()) return false;
    std::size_t used = 0;
    try {
      out.push_back(std::stoll(item, &used));
    } catch (const std::exception&) {
      return false;
    }
    if (used != item.size()) return false;
  }
  return !out.empty();
}

struct Row {
  uint64_t seed;
  int spp;
  double seconds;
  pt::ImageError error;
};

// The rows of one seed; false (with `error`) if the error cannot be computed.
bool run_seed(const pt::RenderScene& scene, const pt::RenderSettings& render, uint64_t seed,
              const std::vector<int>& checkpoints, const pt::Image& reference, const std::optional<pt::ImageRect>& rect,
              double max_seconds, pt::WorkerPool& pool, std::vector<Row>& rows, std::string& error) {
  pt::IntegratorSettings settings = render.integration;
  settings.seed = seed;
  const bool restart = render.equal_passes();  // jittered stratifies over a pass's sample count
  pt::Film film(scene.width, scene.height);
  double elapsed = 0.0;
  int done = 0;
  for (const int n : checkpoints) {
    if (restart) {
      film.clear();
      settings.first_sample = 0;
      settings.spp = n;
      elapsed = 0.0;
    } else {
      settings.first_sample = done;
      settings.spp = n - done;
    }
    const std::unique_ptr<pt::Integrator> integrator = render.make_integrator(settings);
    const auto t = Clock::now();
    integrator->render(scene, film, pool);
    elapsed += seconds_since(t);
    done = n;
    Row row{settings.seed, n, elapsed, {}};
    if (!pt::compute_image_error(film.image(), reference, rect, row.error, error)) return false;
    rows.push_back(row);
    if (max_seconds > 0.0 && elapsed >= max_seconds) break;
  }
  return true;
}

std::string csv_text(const Options& o, const std::string& sampler, const std::vector<Row>& rows) {
  std::string text = "scene,accel,sampler,seed,spp,seconds,mse,rel_mse,rmse\n";
  char line[512];
  for (const Row& r : rows) {
    std::snprintf(line, sizeof line, "%s,%s,%s,%llu,%d,%.6f,%.9g,%.9g,%.9g\n", o.scene.c_str(), o.accel.c_str(),
                  sampler.c_str(), static_cast<unsigned long long>(r.seed), r.spp, r.seconds, r.error.mse,
                  r.error.rel_mse, r.error.rmse);
    text += line;
  }
  return text;
}

int run(const Options& o) {
  // Arguments that need more than CLI11's checks.
  std::vector<long long> values, seed_values;
  if (!parse_list(o.checkpoints, values)) {
    std::cerr << "error: --checkpoints " << o.checkpoints << ": expected a comma-separated list of integers\n";
    return kExitUsage;
  }
  std::vector<int> checkpoints;
  for (const long long v : values) {
    if (v < 1 || v > (1 << 24) || (!checkpoints.empty() && v <= checkpoints.back())) {
      std::cerr << "error: --checkpoints " << o.checkpoints
                << ": sample counts must be increasing, from 1 to 16777216\n";
      return kExitUsage;
    }
    checkpoints.push_back(static_cast<int>(v));
  }
  if (!parse_list(o.seeds, seed_values)) {
    std::cerr << "error: --seeds " << o.seeds << ": expected a comma-separated list of integers\n";
    return kExitUsage;
  }
  std::optional<pt::ImageRect> rect;
  if (!o.rect.empty()) {
    pt::ImageRect r;
    if (!pt::parse_image_rect(o.rect, r)) {
      std::cerr << "error: --rect " << o.rect << ": expected X,Y,W,H (integers, W and H > 0)\n";
      return kExitUsage;
    }
    rect = r;
  }
  pt::AccelKind accel = pt::AccelKind::Bvh;
  pt::parse_accel_kind(o.accel, accel);  // validated by CLI11
  const pt::SamplerType sampler = pt::parse_sampler_type(o.sampler).value_or(pt::SamplerType::Random);

  // Inputs.
  pt::Image reference;
  std::string error;
  if (!pt::read_image(o.reference, reference, error)) {
    std::cerr << "error: " << o.reference << ": " << error << "\n";
    return kExitFailure;
  }
  pt::Diagnostics diag;
  const std::optional<pt::SceneDescription> desc = pt::load_scene(o.scene, pt::LoadOptions{}, diag);
  if (!desc || diag.has_errors()) {
    std::cerr << diag.format();
    return kExitFailure;
  }
  // The path integrator with the scene's filter and clamp, as the pathtracer resolves them.
  pt::SettingsOverrides overrides;
  overrides.integrator = "path";
  overrides.max_depth = o.max_depth;
  overrides.sampler = sampler;
  overrides.width = o.width;
  overrides.height = o.height;
  pt::RenderSettings settings;
  pt::resolve_render_settings(*desc, overrides, settings, diag);  // "path" is registered
  pt::WorkerPool pool(o.threads);
  const std::unique_ptr<pt::RenderScene> scene =
      pt::build_render_scene(*desc, settings.build_options(accel), pool, diag);
  if (!scene) {
    std::cerr << diag.format();
    return kExitFailure;
  }
  if (scene->width != reference.width || scene->height != reference.height) {
    std::cerr << "error: " << o.reference << ": " << reference.width << "x" << reference.height
              << " reference for a " << scene->width << "x" << scene->height << " render of " << o.scene << "\n";
    return kExitFailure;
  }

  if (pt::ImageError check; !pt::compute_image_error(reference, reference, rect, check, error)) {
    std::cerr << "error: " << o.reference << ": " << error << "\n";  // a rectangle outside the image
    return kExitFailure;
  }

  std::vector<Row> rows;
  for (const long long seed : seed_values) {
    if (!run_seed(*scene, settings, static_cast<uint64_t>(seed), checkpoints, reference, rect, o.max_seconds, pool,
                  rows, error)) {
      std::cerr << "error: " << o.scene << " vs " << o.reference << ": " << error << "\n";
      return kExitFailure;
    }
  }
  if (!pt::write_text_file(o.csv, csv_text(o, o.sampler, rows), error)) {
    std::cerr << "error: " << error << "\n";
    return kExitFailure;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"pt-converge: error against a reference at checkpoint sample counts of one render (CSV)"};
  Options o;
  app.add_option("scene", o.scene, "Scene file")->required();
  app.add_option("--reference", o.reference, "Reference image (same size as the render)")->required();
  app.add_option("--checkpoints", o.checkpoints, "Increasing sample counts N1,N2,...")->required();
  app.add_option("--csv", o.csv, "Output CSV (written whole, or not at all)")->required();
  app.add_option("--rect", o.rect, "Measure only the rectangle X,Y,W,H (pixels, y down from the top)");
  app.add_option("--accel", o.accel, "Acceleration structure")->check(CLI::IsMember(pt::accel_kind_names()));
  app.add_option("--sampler", o.sampler, "Sampler")->check(CLI::IsMember(pt::sampler_type_names()));
  app.add_option("--seeds", o.seeds, "Seeds S1,S2,... (one run per seed)");
  app.add_option("--threads", o.threads, "Worker threads (default: all)")->check(CLI::NonNegativeNumber);
  const int max_side = pt::ResolutionLimits{}.max_resolution;
  app.add_option("--width", o.width, "Image width override")->check(CLI::Range(1, max_side));
  app.add_option("--height", o.height, "Image height override")->check(CLI::Range(1, max_side));
  app.add_option("--max-depth", o.max_depth, "Path length limit (default: the scene's)")->check(CLI::Range(0, 1024));
  app.add_option("--max-seconds", o.max_seconds, "Stop a seed after the checkpoint that passes T seconds")
      ->check(CLI::NonNegativeNumber);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : kExitUsage;
  }
  return run(o);
}
