#include "report.h"

#include <algorithm>
#include <cstdio>
#include <sstream>

#include <nlohmann/json.hpp>

namespace pt::bench {

namespace {

using nlohmann::json;

// The goals relative to bare Embree, measured in the same run: our BVH's
// throughput (issue 18; build time and memory from issue 3) and the Embree
// backend's throughput (issue 18: within 5%).
constexpr double kCameraGoal = 0.95, kShadowGoal = 0.95, kDiffuseGoal = 0.95, kBuildGoal = 1.5, kMemoryGoal = 1.0;
constexpr double kBackendGoal = 0.95;

json measured(const Measured& m) { return json{{"median", m.median}, {"min", m.min}, {"max", m.max}}; }

json backend_json(const BackendRun& b, std::size_t primitives) {
  return json{{"backend", b.backend},
              {"build_seconds", measured(b.build_seconds)},
              {"memory_bytes", b.memory_bytes},
              {"bytes_per_primitive", primitives ? static_cast<double>(b.memory_bytes) / primitives : 0.0},
              {"camera_mrays_per_s", measured(b.camera)},
              {"shadow_mrays_per_s", measured(b.shadow)},
              {"diffuse_mrays_per_s", measured(b.diffuse)},
              {"hits", {{"camera", b.camera_hits}, {"shadow", b.shadow_hits}, {"diffuse", b.diffuse_hits}}}};
}

json tree_json(const bvh::TreeStats& t) {
  json histogram = json::object();
  for (std::size_t k = 1; k < t.leaf_sizes.size(); ++k) {
    if (t.leaf_sizes[k] > 0) histogram[std::to_string(k)] = t.leaf_sizes[k];
  }
  return json{{"nodes", t.nodes},
              {"leaves", t.leaves},
              {"primitives", t.prims},
              {"leaf_blocks", t.blocks},
              {"depth", t.depth},
              {"child_fill", t.nodes ? static_cast<double>(t.child_slots_used) / (8.0 * t.nodes) : 0.0},
              {"leaf_size_histogram", histogram},
              {"sah_cost", t.sah_cost},
              {"bytes", t.bytes}};
}

json counts_json(const CrossCheckCounts& c) {
  json causes = json::object();
  for (int k = 0; k < kCauses; ++k) causes[cause_name(static_cast<Cause>(k))] = c.cause[k];
  return json{{"rays", c.rays},
              {"agree", c.agree},
              {"tie", c.tie},
              {"hit_vs_miss", c.hit_miss},
              {"distance", c.distance},
              {"rate", c.rate()},
              {"causes", causes},
              {"agreeing_hits", {{"compared", c.hits_compared},
                                 {"t_not_bit_identical", c.t_differs},
                                 {"max_relative_t_difference", c.max_relative_t}}}};
}

double ratio(double a, double b) { return b > 0 ? a / b : 0.0; }

json ratios_json(const BackendRun& b, const BackendRun& e) {
  return json{{"camera", ratio(b.camera.median, e.camera.median)},
              {"shadow", ratio(b.shadow.median, e.shadow.median)},
              {"diffuse", ratio(b.diffuse.median, e.diffuse.median)},
              {"build_time", ratio(b.build_seconds.median, e.build_seconds.median)},
              {"memory", ratio(static_cast<double>(b.memory_bytes), static_cast<double>(e.memory_bytes))}};
}

std::string fmt(const char* format, double v) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, format, v);
  return buffer;
}

// "12.3 (±4%)": a median and the spread of its repetitions.
std::string with_spread(const Measured& m, const char* format, double scale = 1.0) {
  return fmt(format, m.median * scale) + " (±" + fmt("%.0f", 50.0 * m.spread()) + "%)";
}

std::string goal_cell(double r, double goal, bool higher_is_better) {
  const bool met = higher_is_better ? r >= goal : r <= goal;
  return fmt("%.2f", r) + (met ? " ✓" : " ✗");
}

}  // namespace

