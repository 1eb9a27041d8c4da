#include <cmath>
#include <string>
#include <variant>

#include "fuzz_check.h"
#include "fuzz_targets.h"
#include "scene/loader.h"

namespace pt::fuzz {
namespace {

const std::string kScenePath = std::string(PT_FUZZ_FIXTURES_DIR) + "/fuzz-input.json";

bool finite_rgb(const RGB& c) { return std::isfinite(c.r) && std::isfinite(c.g) && std::isfinite(c.b); }

// Every diagnostic with a location points into the text it quotes.
void check_diagnostics(const Diagnostics& diag, std::size_t text_size) {
  for (const Diagnostic& d : diag.all()) {
    require(!d.message.empty(), "every diagnostic says something");
    if (!d.where.valid()) continue;
    require(d.where.col >= 1, "columns are 1-based");
    require(static_cast<std::size_t>(d.where.line) <= text_size + 1, "a diagnostic's line exists");
  }
  require(!diag.format().empty() || diag.all().empty(), "diagnostics format");
}

// What the render-scene builder relies on in a loaded description.
void check_description(const SceneDescription& s) {
  require(s.film.width >= 1 && s.film.height >= 1, "the film has pixels");
  require(s.film.width <= 32768 && s.film.height <= 32768, "the film is within the resolution limit");
  require(s.render.spp >= 1 && s.render.max_depth >= 0, "render settings are in range");
  require(is_finite(s.camera.position) && is_finite(s.camera.look_at) && is_finite(s.camera.up),
          "the camera is finite");
  require(std::isfinite(s.camera.fov_y_deg) && s.camera.fov_y_deg > 0 && s.camera.fov_y_deg < 180,
          "the field of view is in (0, 180)");
  require(finite_rgb(s.render.background), "the background is finite");
  for (const MaterialDesc& m : s.materials) {
    require(finite_rgb(m.diffuse) && finite_rgb(m.specular) && finite_rgb(m.emission), "material colours are finite");
    require(std::isfinite(m.kd) && std::isfinite(m.ks) && std::isfinite(m.exponent) && std::isfinite(m.ior),
            "material numbers are finite");
    require(!m.texture || (*m.texture >= 0 && static_cast<std::size_t>(*m.texture) < s.textures.size()),
            "texture indices are in range");
  }
  for (const TextureDesc& t : s.textures) require(!t.resolved.empty(), "every texture was found");
  for (const LightDesc& l : s.lights) {
    if (const auto* p = std::get_if<PointLightDesc>(&l)) {
      require(is_finite(p->position) && finite_rgb(p->intensity) && finite_rgb(p->specular_intensity),
              "point lights are finite");
    }
  }
  for (const ShapeDesc& shape : s.shapes) {
    require(shape.material >= 0 && static_cast<std::size_t>(shape.material) < s.materials.size(),
            "every shape has a material");
    if (const auto* sp = std::get_if<Sphere>(&shape.geometry)) {
      require(is_finite(sp->center) && std::isfinite(sp->radius) && sp->radius > 0, "spheres are valid");
    } else if (const auto* q = std::get_if<Quad>(&shape.geometry)) {
      for (const auto& v : q->v) require(is_finite(v), "quad corners are finite");
    } else if (const auto* c = std::get_if<Cylinder>(&shape.geometry)) {
      require(is_finite(c->p0) && is_finite(c->p1) && std::isfinite(c->radius) && c->radius > 0,
              "cylinders are valid");
    } else if (const auto* m = std::get_if<TriangleMesh>(&shape.geometry)) {
      require(m->indices.size() % 3 == 0, "mesh indices come in triangles");
      for (uint32_t i : m->indices) require(i < m->positions.size(), "mesh indices are in range");
      for (const Vec3f& p : m->positions) require(is_finite(p), "mesh positions are finite");
      require(m->normals.empty() || m->normals.size() == m->positions.size(), "one normal per vertex, or none");
      require(m->uvs.empty() || m->uvs.size() == m->positions.size(), "one uv per vertex, or none");
    }
  }
}

}  // namespace

int scene_one_input(const uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);

  Diagnostics diag;
  const auto scene = load_scene_from_string(kScenePath, text, LoadOptions{}, diag);
  check_diagnostics(diag, size);
  require(scene.has_value() == !diag.has_errors(), "a scene loads exactly when no error is reported");
  if (scene) check_description(*scene);

  // Strict mode (warnings are errors, as --strict does): loads exactly when the
  // ordinary load reported nothing at all.
  Diagnostics strict_diag;
  strict_diag.set_warnings_as_errors(true);
  LoadOptions strict;
  strict.strict = true;
  const auto strict_scene = load_scene_from_string(kScenePath, text, strict, strict_diag);
  check_diagnostics(strict_diag, size);
  require(strict_scene.has_value() == !strict_diag.has_errors(), "strict: loads exactly when no error is reported");
  require(strict_scene.has_value() == (scene.has_value() && diag.warning_count() == 0),
          "strict mode fails exactly when the ordinary load warned or failed");
  return 0;
}

}  // namespace pt::fuzz
