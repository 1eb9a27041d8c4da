// bench_accel: our BVH against Embree on the benchmark scenes (the Stanford
// bunny, Crytek Sponza, a procedural sphere of about a million triangles, the
// Path of Light example), measured in one run: build time, memory, and Mrays/s
// for camera, shadow (any-hit) and diffuse-bounce rays with 1 and with all
// threads; plus the BVH's tree statistics, its work per ray (nodes and triangles
// tested by camera and diffuse rays) and a cross-check of both backends.
// Three accelerators are timed: bare Embree (the yardstick, embree_reference.h:
// Embree called directly), the --accel=embree backend, and --accel=bvh.
//
//   bench_accel [--scenes bunny,sponza,sphere,path-of-light] [--width 800 --height 600]
//               [--builds 5] [--repetitions 7] [--threads N] [--sphere-triangles 1000000]
//               [--clock wall|cpu] [--quick] [--json docs/bench/accel.json] [--markdown docs/bench/accel.md]
//               [--note TEXT]
//
// --clock cpu times every pass and build in CPU time of the process (every
// thread) instead of wall-clock time: on a machine shared with other jobs it
// counts the time the benchmark ran, not the time it waited for a core.
//
// Shared assets that are absent are skipped with a message.
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include <CLI/CLI.hpp>

#include "accel/accelerator.h"
#include "accel/bvh/bvh_accel.h"
#include "bench_scene.h"
#include "core/parallel.h"
#include "embree_reference.h"
#include "io/atomic_file.h"
#include "ray_sets.h"
#include "report.h"
#include "throughput.h"

