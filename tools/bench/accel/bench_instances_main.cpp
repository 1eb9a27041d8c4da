// bench_instances: memory per placement of an instanced object. Places the
// Stanford bunny (../shared/assets/meshes/stanford-bunny.obj) N times, each
// with its own rotation, scale and position on a grid, builds each backend
// over it, and reports the acceleration structure's memory and the process's
// resident memory growth for 1 placement and for N, so the cost of one extra
// placement is (mem(N) - mem(1)) / (N - 1). It then traces a grid of rays
// from above through the N placements to show that they are all there.
//
//   bench_instances [--placements 10000] [--backends bvh,embree] [--mesh PATH]
//   bench_instances --placements 10000 --write-scene FILE   (the same placements
//       as a native scene of `instance` entries, one in seven with a material
//       of its own, for rendering with pathtracer; docs/bench/instancing.md)
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "accel/accelerator.h"
#include "core/parallel.h"
#include "scene/mesh_obj.h"

namespace {

using namespace pt;

// Resident set size of this process, bytes (/proc/self/statm).
std::size_t resident_bytes() {
  std::ifstream f("/proc/self/statm");
  std::size_t pages = 0, resident = 0;
  f >> pages >> resident;
  return resident * 4096;
}

// Placement i of n: uniform scale s, then a turn about +y, then a position on the grid.
struct Placement {
  double scale, degrees, x, z;
};

Placement placement(int i, int n) {
  const int side = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n))));
  return {0.8 + 0.4 * ((i * 37) % 100) / 100.0, static_cast<double>((i * 73) % 360), (i % side) * 0.25,
          (i / side) * 0.25};
}

SceneGeometry placements(const TriangleMesh& mesh, int n) {
  SceneGeometry g;
  g.shapes.push_back(mesh);
  g.prototypes.push_back({0});
  for (int i = 0; i < n; ++i) {
    const Placement p = placement(i, n);
    g.instances.push_back(Instance{0, Transform(Affine::translate(p.x, 0, p.z) * Affine::rotate(0, 1, 0, p.degrees) *
                                                Affine::scale(p.scale, p.scale, p.scale))});
  }
  return g;
}

// The same placements as a native scene: the mesh defined once as an object,
// n instances (one in seven red), seen from above and lit by the sun and the sky.
bool write_scene(const std::string& path, const std::string& mesh_path, int n) {
  std::ofstream f(path);
  const double side = std::ceil(std::sqrt(static_cast<double>(n))) * 0.25;  // the grid's width (x)
  const double extent = placement(n - 1, n).z + 0.25;                         // and depth (z)
  f << "{\n  \"format\": \"pathtracer-scene\", \"version\": 1,\n"
    << "  \"camera\": { \"position\": [" << side / 2 << ", " << side * 0.6 << ", " << extent + side * 0.5
    << "], \"look_at\": [" << side / 2 << ", 0, " << extent / 2 << "], \"fov\": 45 },\n"
    << "  \"film\": { \"width\": 320, \"height\": 240 },\n"
    << "  \"render\": { \"integrator\": \"path\", \"max_depth\": 3, \"spp\": 4, \"background\": [0.3, 0.35, 0.4] },\n"
    << "  \"materials\": { \"white\": { \"type\": \"lambert\", \"diffuse\": [0.75, 0.75, 0.75] },\n"
    << "                 \"red\": { \"type\": \"lambert\", \"diffuse\": [0.7, 0.15, 0.1] } },\n"
    << "  \"lights\": [ { \"type\": \"directional\", \"direction\": [-0.3, -1, -0.4], \"irradiance\": [2, 2, 2] } ],\n"
    << "  \"objects\": [ { \"name\": \"bunny\", \"shapes\": [ { \"type\": \"mesh\", \"file\": \"" << mesh_path
    << "\", \"material\": \"white\" } ] } ],\n  \"shapes\": [\n";
  for (int i = 0; i < n; ++i) {
    const Placement p = placement(i, n);
    f << "    { \"type\": \"instance\", \"object\": \"bunny\", " << (i % 7 == 0 ? "\"material\": \"red\", " : "")
      << "\"transform\": [ { \"scale\": " << p.scale << " }, { \"rotate\": { \"axis\": [0, 1, 0], \"angle\": "
      << p.degrees << " } }, { \"translate\": [" << p.x << ", 0, " << p.z << "] } ] }" << (i + 1 < n ? ",\n" : "\n");
  }
  f << "  ]\n}\n";
  return static_cast<bool>(f);
}

