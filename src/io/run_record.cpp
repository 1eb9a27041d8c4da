#include "io/run_record.h"

#include <nlohmann/json.hpp>

#include "io/atomic_file.h"

namespace pt {

std::string run_record_json(const RunRecord& r) {
  const PhaseTimings& t = r.timings;
  const SoftwareVersions& v = r.versions;
  nlohmann::ordered_json j = {
      {"software",
       {{"name", "pathtracer"},
        {"version", v.pathtracer},
        {"embree", {{"version", v.embree}, {"tasking_system", v.embree_tasking},
                    {"native_packets", v.embree_native_packets}}},
        {"openimageio", v.openimageio},
        {"openexr", v.openexr},
        {"opencolorio", v.opencolorio},
        {"tbb", v.tbb},
        {"compiler", {{"name", v.compiler}, {"flags", v.compiler_flags}, {"build_type", v.build_type}}}}},
      {"scene", r.scene},
      {"overrides", r.overrides},
      {"image", {{"width", r.width}, {"height", r.height}, {"spp", r.spp}, {"integrator", r.integrator},
                 {"sampler", r.sampler}, {"max_depth", r.max_depth}, {"seed", r.seed}, {"filter", r.filter},
                 {"light_sampler", r.light_sampler}, {"light_guiding", r.light_guiding},
                 {"path_guiding", r.path_guiding},
                 {"shadow_terminator_geometry_offset", r.shadow_terminator_offset}, {"clamp", r.clamp}}},
      {"progress", {{"spp_reached", r.spp}, {"target_spp", r.target_spp}, {"time_budget", r.time_budget},
                    {"passes", r.passes},
                    {"pass_spp", r.pass_spp > 0 ? nlohmann::ordered_json(r.pass_spp) : nlohmann::ordered_json("adaptive")},
                    {"resumed_spp", r.resumed_spp}, {"last_pass_seconds", r.last_pass_seconds},
                    {"partial", r.partial}, {"signal", r.signal}}},
      {"threads", r.threads},
      {"accel", {{"backend", r.accel_backend}, {"memory_bytes", r.accel_memory_bytes},
                 {"build_peak_bytes", r.accel_build_peak_bytes},
                 {"primitive_count", r.primitive_count}, {"build_seconds", t.accel_build}}},
      {"timings", {{"parse", t.parse}, {"mesh_load", t.mesh_load}, {"texture_load", t.texture_load},
                   {"scene_build", t.scene_build}, {"accel_build", t.accel_build}, {"render", t.render},
                   {"write", t.write}, {"total", t.total}}},
      {"performance", {{"pixel_samples", r.pixel_samples}, {"samples_per_second", r.samples_per_second},
                       {"rays", r.rays}, {"rays_per_second", r.rays_per_second},
                       {"render_cpu_seconds", r.render_cpu_seconds}}},
      {"memory", {{"estimate_bytes", r.memory_estimate_bytes}, {"peak_rss_bytes", r.peak_memory_bytes}}},
  };
  nlohmann::ordered_json parts = nlohmann::ordered_json::object();
  for (const auto& [name, bytes] : r.memory_estimate_parts) parts[name] = bytes;
  j["memory"]["estimate_parts"] = parts;
  nlohmann::ordered_json aovs = nlohmann::ordered_json::array();
  for (const auto& [name, type] : r.aovs) aovs.push_back({{"name", name}, {"type", type}});
  j["output"] = {{"files", r.outputs},
                 {"crop", {{"x", r.crop.x}, {"y", r.crop.y}, {"width", r.crop.width}, {"height", r.crop.height}}},
                 {"beauty_type", r.beauty_type},
                 {"aovs", aovs}};
  const auto path_or_null = [](const std::string& p) {
    return p.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(p);
  };
  j["checkpoint"] = {{"file", path_or_null(r.checkpoint)},
                     {"every_seconds", r.checkpoint_every},
                     {"resumed_from", path_or_null(r.resumed_from)}};
  const RunRecord::Display& d = r.display;
  j["display"] = {{"transform", d.transform}, {"exposure", d.exposure}, {"view", d.view},
                  {"display", d.display},     {"look", d.look},         {"ocio_config", path_or_null(d.ocio_config)},
                  {"pipeline", d.pipeline}};
  nlohmann::ordered_json imports = nlohmann::ordered_json::array();
  for (const RunRecord::Import& i : r.imports) {
    nlohmann::ordered_json imported = nlohmann::ordered_json::object(), skipped = nlohmann::ordered_json::object();
    for (const auto& [what, n] : i.imported) imported[what] = n;
    for (const auto& [what, n] : i.skipped) skipped[what] = n;
    imports.push_back({{"file", i.file}, {"format", i.format}, {"seconds", i.seconds}, {"imported", imported},
                       {"skipped", skipped}});
  }
  j["imports"] = imports;
  const RunRecord::NonFinite& nf = r.non_finite;
  j["non_finite"] = {{"nan", nf.nan}, {"pos_inf", nf.pos_inf}, {"neg_inf", nf.neg_inf},
                     {"first", nf.has_first ? nlohmann::ordered_json{{"x", nf.x}, {"y", nf.y}, {"sample", nf.sample}}
                                            : nlohmann::ordered_json(nullptr)}};
  return j.dump(2) + "\n";
}

bool write_run_record(const std::string& path, const RunRecord& record, std::string& error) {
  return write_text_file(path, run_record_json(record), error);
}

}  // namespace pt
