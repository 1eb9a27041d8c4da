// accel_crosscheck: traces the same camera, shadow and diffuse rays of a scene
// through the Embree backend and our BVH and reports where they disagree (hit
// versus miss, or a distance beyond the tolerance) as a rate, with the cause
// of each disagreement (cross_check.h: vertex, edge, grazing, ray end, same
// triangle, other), how many agreeing distances differ in their last bits,
// and an image marking the pixels (red: hit versus miss, yellow: distance,
// blue: a tie, i.e. different primitives at the same distance).
//
//   accel_crosscheck SCENE [--width 640 --height 480] [--tolerance 1e-4] [--max-rate 1e-4]
//                    [--max-other 0] [-o marks.png]
//
// SCENE is a scene file (native, Path of Light, CGR), an OBJ or PLY mesh, or one
// of the benchmark's scenes: bunny, sponza, sphere, path-of-light.
// The backends' triangle tests differ (Embree's Plücker test, our watertight
// one; docs/geometry.md), so a few disagreements at triangle boundaries are
// expected. Exit status: 0 when the rate of disagreements is at most
// --max-rate and at most --max-other of them have no geometric cause ("other"),
// 1 otherwise, 2 for bad input, 77 when a built-in scene's shared asset is
// absent (ctest counts that as skipped).
#include <iostream>
#include <string>

#include <CLI/CLI.hpp>

#include "accel/accelerator.h"
#include "bench_scene.h"
#include "core/parallel.h"
#include "cross_check.h"
#include "io/image_io.h"
#include "ray_sets.h"

namespace {

void print(const char* kind, const pt::bench::CrossCheckCounts& c) {
  using pt::bench::thousands;
  std::cout << "  " << kind << ": " << thousands(c.rays) << " rays, " << thousands(c.agree) << " agree, "
            << thousands(c.tie) << " ties, " << c.hit_miss << " hit/miss, " << c.distance << " distance";
  for (int k = 0; k < pt::bench::kCauses; ++k) {
    if (c.cause[k] > 0) std::cout << "; " << c.cause[k] << " " << pt::bench::cause_name(static_cast<pt::bench::Cause>(k));
  }
  if (c.hits_compared > 0) {
    std::cout << "; agreeing hits: " << thousands(c.t_differs) << " of " << thousands(c.hits_compared)
              << " distances not bit-identical, largest relative difference " << c.max_relative_t;
  }
  std::cout << "\n";
}

}  // namespace

int main(int argc, char** argv) {
  using namespace pt;
  CLI::App app{"accel_crosscheck: the same rays through Embree and our BVH; the rate of disagreements and their causes"};
  bench::SceneRequest request;
  float tolerance = 1e-4f;
  double max_rate = 1e-4;
  std::size_t max_other = 0;
  std::string image_path;
  int threads = 0;
  app.add_option("scene", request.what, "Scene file, mesh file, or bunny|sponza|sphere|path-of-light")->required();
  app.add_option("--width", request.width, "Image width")->check(CLI::Range(1, 16384));
  app.add_option("--height", request.height, "Image height (bare meshes)")->check(CLI::Range(1, 16384));
  app.add_option("--sphere-triangles", request.sphere_triangles, "Triangles of the procedural sphere");
  app.add_option("--tolerance", tolerance, "Relative distance tolerance")->check(CLI::Range(0.0f, 1.0f));
  app.add_option("--max-rate", max_rate, "Largest rate of disagreements (of all rays) that passes")
      ->check(CLI::Range(0.0, 1.0));
  app.add_option("--max-other", max_other, "Largest number of disagreements without a geometric cause that passes");
  app.add_option("-o,--output", image_path, "Image marking the pixels where the backends differ")
      ->check([](const std::string& p) { return is_supported_image_path(p) ? "" : "unsupported image extension"; });
  app.add_option("--threads", threads, "Threads (default: all)");
  CLI11_PARSE(app, argc, argv);

  bench::BenchScene scene;
  bool missing = false;
  std::string error;
  if (!bench::load_bench_scene(request, scene, missing, error)) {
    std::cerr << (missing ? "skipped: " : "error: ") << error << "\n";
    return missing ? 77 : 2;
  }
  WorkerPool pool(threads);
  Diagnostics diag;
  const auto embree = build_accelerator(AccelKind::Embree, scene.geometry, pool, diag);
  const auto bvh = build_accelerator(AccelKind::Bvh, scene.geometry, pool, diag);
  if (!embree || !bvh) {
    std::cerr << diag.format();
    return 2;
  }
  const bench::RaySets rays = bench::make_ray_sets(scene, *embree, pool);
  const bench::CrossCheck check = bench::cross_check(*embree, *bvh, scene.geometry, rays, pool, tolerance);
  std::cout << scene.name << " (" << scene.primitives << " primitives), " << embree->stats().backend << " vs "
            << bvh->stats().backend << ", tolerance " << tolerance << ":\n";
  print("camera", check.camera);
  print("shadow", check.shadow);
  print("diffuse", check.diffuse);
  std::cout << "disagreements: " << bench::describe_rate(check) << "\n";
  if (!image_path.empty()) {
    if (!write_image(image_path, bench::disagreement_image(check, rays, scene.geometry, *embree, pool), DisplaySettings{}, error)) {
      std::cerr << "error: " << error << "\n";
      return 2;
    }
    std::cout << "wrote " << image_path << "\n";
  }
  const bool pass = check.rate() <= max_rate && check.cause(bench::Cause::Other) <= max_other;
  std::cout << (pass ? "within" : "beyond") << " the limits (rate " << max_rate << ", " << max_other
            << " without a cause)\n";
  return pass ? 0 : 1;
}
