// What bench_accel measured, and its two renderings: JSON (every number) and
// the markdown report committed as docs/bench/accel.md.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "accel/bvh/bvh_accel.h"
#include "cross_check.h"
#include "throughput.h"

namespace pt::bench {

struct BackendRun {
  std::string backend;        // AccelStats::backend
  Measured build_seconds;
  std::size_t memory_bytes = 0;
  Measured camera, shadow, diffuse;  // millions of rays per second
  std::size_t camera_hits = 0, shadow_hits = 0, diffuse_hits = 0;
};

struct ThreadRun {
  int threads = 1;
  BackendRun reference;  // Embree with its own triangles (embree_reference.h): the goals' yardstick
  BackendRun embree;     // the --accel=embree backend
  BackendRun bvh;        // the --accel=bvh backend
};

struct SceneResult {
  std::string name, source;
  std::size_t triangles = 0, primitives = 0;
  int width = 0, height = 0;
  std::size_t camera_rays = 0, shadow_rays = 0, diffuse_rays = 0;
  std::vector<ThreadRun> runs;  // 1 thread, then all threads
  bvh::SceneTreeStats tree;
  WorkPerRay bvh_camera_work, bvh_diffuse_work;  // the BVH's nodes and primitives tested per ray
  CrossCheck check;             // the --accel=embree backend against the BVH, on the same rays
};

struct Settings {
  int width = 0, height = 0;
  int builds = 0, repetitions = 0;
  std::size_t sphere_triangles = 0;
  std::string clock = "wall";  // "wall" or "cpu" (process CPU time)
};

struct Report {
  std::string machine;         // lscpu output
  std::string load_before, load_after;  // /proc/loadavg at the start and the end of the run
  std::string note;            // --note: a remark printed at the top of the markdown
  std::string command;         // how the report was produced
  Settings settings;
  std::vector<SceneResult> scenes;
  std::vector<std::string> skipped;  // "sponza: '...' is not available"
};

std::string to_json(const Report& report);
std::string to_markdown(const Report& report);

}  // namespace pt::bench
