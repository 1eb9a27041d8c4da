#include "bench_scene.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <type_traits>
#include <variant>

#include "core/parallel.h"
#include "render/render_scene.h"
#include "scene/loader.h"
#include "scene/mesh_obj.h"
#include "scene/ply.h"

namespace pt::bench {

namespace fs = std::filesystem;

namespace {

std::string shared_path(const std::string& relative) { return (fs::path(PT_SHARED_DIR) / relative).string(); }

std::string lower_extension(const std::string& path) {
  std::string e = fs::path(path).extension().string();
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return e;
}

Bounds3f scene_bounds(const SceneGeometry& g) {
  Bounds3f b;
  for (const Shape& s : g.shapes) b.extend(bounds(s));
  return b;
}

Camera make_camera(Vec3f position, Vec3f look_at, float fov_deg, int width, int height) {
  CameraDesc d;
  d.position = position;
  d.look_at = look_at;
  d.up = Vec3f(0, 1, 0);
  d.fov_y_deg = fov_deg;
  return Camera(d, width, height);
}

// A camera looking at the bounds' centre from `view` (a direction, +y up),
// far enough that the box's larger side across the view fills about 90% of
// the vertical field of view.
Camera framing_camera(const Bounds3f& b, Vec3f view, int width, int height) {
  const float fov = 40.0f;
  const Vec3f e = b.extent();
  const float half = 0.5f * std::max(e.y, std::max(e.x, e.z)) / 0.9f;
  const float distance = half / std::tan(0.5f * fov * kPi / 180.0f) + 0.5f * std::max(e.x, e.z);
  return make_camera(b.centre() + normalize(view) * distance, b.centre(), fov, width, height);
}

// The light used for shadow rays of bare meshes: high above the middle (+y up).
Vec3f light_above(const Bounds3f& b) { return b.centre() + Vec3f(0.25f, 0.45f, 0.3f) * b.extent(); }

void count(BenchScene& s) {
  s.triangles = 0;
  s.primitives = 0;
  for (const Shape& shape : s.geometry.shapes) {
    if (const auto* m = std::get_if<TriangleMesh>(&shape)) {
      s.triangles += m->triangle_count();
      s.primitives += m->triangle_count();
    } else {
      s.primitives += 1;
    }
  }
}

bool load_mesh_file(const std::string& path, TriangleMesh& mesh, std::string& error) {
  if (lower_extension(path) == ".obj") {
    if (!load_obj(path, mesh, error)) {
      error = "cannot read '" + path + "': " + error;
      return false;
    }
  } else if (PlyError e; !load_ply(path, mesh, e)) {
    error = "cannot read '" + path + "': " + e.message;
    return false;
  }
  mesh.positions.reserve(mesh.positions.size() + 1);  // lets Embree share the buffer (no copy counted)
  return true;
}

// A UV sphere of radius 1 with about `target` triangles (2 s (r - 1) for r
// rings of s = 2 r segments).
TriangleMesh tessellated_sphere(std::size_t target) {
  const int rings = std::max(3, static_cast<int>(std::lround(std::sqrt(static_cast<double>(target) / 4.0))));
  const int segments = 2 * rings;
  TriangleMesh m;
  m.positions.reserve(static_cast<std::size_t>(rings - 1) * segments + 3);
  m.positions.push_back({0, 1, 0});
  for (int i = 1; i < rings; ++i) {
    const double theta = std::numbers::pi * i / rings;
    for (int j = 0; j < segments; ++j) {
      const double phi = 2.0 * std::numbers::pi * j / segments;
      m.positions.push_back({static_cast<float>(std::sin(theta) * std::cos(phi)), static_cast<float>(std::cos(theta)),
                             static_cast<float>(std::sin(theta) * std::sin(phi))});
    }
  }
  const auto south = static_cast<uint32_t>(m.positions.size());
  m.positions.push_back({0, -1, 0});
  auto ring = [&](int r, int s) { return static_cast<uint32_t>(1 + (r - 1) * segments + (s % segments)); };
  auto tri = [&](uint32_t a, uint32_t b, uint32_t c) { m.indices.insert(m.indices.end(), {a, b, c}); };
  for (int j = 0; j < segments; ++j) tri(0, ring(1, j + 1), ring(1, j));
  for (int i = 1; i < rings - 1; ++i) {
    for (int j = 0; j < segments; ++j) {
      tri(ring(i, j), ring(i, j + 1), ring(i + 1, j + 1));
      tri(ring(i, j), ring(i + 1, j + 1), ring(i + 1, j));
    }
  }
  for (int j = 0; j < segments; ++j) tri(south, ring(rings - 1, j), ring(rings - 1, j + 1));
  return m;
}

bool load_mesh_scene(const std::string& name, const std::string& path, const SceneRequest& r, BenchScene& s,
                     std::string& error) {
  TriangleMesh mesh;
  if (!load_mesh_file(path, mesh, error)) return false;
  s.name = name;
  if (s.source.empty()) s.source = path;
  s.geometry.shapes.push_back(std::move(mesh));
  const Bounds3f b = scene_bounds(s.geometry);
  s.width = r.width;
  s.height = r.height;
  if (name == "sponza") {
    // Inside the atrium, looking down its long (x) axis.
    const Vec3f lo = b.lo, e = b.extent();
    s.camera = make_camera({lo.x + 0.84f * e.x, lo.y + 0.21f * e.y, b.centre().z},
                           {lo.x + 0.11f * e.x, lo.y + 0.34f * e.y, b.centre().z}, 60.0f, r.width, r.height);
  } else {
    s.camera = framing_camera(b, Vec3f(0.35f, 0.3f, 1.0f), r.width, r.height);
  }
  s.lights = {light_above(b)};
  return true;
}

bool load_scene_file(const std::string& name, const std::string& path, const SceneRequest& r, BenchScene& s,
                     std::string& error) {
  Diagnostics diag;
  const std::optional<SceneDescription> desc = load_scene(path, LoadOptions{}, diag);
  if (!desc || diag.has_errors()) {
    error = diag.format();
    return false;
  }
  WorkerPool pool;
  BuildOptions options;
  options.width_override = r.width;
  std::unique_ptr<RenderScene> scene = build_render_scene(*desc, options, pool, diag);
  if (!scene) {
    error = diag.format();
    return false;
  }
  s.name = name;
  if (s.source.empty()) s.source = path;
  s.camera = scene->camera;
  s.width = scene->width;
  s.height = scene->height;
  s.geometry = std::move(scene->geometry);
  for (Shape& shape : s.geometry.shapes) {
    if (auto* m = std::get_if<TriangleMesh>(&shape)) m->positions.reserve(m->positions.size() + 1);
  }
  for (const LightDesc& light : desc->lights) {
    if (const auto* p = std::get_if<PointLightDesc>(&light)) s.lights.push_back(p->position.value);
  }
  if (s.lights.empty()) s.lights = {light_above(scene_bounds(s.geometry))};
  return true;
}

}  // namespace

std::vector<std::string> builtin_scene_names() { return {"bunny", "sponza", "sphere", "path-of-light"}; }

bool load_bench_scene(const SceneRequest& r, BenchScene& out, bool& missing, std::string& error) {
  out = BenchScene{};
  missing = false;
  bool ok = false;
  auto shared_file = [&](const std::string& relative, std::string& path) {
    path = shared_path(relative);
    if (fs::exists(path)) {
      out.source = "../shared/" + relative;  // as the repository's docs name it
      return true;
    }
    missing = true;
    error = "'" + path + "' is not available";
    return false;
  };
  std::string path;
  if (r.what == "bunny") {
    ok = shared_file("assets/meshes/stanford-bunny.obj", path) && load_mesh_scene("bunny", path, r, out, error);
  } else if (r.what == "sponza") {
    ok = shared_file("assets/sponza/sponza.obj", path) && load_mesh_scene("sponza", path, r, out, error);
  } else if (r.what == "path-of-light") {
    ok = shared_file("seed-scenes/path-of-light/examples/example.json", path) &&
         load_scene_file("path-of-light", path, r, out, error);
  } else if (r.what == "sphere") {
    out.name = "sphere";
    out.geometry.shapes.push_back(tessellated_sphere(r.sphere_triangles));
    out.source = "procedural UV sphere, radius 1";
    const Bounds3f b = scene_bounds(out.geometry);
    out.width = r.width;
    out.height = r.height;
    out.camera = framing_camera(b, Vec3f(0.35f, 0.3f, 1.0f), r.width, r.height);
    out.lights = {light_above(b)};
    ok = true;
  } else if (!fs::exists(r.what)) {
    error = "'" + r.what + "' is neither a file nor a built-in scene (bunny, sponza, sphere, path-of-light)";
  } else {
    const std::string e = lower_extension(r.what);
    const std::string name = fs::path(r.what).filename().string();
    ok = (e == ".obj" || e == ".ply") ? load_mesh_scene(name, r.what, r, out, error)
                                       : load_scene_file(name, r.what, r, out, error);
  }
  if (ok) count(out);
  return ok;
}

}  // namespace pt::bench
