#include "io/run_record.h"

#include <nlohmann/json.hpp>

#include "io/atomic_file.h"

namespace pt {

std::string run_record_json(const RunRecord& r) {
  const PhaseTimings& t = r.timings;
  const nlohmann::ordered_json j = {
      {"software", {{"name", "pathtracer"}, {"version", r.software_version}}},
      {"scene", r.scene},
      {"image", {{"width", r.width}, {"height", r.height}, {"spp", r.spp}, {"integrator", r.integrator},
                 {"max_depth", r.max_depth}, {"seed", r.seed}, {"filter", r.filter}, {"clamp", r.clamp}}},
      {"threads", r.threads},
      {"accel", {{"backend", r.accel_backend}, {"memory_bytes", r.accel_memory_bytes},
                 {"primitive_count", r.primitive_count}, {"build_seconds", t.accel_build}}},
      {"timings", {{"parse", t.parse}, {"scene_build", t.scene_build}, {"accel_build", t.accel_build},
                   {"render", t.render}, {"write", t.write}, {"total", t.total}}},
  };
  return j.dump(2) + "\n";
}

bool write_run_record(const std::string& path, const RunRecord& record, std::string& error) {
  return write_text_file(path, run_record_json(record), error);
}

}  // namespace pt