struct Measure {
  std::size_t accel_bytes = 0, rss_growth = 0;
  double build_seconds = 0;
  long hits = 0, instances_hit = 0;
};

Measure measure(AccelKind kind, const SceneGeometry& g, WorkerPool& pool, bool trace) {
  Measure m;
  Diagnostics diag;
  const std::size_t before = resident_bytes();
  auto accel = build_accelerator(kind, g, pool, diag);
  if (!accel) {
    std::cerr << diag.format();
    return m;
  }
  m.rss_growth = resident_bytes() - before;
  m.accel_bytes = accel->stats().memory_bytes;
  m.build_seconds = accel->stats().build_seconds;
  if (trace) {
    const Bounds3f b = accel->bounds();
    std::vector<char> seen(g.instances.size(), 0);
    for (int i = 0; i < 1000; ++i) {
      for (int j = 0; j < 1000; ++j) {
        const Vec3f o(b.lo.x + (b.hi.x - b.lo.x) * (i + 0.5f) / 1000, b.hi.y + 1, b.lo.z + (b.hi.z - b.lo.z) * (j + 0.5f) / 1000);
        Hit h;
        if (accel->intersect(Ray{o, {0, -1, 0}}, h)) {
          ++m.hits;
          if (h.instance < seen.size() && !seen[h.instance]) {
            seen[h.instance] = 1;
            ++m.instances_hit;
          }
        }
      }
    }
  }
  return m;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"bench_instances: memory per placement of an instanced mesh"};
  int n = 10000;
  std::vector<std::string> backends = {"bvh", "embree"};
  std::string mesh_path = std::string(PT_SHARED_DIR) + "/assets/meshes/stanford-bunny.obj";
  app.add_option("--placements", n, "Placements of the mesh")->check(CLI::Range(2, 10000000));
  app.add_option("--backends", backends, "Backends")->delimiter(',');
  app.add_option("--mesh", mesh_path, "The mesh (OBJ)");
  std::string scene_path;
  app.add_option("--write-scene", scene_path, "Write the placements as a native scene file instead of measuring");
  CLI11_PARSE(app, argc, argv);
  if (!scene_path.empty()) {
    if (write_scene(scene_path, mesh_path, n)) return 0;
    std::cerr << "cannot write " << scene_path << "\n";
    return 1;
  }

  TriangleMesh mesh;
  std::string error;
  if (!load_obj(mesh_path, mesh, error)) {
    std::cerr << "cannot read " << mesh_path << ": " << error << "\n";
    return 1;
  }
  WorkerPool pool(0);
  std::printf("mesh %s: %zu triangles; %d placements = %.0f M triangles placed\n", mesh_path.c_str(),
              mesh.triangle_count(), n, static_cast<double>(mesh.triangle_count()) * n / 1e6);
  for (const std::string& name : backends) {
    AccelKind kind{};
    if (!parse_accel_kind(name, kind)) {
      std::cerr << "unknown backend " << name << "\n";
      return 1;
    }
    // N first: memory freed after it is reused by the single placement's build,
    // whose RSS growth then reads low (the per-placement figure errs high by at most mem(1) / N).
    const SceneGeometry g = placements(mesh, n);
    const Measure many = measure(kind, g, pool, true);
    const Measure one = measure(kind, placements(mesh, 1), pool, false);
    const double per_accel = (static_cast<double>(many.accel_bytes) - one.accel_bytes) / (n - 1);
    const double per_rss = (static_cast<double>(many.rss_growth) - one.rss_growth) / (n - 1);
    std::printf(
        "%-7s 1 placement: accel %.1f MB, RSS +%.1f MB | %d placements: accel %.1f MB, RSS +%.1f MB, build %.2f s | "
        "per extra placement: accel %.0f B, RSS %.0f B | rays from above: %ld hits, %ld placements hit\n",
        name.c_str(), one.accel_bytes / 1e6, one.rss_growth / 1e6, n, many.accel_bytes / 1e6, many.rss_growth / 1e6,
        many.build_seconds, per_accel, per_rss, many.hits, many.instances_hit);
  }
  return 0;
}
