// The run record (`pathtracer --report run.json`): what was rendered, with
// which settings, and how long each phase took. A machine-readable companion
// to the image, read by the benchmark tools in tools/.
#pragma once

#include <cstdint>
#include <string>

namespace pt {

struct PhaseTimings {
  double parse = 0;        // reading and validating the scene file (meshes included)
  double scene_build = 0;  // textures, geometry conversion (excludes accel_build)
  double accel_build = 0;  // acceleration structure
  double render = 0;
  double write = 0;        // all output images
  double total = 0;        // sum of the above
};

struct RunRecord {
  std::string scene;
  std::string integrator;
  int width = 0, height = 0, spp = 0, max_depth = 0;
  uint64_t seed = 0;
  std::string filter = "box";  // pixel filter (path integrator)
  float clamp = 0.0f;          // firefly clamp; 0 = off (recorded either way)
  int threads = 0;
  std::string accel_backend;   // AccelStats::backend
  std::size_t accel_memory_bytes = 0;
  std::size_t primitive_count = 0;
  PhaseTimings timings;
  std::string software_version;
};

std::string run_record_json(const RunRecord& record);
// Written atomically; false with `error` set on failure.
bool write_run_record(const std::string& path, const RunRecord& record, std::string& error);

}  // namespace pt