std::string to_json(const Report& report) {
  json scenes = json::array();
  for (const SceneResult& s : report.scenes) {
    json runs = json::array();
    for (const ThreadRun& r : s.runs) {
      runs.push_back(json{{"threads", r.threads},
                          {"embree_reference", backend_json(r.reference, s.primitives)},
                          {"embree_backend", backend_json(r.embree, s.primitives)},
                          {"bvh", backend_json(r.bvh, s.primitives)},
                          {"ratios_bvh_over_embree_reference", ratios_json(r.bvh, r.reference)},
                          {"ratios_embree_backend_over_embree_reference", ratios_json(r.embree, r.reference)},
                          {"ratios_bvh_over_embree_backend", ratios_json(r.bvh, r.embree)}});
    }
    scenes.push_back(json{{"name", s.name},
                          {"source", s.source},
                          {"triangles", s.triangles},
                          {"primitives", s.primitives},
                          {"camera", {{"width", s.width}, {"height", s.height}}},
                          {"rays", {{"camera", s.camera_rays}, {"shadow", s.shadow_rays}, {"diffuse", s.diffuse_rays}}},
                          {"runs", runs},
                          {"tree",
                           {{"bottom_levels", s.tree.bottom_levels},
                            {"bottom", tree_json(s.tree.bottom)},
                            {"top", tree_json(s.tree.top)},
                            {"kernel", s.tree.isa},
                            {"work_per_ray",
                             {{"camera", {{"nodes", s.bvh_camera_work.nodes}, {"prims", s.bvh_camera_work.prims}}},
                              {"diffuse", {{"nodes", s.bvh_diffuse_work.nodes}, {"prims", s.bvh_diffuse_work.prims}}}}}}},
                          {"cross_check",
                           {{"tolerance", s.check.tolerance},
                            {"camera", counts_json(s.check.camera)},
                            {"shadow", counts_json(s.check.shadow)},
                            {"diffuse", counts_json(s.check.diffuse)},
                            {"disagreements", s.check.disagreements()},
                            {"rate", s.check.rate()}}}});
  }
  const json out{{"command", report.command},
                 {"settings",
                  {{"width", report.settings.width},
                   {"height", report.settings.height},
                   {"builds", report.settings.builds},
                   {"repetitions", report.settings.repetitions},
                   {"sphere_triangles", report.settings.sphere_triangles},
                   {"clock", report.settings.clock}}},
                 {"scenes", scenes},
                 {"skipped", report.skipped},
                 {"note", report.note},
                 {"load_average", {{"before", report.load_before}, {"after", report.load_after}}},
                 {"machine_lscpu", report.machine}};
  return out.dump(2) + "\n";
}

