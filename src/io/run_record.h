// The run record (`pathtracer --report run.json`): what was rendered, with
// which settings and software, how long each phase took, how fast the render
// went and how far it got. A machine-readable companion to the image, read by
// the benchmark tools in tools/ (layout in docs/cli.md).
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace pt {

struct PhaseTimings {
  double parse = 0;         // reading and validating the scene file (excludes mesh_load)
  double mesh_load = 0;     // reading the mesh files it names (PLY, OBJ)
  double texture_load = 0;  // decoding the textures materials use and the environment map
  double scene_build = 0;   // geometry conversion, lights (excludes texture_load and accel_build)
  double accel_build = 0;   // acceleration structure
  double render = 0;
  double write = 0;        // all output images
  double total = 0;        // sum of the above
};

// Libraries the executable runs with, as they report themselves at run time
// where they can (compile-time versions otherwise, named so).
struct SoftwareVersions {
  std::string pathtracer;
  std::string embree;                 // rtcGetDeviceProperty(RTC_DEVICE_PROPERTY_VERSION)
  std::string embree_tasking;         // RTC_DEVICE_PROPERTY_TASKING_SYSTEM: "internal", "TBB" or "PPL"
  std::string embree_native_packets;  // RTC_DEVICE_PROPERTY_NATIVE_RAY{4,8,16}_SUPPORTED, e.g. "4 8"
  std::string openimageio;           // the image module's once loaded, else the one it was built with
  std::string image_module;           // where the image module is (imagelib/image_library.h)
  std::string image_module_origin;    // why there ("beside the executable", ...)
  std::string openexr;                // the headers' OPENEXR_VERSION_STRING
  std::string opencolorio;
  std::string tbb;
  std::string compiler;
  std::string compiler_flags;
  std::string build_type;
};

struct RunRecord {
  std::string scene;
  std::vector<std::string> overrides;  // --set key=value, in order
  std::string integrator;
  std::string sampler;
  int width = 0, height = 0, max_depth = 0;
  int spp = 0;                 // samples per pixel reached (complete passes)
  int target_spp = 0;          // 0: no target (time budget only)
  double time_budget = 0;      // seconds; 0: none
  int passes = 0;
  int pass_spp = 0;            // samples per pass when the passes have a fixed size; 0: adaptive (time budget)
  int resumed_spp = 0;         // samples per pixel read from --resume's checkpoint
  double last_pass_seconds = 0;  // the last pass's render time (a pass, once started, completes)
  bool partial = false;        // stopped by a signal before the target/budget
  int signal = 0;              // the signal that stopped it, 0 if none
  uint64_t seed = 0;
  std::string filter = "box";  // pixel filter (path integrator)
  std::string light_sampler;   // RenderStamp::light_sampler
  int light_guiding = 0;       // RenderStamp::light_guiding
  int path_guiding = 0;        // RenderStamp::path_guiding
  float shadow_terminator_offset = 0.0f;  // RenderStamp::shadow_terminator_offset
  float clamp = 0.0f;          // firefly clamp; 0 = off (recorded either way)
  int threads = 0;
  std::string accel_backend;   // AccelStats::backend
  std::size_t accel_memory_bytes = 0;
  std::size_t accel_build_peak_bytes = 0;  // AccelStats::build_peak_bytes (0: not known)
  std::size_t primitive_count = 0;
  PhaseTimings timings;
  int64_t pixel_samples = 0;   // camera samples rendered by this run
  double samples_per_second = 0;
  int64_t rays = 0;            // rays traced by this run (camera, bounce, shadow)
  double rays_per_second = 0;
  // CPU time (user + system, every thread) of the process during the render
  // phase: with `threads`, how well the threads were used on a loaded machine.
  double render_cpu_seconds = 0;
  // Non-finite samples (counted by the film, added as black; docs/output.md):
  // per kind, and the first one, which `pathtracer --replay X,Y,N` reproduces.
  struct NonFinite {
    uint64_t nan = 0, pos_inf = 0, neg_inf = 0;
    bool has_first = false;
    int x = 0, y = 0, sample = 0;
  } non_finite;
  // Outputs (docs/output.md): the files, the window rendered (the EXR's data
  // window; the whole frame without a crop), the beauty's and each AOV's type.
  std::vector<std::string> outputs;
  struct Window {
    int x = 0, y = 0, width = 0, height = 0;
  } crop;
  std::string beauty_type = "float";
  std::vector<std::pair<std::string, std::string>> aovs;  // (name, "half" or "float"), in file order
  // Checkpoints: --checkpoint and --checkpoint-every, --resume (empty: none).
  std::string checkpoint;
  double checkpoint_every = 0;
  std::string resumed_from;
  // Display images (PNG, JPEG, PPM): the scene's transform ("srgb", "linear",
  // "cgr"), the exposure in stops, the OCIO names asked for (empty: defaults)
  // and the pipeline as built (DisplayEncoder::description).
  struct Display {
    std::string transform = "srgb";
    float exposure = 0;
    std::string view, display, look, ocio_config, pipeline;
  } display;
  // Model files the scene imported (docs/importing.md): what each brought in
  // and what it left out, as (what, count) pairs.
  struct Import {
    std::string file, format;
    double seconds = 0;
    std::vector<std::pair<std::string, uint64_t>> imported, skipped;
  };
  std::vector<Import> imports;
  uint64_t memory_estimate_bytes = 0;  // the pre-flight estimate
  std::vector<std::pair<std::string, uint64_t>> memory_estimate_parts;  // its parts (app/memory_estimate.h)
  uint64_t peak_memory_bytes = 0;      // getrusage ru_maxrss
  SoftwareVersions versions;
};

std::string run_record_json(const RunRecord& record);
// Written atomically; false with `error` set on failure.
bool write_run_record(const std::string& path, const RunRecord& record, std::string& error);

}  // namespace pt
