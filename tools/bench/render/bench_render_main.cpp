// bench_render: the path tracer's performance measurements, as JSON.
//
//   bench_render time-to-error SCENE --reference EXR [--accel A] [--threads N] [--pass-spp K]
//                [--rmse X] [--relmse Y] [--max-seconds S] [--runs R] [--json FILE]
//   bench_render compare SCENE --reference EXR [--accel A ...] [--threads N] [--spp K] [--pass-spp P]
//                [--seed S] [--output EXR] [--error-map EXR] [--json FILE]
//   bench_render throughput SCENE [--accel A ...] [--threads N] [--spp K] [--runs R] [--json FILE]
//   bench_render profile SCENE [--accel A ...] [--threads N] [--spp K] [--json FILE]
//
// Every subcommand takes --sampler random|jittered|sobol (default: the path
// integrator's default) and --rr-depth / --rr-threshold (Russian roulette,
// default: the integrator's), and records them in its JSON.
//
// tools/bench/render/run_benchmarks.py runs the set documented in
// docs/performance.md and writes docs/bench/cornell.* and docs/bench/render.*.
#include <algorithm>
#include <fstream>
#include <functional>
#include <optional>
#include <iostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "io/image_io.h"
#include "measurements.h"

namespace {

using nlohmann::ordered_json;
using namespace pt;
using namespace pt::bench;

struct Common {
  std::string scene;
  std::vector<std::string> accels{"embree"};
  int threads = 2;
  int runs = 3;
  std::string json;
  std::string sampler = sampler_type_name(IntegratorSettings{}.sampler);
  SettingsOverrides overrides;  // Russian roulette (--rr-depth, --rr-threshold) and the sampler
};

// Loads the scene with the sampler and Russian roulette of `c`; nullopt after printing why.
std::optional<LoadedScene> load_for(const Common& c, AccelKind accel, WorkerPool& pool) {
  SettingsOverrides overrides = c.overrides;
  overrides.sampler = parse_sampler_type(c.sampler).value_or(overrides.sampler);
  return load(c.scene, accel, overrides, pool);
}

// Measures every backend of `c` in turn, each with a worker pool and scene of
// its own, and writes the JSON array of their records: scene_json and the
// thread count, then what `measure` adds. 1 if a scene fails to load or
// `measure` returns false (after printing why).
using Measure = std::function<bool(const std::string& accel_name, LoadedScene& s, WorkerPool& pool,
                                   ordered_json& record)>;
int measure_each_backend(const Common& c, const Measure& measure);

// The reference image at `path`; false after printing why.
bool read_reference(const std::string& path, Image& reference) {
  std::string error;
  if (read_image(path, reference, error)) return true;
  std::cerr << "bench_render: " << error << '\n';
  return false;
}

double median(std::vector<double> v) {
  if (v.empty()) return -1;
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

bool emit(const ordered_json& j, const std::string& path) {
  if (path.empty()) {
    std::cout << j.dump(2) << '\n';
    return true;
  }
  std::ofstream out(path);
  out << j.dump(2) << '\n';
  return static_cast<bool>(out);
}

ordered_json scene_json(const LoadedScene& s, AccelKind accel) {
  const AccelStats stats = s.scene->accel->stats();
  return {{"scene", s.desc.source_path},
          {"width", s.scene->width},
          {"height", s.scene->height},
          {"max_depth", s.settings.integration.max_depth},
          {"accel", accel_kind_name(accel)},
          {"backend", stats.backend},
          {"sampler", sampler_type_name(s.settings.integration.sampler)},
          {"roulette_depth", s.settings.integration.roulette_depth},
          {"roulette_threshold", s.settings.integration.roulette_threshold},
          {"primitives", stats.primitive_count},
          {"load_seconds", s.load_seconds},
          {"build_seconds", s.build_seconds}};
}

int measure_each_backend(const Common& c, const Measure& measure) {
  ordered_json out = ordered_json::array();
  for (const std::string& name : c.accels) {
    AccelKind accel;
    parse_accel_kind(name, accel);
    WorkerPool pool(c.threads);
    std::optional<LoadedScene> s = load_for(c, accel, pool);
    if (!s) return 1;
    ordered_json j = scene_json(*s, accel);
    j["threads"] = pool.threads();
    if (!measure(name, *s, pool, j)) return 1;
    out.push_back(std::move(j));
  }
  return emit(out, c.json) ? 0 : 1;
}

int run_time_to_error(const Common& c, const std::string& reference_path, int pass_spp, double rmse, double relmse,
                      double max_seconds) {
  Image reference;
  if (!read_reference(reference_path, reference)) return 1;
  return measure_each_backend(c, [&](const std::string& name, LoadedScene& s, WorkerPool& pool,
                                     ordered_json& j) {
    if (s.scene->width != reference.width || s.scene->height != reference.height) {
      std::cerr << "bench_render: the reference is " << reference.width << "x" << reference.height << '\n';
      return false;
    }
    ordered_json runs = ordered_json::array();
    std::vector<double> t_rmse, t_relmse;
    for (int r = 0; r < c.runs; ++r) {
      const TimeToError t = time_to_error(s, reference, pool, pass_spp, rmse, relmse, max_seconds, 1000 + r);
      t_rmse.push_back(t.seconds_to_rmse);
      t_relmse.push_back(t.seconds_to_relmse);
      ordered_json trace = ordered_json::array();
      for (const ErrorPoint& p : t.trace) trace.push_back({p.spp, p.seconds, p.rmse, p.relmse});
      runs.push_back({{"seed", 1000 + r},
                      {"seconds_to_rmse", t.seconds_to_rmse},
                      {"spp_to_rmse", t.spp_to_rmse},
                      {"seconds_to_relmse", t.seconds_to_relmse},
                      {"spp_to_relmse", t.spp_to_relmse},
                      {"final", {{"rmse", t.final_error.rmse},
                                 {"relmse", t.final_error.relmse},
                                 {"mean_ratio", {t.final_error.mean_ratio[0], t.final_error.mean_ratio[1],
                                                 t.final_error.mean_ratio[2]}}}},
                      {"trace_spp_seconds_rmse_relmse", trace}});
      std::cerr << name << " run " << r << ": rmse < " << rmse << " after " << t.seconds_to_rmse << " s ("
                << t.spp_to_rmse << " spp), relmse < " << relmse << " after " << t.seconds_to_relmse << " s\n";
    }
    j["reference"] = reference_path;
    j["pass_spp"] = pass_spp;
    j["target_rmse"] = rmse;
    j["target_relmse"] = relmse;
    j["max_seconds"] = max_seconds;
    j["median_seconds_to_rmse"] = median(t_rmse);
    j["median_seconds_to_relmse"] = median(t_relmse);
    j["runs"] = runs;
    return true;
  });
}

int run_compare(const Common& c, const std::string& reference_path, int spp, int pass_spp, uint64_t seed,
                const std::string& output, const std::string& map_output) {
  Image reference;
  if (!read_reference(reference_path, reference)) return 1;
  return measure_each_backend(c, [&](const std::string& name, LoadedScene& s, WorkerPool& pool,
                                     ordered_json& j) {
    double seconds = 0;
    const std::string path = c.accels.size() > 1 && !output.empty() ? name + "-" + output : output;
    Image image;
    std::string error;
    const ImageError e = converge(s, reference, pool, spp, pass_spp, seed, path, &seconds, &image);
    if (!map_output.empty()) {
      const std::string map_path = c.accels.size() > 1 ? name + "-" + map_output : map_output;
      if (!write_image(map_path, error_map(image, reference), DisplaySettings{}, error)) {
        std::cerr << "bench_render: " << error << '\n';
        return false;
      }
    }
    ordered_json regions = ordered_json::array();
    for (const RegionError& r : error_breakdown(image, reference)) {
      regions.push_back({{"region", r.name}, {"pixel_share", r.pixel_share}, {"error_share", r.error_share},
                         {"rmse", r.rmse}});
      std::cerr << "  " << r.name << ": " << 100 * r.pixel_share << "% of pixels, " << 100 * r.error_share
                << "% of the squared error, rmse " << r.rmse << '\n';
    }
    j["reference"] = reference_path;
    j["spp"] = spp;
    j["seed"] = seed;
    j["seconds"] = seconds;
    j["rmse"] = e.rmse;
    j["relmse"] = e.relmse;
    j["mean_ratio"] = {e.mean_ratio[0], e.mean_ratio[1], e.mean_ratio[2]};
    j["error_by_region"] = regions;
    std::cerr << name << ": " << spp << " spp, rmse " << e.rmse << ", relmse " << e.relmse << ", mean ratio "
              << e.mean_ratio[0] << " " << e.mean_ratio[1] << " " << e.mean_ratio[2] << '\n';
    return true;
  });
}

int run_throughput(const Common& c, int spp) {
  return measure_each_backend(c, [&](const std::string& name, LoadedScene& s, WorkerPool& pool,
                                     ordered_json& j) {
    throughput(s, pool, 1, 1);  // warm-up: page in the scene and the code
    std::vector<double> rates, cpu_rates;
    for (int r = 0; r < c.runs; ++r) {
      const Throughput t = throughput(s, pool, spp, 2000 + r);
      rates.push_back(t.samples_per_second);
      cpu_rates.push_back(t.samples_per_cpu_second);
    }
    j["spp"] = spp;
    j["samples_per_second"] = rates;
    j["median_samples_per_second"] = median(rates);
    // Per second of the process's CPU time (every thread): on a shared machine
    // it counts the time the render ran, not the time it waited for a core.
    j["samples_per_cpu_second"] = cpu_rates;
    j["median_samples_per_cpu_second"] = median(cpu_rates);
    std::cerr << name << ": " << median(rates) << " samples/s\n";
    return true;
  });
}

int run_profile(const Common& c, int spp) {
  return measure_each_backend(c, [&](const std::string& name, LoadedScene& s, WorkerPool& pool,
                                     ordered_json& j) {
    throughput(s, pool, 1, 1);  // warm-up
    std::vector<Profile> runs;
    for (int r = 0; r < c.runs; ++r) runs.push_back(profile(s, pool, spp, 3000 + r));
    std::vector<double> share, render, traversal;
    for (const Profile& p : runs) {
      share.push_back(p.traversal_share());
      render.push_back(p.render_seconds);
      traversal.push_back(p.traversal_seconds);
    }
    j["spp"] = spp;
    j["method"] = "record every ray of a render, replay them through the accelerator alone";
    j["rays"] = runs.front().rays;
    j["shadow_rays"] = runs.front().shadow_rays;
    j["rays_per_sample"] = static_cast<double>(runs.front().rays) / (static_cast<double>(s.scene->width) * s.scene->height * spp);
    j["median_render_seconds"] = median(render);
    j["median_traversal_seconds"] = median(traversal);
    j["median_traversal_share"] = median(share);
    std::cerr << name << ": traversal " << 100 * median(share) << "% of render time\n";
    return true;
  });
}

void add_common(CLI::App& app, Common& c) {
  app.add_option("scene", c.scene, "Scene file")->required();
  app.add_option("--accel", c.accels, "Backends (embree, bvh), one measurement each")
      ->check(CLI::IsMember(accel_kind_names()));
  app.add_option("--threads", c.threads, "Worker threads")->check(CLI::Range(1, 4096));
  app.add_option("--runs", c.runs, "Repetitions (the median is reported)")->check(CLI::Range(1, 1000));
  app.add_option("--json", c.json, "Write the result here (default: standard output)");
  app.add_option("--sampler", c.sampler, "Sampler of the path integrator (docs/samplers.md)")
      ->check(CLI::IsMember(sampler_type_names()));
  app.add_option("--rr-depth", c.overrides.roulette_depth,
                 "Russian roulette: first bounce it applies to (path integrator)")
      ->check(CLI::Range(1, 1 << 20));
  app.add_option("--rr-threshold", c.overrides.roulette_threshold,
                 "Russian roulette: throughput below which paths may end (path integrator)")
      ->check(CLI::Range(1e-6f, 1e6f));
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"bench_render: time to error, samples per second and the traversal share of the path tracer"};
  app.require_subcommand(1);
  Common c;
  std::string reference;
  int pass_spp = 4, spp = 16;
  double rmse = 0.005, relmse = 0.002, max_seconds = 120.0;

  CLI::App* tte = app.add_subcommand("time-to-error", "Render time until RMSE and relative MSE reach their targets");
  add_common(*tte, c);
  tte->add_option("--reference", reference, "Reference image (linear EXR)")->required();
  tte->add_option("--pass-spp", pass_spp, "Samples per pixel per progressive pass")->check(CLI::Range(1, 1 << 16));
  tte->add_option("--rmse", rmse, "Target RMSE");
  tte->add_option("--relmse", relmse, "Target relative MSE, mean of (x - r)^2 / (r^2 + 0.01)");
  tte->add_option("--max-seconds", max_seconds, "Give up after this much render time");

  std::string output;
  CLI::App* cmp = app.add_subcommand("compare", "Render a fixed number of samples and compare with a reference");
  add_common(*cmp, c);
  cmp->add_option("--reference", reference, "Reference image (linear EXR)")->required();
  cmp->add_option("--spp", spp, "Samples per pixel")->check(CLI::Range(1, 1 << 24));
  cmp->add_option("--pass-spp", pass_spp, "Samples per pixel per pass")->check(CLI::Range(1, 1 << 16));
  cmp->add_option("--output", output, "Write the image here (EXR); prefixed with the backend for several");
  std::string map_output;
  uint64_t compare_seed = 4000;
  cmp->add_option("--seed", compare_seed, "Seed of the render");
  cmp->add_option("--error-map", map_output, "Write the per-pixel squared error here (EXR); prefixed likewise");

  CLI::App* thr = app.add_subcommand("throughput", "Samples per second of one render");
  add_common(*thr, c);
  thr->add_option("--spp", spp, "Samples per pixel")->check(CLI::Range(1, 1 << 16));

  CLI::App* prof = app.add_subcommand("profile", "Share of render time spent in ray traversal");
  add_common(*prof, c);
  prof->add_option("--spp", spp, "Samples per pixel")->check(CLI::Range(1, 1 << 16));

  CLI11_PARSE(app, argc, argv);
  if (tte->parsed()) return run_time_to_error(c, reference, pass_spp, rmse, relmse, max_seconds);
  if (cmp->parsed()) return run_compare(c, reference, spp, pass_spp, compare_seed, output, map_output);
  if (thr->parsed()) return run_throughput(c, spp);
  return run_profile(c, spp);
}