namespace {

using namespace pt;
using namespace pt::bench;

struct Options {
  std::vector<std::string> scenes = builtin_scene_names();
  int width = 800, height = 600;
  int builds = 5, repetitions = 7;
  int threads = 0;  // 0: all hardware threads
  std::size_t sphere_triangles = 1'000'000;
  bool quick = false;
  std::string clock = "wall";
  bool cpu_clock = false;
  std::string json_path, markdown_path, note;
};

// The three load averages of /proc/loadavg ("" where it does not exist).
std::string load_average() {
  std::ifstream in("/proc/loadavg");
  std::string a, b, c;
  in >> a >> b >> c;
  return in ? a + " " + b + " " + c : std::string("unknown");
}

std::string lscpu() {
  std::string out;
  if (FILE* p = popen("lscpu 2>/dev/null", "r")) {
    char buffer[4096];
    std::size_t n;
    while ((n = std::fread(buffer, 1, sizeof buffer, p)) > 0) out.append(buffer, n);
    pclose(p);
  }
  return out.empty() ? std::string("(lscpu unavailable)\n") : out;
}

std::unique_ptr<Accelerator> build(AccelKind kind, const SceneGeometry& g, WorkerPool& pool) {
  Diagnostics diag;
  auto accel = build_accelerator(kind, g, pool, diag);
  if (!accel) std::cerr << "error: building " << accel_kind_name(kind) << ": " << diag.format() << "\n";
  return accel;
}

// The accelerators timed side by side, in the order of ThreadRun's members.
struct Contenders {
  std::unique_ptr<BareEmbree> reference;  // called without a virtual call (trace_pass on its own type)
  std::unique_ptr<Accelerator> embree, bvh;
  BackendRun* runs[3];
  const Accelerator* accel(int i) const { return i == 0 ? reference.get() : i == 1 ? embree.get() : bvh.get(); }
  Pass trace(int i, const RaySet& set, Query query, WorkerPool& pool) const {
    return i == 0 ? trace_pass(*reference, set.rays, query, pool) : trace_pass(*accel(i), set.rays, query, pool);
  }
};

// Times one ray set: a warm-up pass each, then `repetitions` rounds of one
// pass each, the order rotating from round to round.
void time_set(const Contenders& c, const RaySet& set, Query query, WorkerPool& pool, int repetitions, bool cpu_clock,
              Measured BackendRun::*field, std::size_t BackendRun::*hits) {
  for (int i = 0; i < 3; ++i) c.trace(i, set, query, pool);
  std::vector<double> mrays[3];
  const double n = static_cast<double>(set.rays.size());
  for (int rep = 0; rep < repetitions; ++rep) {
    for (int k = 0; k < 3; ++k) {
      const int i = (rep + k) % 3;
      const Pass p = c.trace(i, set, query, pool);
      mrays[i].push_back(n / (cpu_clock ? p.cpu_seconds : p.seconds) * 1e-6);
      c.runs[i]->*hits = p.hits;
    }
  }
  for (int i = 0; i < 3; ++i) c.runs[i]->*field = summarize(mrays[i]);
}

std::unique_ptr<BareEmbree> build_reference(const SceneGeometry& g, WorkerPool& pool) {
  Diagnostics diag;
  auto accel = build_embree_reference(g, pool, diag);
  if (!accel) std::cerr << "error: building the Embree reference: " << diag.format() << "\n";
  return accel;
}

// Builds each accelerator o.builds times, the whole build call timed with the
// clock asked for, in rotating order; leaves the last builds in `c`.
bool time_builds(Contenders& c, const SceneGeometry& g, WorkerPool& pool, const Options& o,
                 std::vector<double> (&seconds)[3]) {
  for (int k = 0; k < o.builds; ++k) {
    for (int j = 0; j < 3; ++j) {
      const int i = (k + j) % 3;
      const double cpu = process_cpu_seconds();
      const auto wall = std::chrono::steady_clock::now();
      if (i == 0) {
        c.reference.reset();
        c.reference = build_reference(g, pool);
      } else {
        std::unique_ptr<Accelerator>& a = i == 1 ? c.embree : c.bvh;
        a.reset();
        a = build(i == 1 ? AccelKind::Embree : AccelKind::Bvh, g, pool);
      }
      seconds[i].push_back(o.cpu_clock ? process_cpu_seconds() - cpu
                                       : std::chrono::duration<double>(std::chrono::steady_clock::now() - wall).count());
    }
    if (!c.reference || !c.embree || !c.bvh) return false;
  }
  return true;
}

bool measure(const BenchScene& scene, const Options& o, int all_threads, SceneResult& r) {
  r.name = scene.name;
  r.source = scene.source;
  r.triangles = scene.triangles;
  r.primitives = scene.primitives;
  r.width = scene.width;
  r.height = scene.height;

  RaySets rays;
  {
    WorkerPool pool(all_threads);
    const auto reference = build(AccelKind::Embree, scene.geometry, pool);
    const auto bvh = build(AccelKind::Bvh, scene.geometry, pool);
    if (!reference || !bvh) return false;
    rays = make_ray_sets(scene, *reference, pool);
    r.tree = *bvh::tree_stats(*bvh);
    r.bvh_camera_work = count_work(*bvh, rays.camera.rays, pool);
    r.bvh_diffuse_work = count_work(*bvh, rays.diffuse.rays, pool);
    r.check = cross_check(*reference, *bvh, scene.geometry, rays, pool);
  }
  r.camera_rays = rays.camera.rays.size();
  r.shadow_rays = rays.shadow.rays.size();
  r.diffuse_rays = rays.diffuse.rays.size();
  std::cout << "  cross-check: " << describe_rate(r.check) << ", " << r.check.camera.tie + r.check.diffuse.tie
            << " ties\n";

  std::vector<int> counts{1};
  if (all_threads > 1) counts.push_back(all_threads);
  for (const int threads : counts) {
    WorkerPool pool(threads);
    ThreadRun run;
    run.threads = threads;
    Contenders c;
    c.runs[0] = &run.reference;
    c.runs[1] = &run.embree;
    c.runs[2] = &run.bvh;
    std::vector<double> seconds[3];
    if (!time_builds(c, scene.geometry, pool, o, seconds)) return false;
    for (int i = 0; i < 3; ++i) {
      const AccelStats stats = c.accel(i)->stats();
      c.runs[i]->backend = stats.backend;
      c.runs[i]->build_seconds = summarize(seconds[i]);
      c.runs[i]->memory_bytes = stats.memory_bytes;
    }
    time_set(c, rays.camera, Query::Nearest, pool, o.repetitions, o.cpu_clock, &BackendRun::camera,
             &BackendRun::camera_hits);
    time_set(c, rays.shadow, Query::Any, pool, o.repetitions, o.cpu_clock, &BackendRun::shadow,
             &BackendRun::shadow_hits);
    time_set(c, rays.diffuse, Query::Nearest, pool, o.repetitions, o.cpu_clock, &BackendRun::diffuse,
             &BackendRun::diffuse_hits);
    const auto line = [](const char* what, const BackendRun& b) {
      std::printf("    %-16s build %8.1f ms, camera %6.2f, shadow %6.2f, diffuse %6.2f Mrays/s\n", what,
                  1e3 * b.build_seconds.median, b.camera.median, b.shadow.median, b.diffuse.median);
    };
    std::printf("  %d thread%s:\n", threads, threads == 1 ? "" : "s");
    line("bare Embree", run.reference);
    line("--accel=embree", run.embree);
    line("--accel=bvh", run.bvh);
    r.runs.push_back(run);
  }
  return true;
}

// The command as run, with a --note's text left out (it is printed apart).
std::string command_line(int argc, char** argv) {
  std::string s = "bench_accel";
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--note" && i + 1 < argc) {
      s += " --note ...";
      ++i;
    } else if (arg.rfind("--note=", 0) == 0) {
      s += " --note=...";
    } else {
      s += " " + arg;
    }
  }
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"bench_accel: our BVH against Embree (build time, memory, Mrays/s, tree statistics, cross-check)"};
  Options o;
  app.add_option("--scenes", o.scenes, "Scenes: bunny, sponza, sphere, path-of-light, or scene/mesh files")->delimiter(',');
  app.add_option("--width", o.width, "Camera resolution for meshes and scene files")->check(CLI::Range(1, 16384));
  app.add_option("--height", o.height, "Camera resolution for bare meshes")->check(CLI::Range(1, 16384));
  app.add_option("--builds", o.builds, "Builds per backend and thread count (median)")->check(CLI::Range(1, 100));
  app.add_option("--repetitions", o.repetitions, "Timed passes per ray set (median)")->check(CLI::Range(1, 100));
  app.add_option("--threads", o.threads, "The 'all threads' count (default: hardware threads)")->check(CLI::Range(0, 1024));
  app.add_option("--sphere-triangles", o.sphere_triangles, "Triangles of the procedural sphere");
  app.add_option("--clock", o.clock, "wall: wall-clock time; cpu: CPU time of the process (a shared machine)")
      ->check(CLI::IsMember({"wall", "cpu"}));
  app.add_flag("--quick", o.quick, "Small settings for a quick check: 256x192, 2 builds, 3 passes, 100k-triangle sphere");
  app.add_option("--json", o.json_path, "Write the JSON record here");
  app.add_option("--markdown", o.markdown_path, "Write the markdown report here");
  app.add_option("--note", o.note, "A remark printed at the top of the markdown report");
  CLI11_PARSE(app, argc, argv);
  o.cpu_clock = o.clock == "cpu";
  if (o.quick) {
    o.width = 256;
    o.height = 192;
    o.builds = 2;
    o.repetitions = 3;
    o.sphere_triangles = 100'000;
  }
  const int all_threads = o.threads > 0 ? o.threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));

  Report report;
  report.machine = lscpu();
  report.load_before = load_average();
  report.note = o.note;
  report.command = command_line(argc, argv);
  report.settings = Settings{o.width, o.height, o.builds, o.repetitions, o.sphere_triangles, o.clock};
  for (const std::string& name : o.scenes) {
    BenchScene scene;
    bool missing = false;
    std::string error;
    std::cout << name << ": loading\n" << std::flush;
    if (!load_bench_scene(SceneRequest{name, o.width, o.height, o.sphere_triangles}, scene, missing, error)) {
      if (missing) {
        std::cout << "  skipped: " << error << "\n";
        report.skipped.push_back(name + ": " + error);
        continue;
      }
      std::cerr << "error: " << name << ": " << error << "\n";
      return 1;
    }
    std::cout << "  " << scene.primitives << " primitives\n" << std::flush;
    SceneResult result;
    if (!measure(scene, o, all_threads, result)) return 1;
    report.scenes.push_back(std::move(result));
  }

  report.load_after = load_average();
  std::string error;
  if (!o.json_path.empty() && !write_text_file(o.json_path, to_json(report), error)) {
    std::cerr << "error: " << error << "\n";
    return 1;
  }
  if (!o.markdown_path.empty() && !write_text_file(o.markdown_path, to_markdown(report), error)) {
    std::cerr << "error: " << error << "\n";
    return 1;
  }
  if (o.json_path.empty() && o.markdown_path.empty()) std::cout << to_markdown(report);
  return 0;
}