std::string to_markdown(const Report& report) {
  std::ostringstream md;
  md << "# Acceleration structures: our BVH against Embree\n\n";
  md << "Produced by `" << report.command << "` (`tools/bench/accel`); every figure below comes from that one run "
        "on the machine described at the end.\n\n";
  if (!report.note.empty()) md << "**Note.** " << report.note << "\n\n";
  if (!report.scenes.empty() && !report.scenes[0].runs.empty()) {
    const ThreadRun& r = report.scenes[0].runs[0];
    md << "Three accelerators, same geometry, same rays:\n\n"
       << "- **bare Embree** (the yardstick of the goals): `" << r.reference.backend
       << "`: Embree called directly (`tools/bench/accel/embree_reference.h`): its own triangle geometry and "
          "intersector over the mesh buffers, scene flag `RTC_SCENE_FLAG_ROBUST`, build quality `HIGH` (spatial "
          "splits), analytic shapes as user geometry; a query copies the ray into an `RTCRayHit` and calls "
          "`rtcIntersect1`/`rtcOccluded1`, with no virtual call.\n"
       << "- **`--accel=embree`**: the renderer's Embree backend (`" << r.embree.backend
       << "`): the same Embree geometry and flags, plus what the renderer's contract needs: invalid rays answered "
          "before Embree, the open interval `(tmin, tmax)` narrowed to Embree's closed one, degenerate triangles "
          "left out of Embree's buffers, a virtual call per query (docs/geometry.md).\n"
       << "- **`--accel=bvh`**: ours, `" << r.bvh.backend << "` (docs/bvh.md).\n\n";
  }
  md << "Method:\n\n";
  md << "- Rays: one camera ray per pixel (" << report.settings.width << "x" << report.settings.height
     << " for bare meshes; a scene file's own aspect ratio otherwise); from each camera hit (found by the "
        "`--accel=embree` backend) one shadow ray to a light (`occluded()`) and one cosine-distributed diffuse "
        "bounce ray (`intersect()`). The same ray sets, generated once outside the timed region, go through every "
        "accelerator.\n";
  md << "- Timing: Mrays/s is the median of " << report.settings.repetitions
     << " passes over a whole ray set (the accelerators take turns pass by pass, in rotating order), after one "
        "warm-up pass each; build time is the median of "
     << report.settings.builds
     << " builds of each (the whole build call, in rotating order). Each figure gives the spread of its "
        "repetitions, ±(max − min) / (2 × median). Clock: "
     << (report.settings.clock == "cpu"
             ? "**CPU time of the process** (every thread; `--clock cpu`): the machine was shared with other "
               "jobs, and CPU time counts the time the benchmark ran, not the time it waited for a core, so "
               "Mrays/s are per CPU-second"
             : "wall-clock time")
     << ".\n";
  md << "- Ratios are against bare Embree (the yardstick): throughput ratios above 1 favour the accelerator; "
        "build-time and memory ratios below 1 favour it. Goals: the BVH's camera ≥ "
     << kCameraGoal << ", shadow ≥ " << kShadowGoal << ", diffuse ≥ " << kDiffuseGoal << " (issue 18), build time ≤ "
     << kBuildGoal << ", memory ≤ " << kMemoryGoal << " (issue 3); `--accel=embree`'s throughput ≥ " << kBackendGoal
     << " on every ray kind (issue 18).\n";
  md << "- Memory: Embree's is what its memory monitor counts after the build (its BVH, with the triangles' "
        "vertices in its leaves; mesh buffers are shared where the layout allows, else Embree holds a copy, which "
        "is counted); ours is the nodes and leaf blocks. Neither includes the scene's own vertex and index arrays.\n\n";

  md << "## Against the goals (ratios to bare Embree)\n\n";
  md << "| scene | threads | BVH camera | BVH shadow | BVH diffuse | BVH build time | BVH memory | `--accel=embree` "
        "camera | shadow | diffuse |\n|---|---|---|---|---|---|---|---|---|---|\n";
  for (const SceneResult& s : report.scenes) {
    for (const ThreadRun& r : s.runs) {
      const BackendRun& e = r.reference;
      md << "| " << s.name << " | " << r.threads << " | "
         << goal_cell(ratio(r.bvh.camera.median, e.camera.median), kCameraGoal, true) << " | "
         << goal_cell(ratio(r.bvh.shadow.median, e.shadow.median), kShadowGoal, true) << " | "
         << goal_cell(ratio(r.bvh.diffuse.median, e.diffuse.median), kDiffuseGoal, true) << " | "
         << goal_cell(ratio(r.bvh.build_seconds.median, e.build_seconds.median), kBuildGoal, false) << " | "
         << goal_cell(ratio(static_cast<double>(r.bvh.memory_bytes), static_cast<double>(e.memory_bytes)),
                      kMemoryGoal, false)
         << " | " << goal_cell(ratio(r.embree.camera.median, e.camera.median), kBackendGoal, true) << " | "
         << goal_cell(ratio(r.embree.shadow.median, e.shadow.median), kBackendGoal, true) << " | "
         << goal_cell(ratio(r.embree.diffuse.median, e.diffuse.median), kBackendGoal, true) << " |\n";
    }
  }
  if (!report.skipped.empty()) {
    md << "\nSkipped: ";
    for (std::size_t i = 0; i < report.skipped.size(); ++i) md << (i ? "; " : "") << report.skipped[i];
    md << ".\n";
  }

  for (const SceneResult& s : report.scenes) {
    md << "\n## " << s.name << "\n\n";
    md << thousands(s.triangles) << " triangles, " << thousands(s.primitives) << " primitives (" << s.source
       << "). Camera " << s.width << "x" << s.height << ": " << thousands(s.camera_rays) << " camera, "
       << thousands(s.shadow_rays) << " shadow, " << thousands(s.diffuse_rays) << " diffuse rays.\n\n";
    md << "| threads | | bare Embree | `--accel=embree` | `--accel=bvh` | `--accel=embree` / bare | BVH / bare "
          "|\n|---|---|---|---|---|---|---|\n";
    for (const ThreadRun& r : s.runs) {
      auto row = [&](const char* label, auto get, const char* format, double scale) {
        const Measured& e = get(r.reference);
        md << "| " << r.threads << " | " << label << " | " << with_spread(e, format, scale) << " | "
           << with_spread(get(r.embree), format, scale) << " | " << with_spread(get(r.bvh), format, scale) << " | "
           << fmt("%.2f", ratio(get(r.embree).median, e.median)) << " | "
           << fmt("%.2f", ratio(get(r.bvh).median, e.median)) << " |\n";
      };
      row("build (ms)", [](const BackendRun& b) -> const Measured& { return b.build_seconds; }, "%.1f", 1e3);
      const double p = static_cast<double>(s.primitives);
      md << "| " << r.threads << " | memory (bytes/primitive) | " << fmt("%.1f", r.reference.memory_bytes / p)
         << " | " << fmt("%.1f", r.embree.memory_bytes / p) << " | " << fmt("%.1f", r.bvh.memory_bytes / p) << " | "
         << fmt("%.2f", ratio(static_cast<double>(r.embree.memory_bytes), static_cast<double>(r.reference.memory_bytes)))
         << " | "
         << fmt("%.2f", ratio(static_cast<double>(r.bvh.memory_bytes), static_cast<double>(r.reference.memory_bytes)))
         << " |\n";
      row("camera (Mrays/s)", [](const BackendRun& b) -> const Measured& { return b.camera; }, "%.2f", 1.0);
      row("shadow (Mrays/s)", [](const BackendRun& b) -> const Measured& { return b.shadow; }, "%.2f", 1.0);
      row("diffuse (Mrays/s)", [](const BackendRun& b) -> const Measured& { return b.diffuse; }, "%.2f", 1.0);
    }

    const bvh::TreeStats& t = s.tree.bottom;
    md << "\nTree (kernel " << s.tree.isa << "): " << s.tree.bottom_levels << " bottom-level BVH"
       << (s.tree.bottom_levels == 1 ? "" : "s") << ", " << thousands(t.nodes) << " nodes ("
       << fmt("%.2f", t.nodes ? static_cast<double>(t.child_slots_used) / static_cast<double>(t.nodes) : 0.0)
       << " children per node on average), " << thousands(t.leaves) << " leaves in " << thousands(t.blocks)
       << " blocks ("
       << fmt("%.2f", t.blocks ? static_cast<double>(t.prims) / static_cast<double>(t.blocks) : 0.0)
       << " primitives per block: 4 fills a triangle block), depth " << t.depth << ", SAH cost " << fmt("%.1f", t.sah_cost)
       << " (node tests + leaf-block tests expected per ray through the root box)";
    if (s.tree.top.nodes > 0) md << "; top level: " << s.tree.top.nodes << " nodes, depth " << s.tree.top.depth;
    md << ". Work per ray (`intersect_counted`): camera " << fmt("%.1f", s.bvh_camera_work.nodes) << " nodes and "
       << fmt("%.1f", s.bvh_camera_work.prims) << " triangles tested, diffuse " << fmt("%.1f", s.bvh_diffuse_work.nodes)
       << " nodes and " << fmt("%.1f", s.bvh_diffuse_work.prims) << " triangles";
    md << ". Leaf sizes (primitives: leaves):";
    for (std::size_t k = 1; k < t.leaf_sizes.size(); ++k) {
      if (t.leaf_sizes[k] > 0) md << " " << k << ": " << thousands(t.leaf_sizes[k]) << ";";
    }
    md << "\n\n";
    const CrossCheck& c = s.check;
    const std::size_t compared = c.camera.hits_compared + c.diffuse.hits_compared;
    const std::size_t differ = c.camera.t_differs + c.diffuse.t_differs;
    md << "Cross-check, `--accel=embree` against `--accel=bvh` on the same rays (distance tolerance " << c.tolerance
       << " relative; `accel_crosscheck`, causes as in `tools/bench/accel/cross_check.h`): disagreements "
       << describe_rate(c) << "; camera " << c.camera.hit_miss << " hit/miss and " << c.camera.distance
       << " distance, shadow " << c.shadow.hit_miss << ", diffuse " << c.diffuse.hit_miss << " hit/miss and "
       << c.diffuse.distance << " distance; " << thousands(c.camera.tie + c.diffuse.tie)
       << " ties. Of " << thousands(compared) << " hits on the same primitive, " << thousands(differ)
       << " distances are not bit-identical; the largest relative difference is "
       << fmt("%.2g", std::max(c.camera.max_relative_t, c.diffuse.max_relative_t)) << ".\n";
  }

  md << "\n## Machine\n\nLoad average (1, 5, 15 minutes; `/proc/loadavg`) at the start of the run: " << report.load_before
     << "; at the end: " << report.load_after << ". Figures from a machine whose load exceeds its idle level "
        "are not comparable with those of a quiet run.\n\n```\n"
     << report.machine << "```\n";
  return md.str();
}

}  // namespace pt::bench
