#include "scene/validate.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "geometry/shapes.h"
#include "scene/json_reader.h"
#include "scene/material_kinds.h"

namespace pt {
namespace {

std::string str(double d) { return format_number(d); }
std::string str(RGB c) { return std::string(1, '[') + str(c.r) + ", " + str(c.g) + ", " + str(c.b) + "]"; }

// The largest radiometric value (emission, a light's intensity or irradiance,
// background, ambient) and the largest product of one with a reflectance
// (kd * diffuse, ks * specular) a scene may hold. A path's radiance is a float
// (largest 3.4e38): the bound leaves 8 orders of magnitude for the geometric
// factors (1/r^2 down to r = 1e-4, cosine over pdf) and a few bounces. Above
// it a light or a surface would overflow to infinity, which the film counts as
// non-finite and adds as black: the light would silently add nothing
// (docs/scene-format.md, "Value limits").
constexpr float kMaxRadiometric = 1e30f;

// What the shape's own rule (geometry/shapes/*.h) finds wrong with it.
std::vector<ShapeProblem> shape_problems(const ShapeDesc& s) {
  ShapeChecker checker(s.type, s.file);
  check(s.geometry, checker);
  return checker.problems();
}

class Validator {
 public:
  Validator(const LoadOptions& options, Diagnostics& diag) : options_(options), diag_(diag) {}

  void camera(const CameraDesc& cam) {
    const Vec3f forward = cam.look_at.value - cam.position.value;
    const Vec3f up = cam.up.value;
    if (length(forward) == 0.0f)
      diag_.error(cam.look_at.where, "the camera's view direction has zero length (it looks at its own position)");
    if (length(up) == 0.0f) diag_.error(cam.up.where, "the camera's up vector has zero length");
    if (length(forward) > 0.0f && length(up) > 0.0f &&
        length(cross(normalize(forward), normalize(up))) < 1e-6f)
      diag_.error(cam.up.where, "the camera's up vector is parallel to its view direction");
    if (!(cam.fov_y_deg.value > 0.0f && cam.fov_y_deg.value < 180.0f))
      diag_.error(cam.fov_y_deg.where, "fov must be between 0 and 180 degrees, got " + str(cam.fov_y_deg.value));
    if (cam.type == CameraType::ThinLens) {
      if (cam.lens_radius.value < 0.0f)
        diag_.error(cam.lens_radius.where, "lens radius must be >= 0, got " + str(cam.lens_radius.value));
      if (cam.focus_distance.value <= 0.0f)
        diag_.error(cam.focus_distance.where, "focus distance must be > 0, got " + str(cam.focus_distance.value));
    }
    if (cam.type == CameraType::Orthographic) {
      if (!(cam.view_height.value > 0.0f && std::isfinite(cam.view_height.value)))
        diag_.error(cam.view_height.where, "view_height must be > 0, got " + str(cam.view_height.value));
      if (cam.view_width.where.valid() && !(cam.view_width.value > 0.0f && std::isfinite(cam.view_width.value)))
        diag_.error(cam.view_width.where, "view_width must be > 0, got " + str(cam.view_width.value));
    }
  }

  void film(const FilmDesc& film) {
    resolution(film.width, "width");
    resolution(film.height, "height");
    const long long pixels = static_cast<long long>(film.width.value) * film.height.value;
    if (film.width.value >= 1 && film.height.value >= 1 && pixels > options_.limits.max_pixels) {
      diag_.error(film.width.where.valid() ? film.width.where : film.height.where,
                  "the film has " + std::to_string(film.width.value) + "x" + std::to_string(film.height.value) +
                      " = " + std::to_string(pixels) + " pixels; at most " +
                      std::to_string(options_.limits.max_pixels) + " are accepted");
    }
  }

  void render(const RenderDesc& render) {
    if (render.spp.value < 1) diag_.error(render.spp.where, "spp must be >= 1, got " + str(render.spp.value));
    if (render.max_depth.value < 0)
      diag_.error(render.max_depth.where, "max_depth must be >= 0, got " + str(render.max_depth.value));
    colour(render.background, "background colour");
    radiometric(render.background, "background colour");
    if (!(render.clamp.value >= 0.0f))
      diag_.error(render.clamp.where, "clamp must be >= 0 (0 turns it off), got " + str(render.clamp.value));
    const Sourced<float>& terminator = render.shadow_terminator_geometry_offset;
    if (!(terminator.value >= 0.0f && terminator.value <= 1.0f))
      diag_.error(terminator.where, "shadow_terminator_geometry_offset must be between 0 and 1 (0 turns it off), got " +
                                        str(terminator.value));
    if (render.light_guiding.value < 0 || render.light_guiding.value > 1024)
      diag_.error(render.light_guiding.where,
                  "light_guiding must be between 0 and 1024 pre-pass paths per pixel (0 turns it off), got " +
                      str(render.light_guiding.value));
    if (render.path_guiding.value < 0 || render.path_guiding.value > 1024)
      diag_.error(render.path_guiding.where,
                  "path_guiding must be between 0 and 1024 pre-pass paths per pixel (0 turns it off), got " +
                      str(render.path_guiding.value));
  }

  void material(const MaterialDesc& m) {
    non_negative(m.kd, "kd");
    non_negative(m.ks, "ks");
    if (m.ka) non_negative(*m.ka, "ka");
    non_negative(m.exponent, "specular exponent");
    if (m.reflectivity.value < 0.0f || m.reflectivity.value > 1.0f)
      diag_.error(m.reflectivity.where, "reflectivity must be between 0 and 1, got " + str(m.reflectivity.value));
    if (m.ior.value <= 0.0f) diag_.error(m.ior.where, "index of refraction must be > 0, got " + str(m.ior.value));
    colour(m.diffuse, "diffuse colour");
    colour(m.specular, "specular colour");
    colour(m.emission, "emission");
    if (m.type == MaterialType::Glass || m.type == MaterialType::Dielectric) {
      const RGB t = m.transmittance.value;
      if (!(t.r >= 0.0f && t.g >= 0.0f && t.b >= 0.0f && t.r <= 1.0f && t.g <= 1.0f && t.b <= 1.0f))
        diag_.error(m.transmittance.where, "transmittance must be between 0 and 1 in every channel, got " + str(t));
    }
    radiometric(m.emission, "emission of material '" + m.name + "'");
    if (is_microfacet(m.type)) microfacet(m);
  }

  // The keys of the microfacet types (docs/scene-format.md).
  void microfacet(const MaterialDesc& m) {
    unit_interval(m.uroughness.value, m.uroughness.texture ? "roughness scale" : "roughness");
    const SourceLocation &u = m.uroughness.value.where, &v = m.vroughness.value.where;
    if (v.line != u.line || v.col != u.col)  // not "roughness" for both
      unit_interval(m.vroughness.value, m.vroughness.texture ? "roughness scale" : "roughness");
    if (m.type == MaterialType::Conductor && !m.schlick) {
      const RGB eta = m.eta.value;
      if (!(eta.r > 0.0f && eta.g > 0.0f && eta.b > 0.0f))
        diag_.error(m.eta.value.where, "a conductor's eta must be > 0 in every channel, got " + str(eta));
      colour(m.k.value, "a conductor's k");
    }
    if (m.type == MaterialType::MetallicRoughness)
      unit_interval(m.metallic.value, m.metallic.texture ? "metallic scale" : "metallic");
    if (has_coated_diffuse(m.type) || m.schlick) {
      const RGB r = m.reflectance.value;
      if (!(r.r >= 0.0f && r.g >= 0.0f && r.b >= 0.0f && r.r <= 1.0f && r.g <= 1.0f && r.b <= 1.0f))
        diag_.error(m.reflectance.value.where, "reflectance must be between 0 and 1 in every channel, got " + str(r));
    }
  }

  // After every radiometric value was seen: a reflectance that overflows
  // against the brightest of them (or on its own).
  void reflectance(const MaterialDesc& m) {
    const auto check = [&](const Sourced<RGB>& c, float scale, const char* name) {
      const double r = static_cast<double>(c.value.max_component()) * scale;
      if (!(r > kMaxRadiometric / std::max(1.0, brightest_))) return;
      std::string why = std::string(name) + " " + str(c.value) + (scale != 1.0f ? " times " + str(scale) : "");
      why += brightest_ > 1.0 ? " times the scene's brightest value " + str(brightest_) + " (the " + brightest_name_ +
                                    ")"
                              : std::string();
      diag_.error(c.where, why + " exceeds " + str(kMaxRadiometric) +
                               ": a path's radiance would overflow the float range (docs/scene-format.md, \"Value "
                               "limits\")");
    };
    check(m.diffuse, m.kd.value, "diffuse colour");
    check(m.specular, m.ks.value, "specular colour");
  }

  void light(const PointLightDesc& l) {
    colour(l.intensity, "light intensity");
    colour(l.specular_intensity, "specular intensity");
    radiometric(l.intensity, "point light's intensity");
    if (!(l.specular_intensity.value == l.intensity.value))  // by default the same value, reported once
      radiometric(l.specular_intensity, "point light's specular intensity");
  }

  void light(const DirectionalLightDesc& l) {
    if (!(length(l.direction.value) > 0.0f))
      diag_.error(l.direction.where, "a directional light's direction must not be zero");
    colour(l.irradiance, "irradiance");
    radiometric(l.irradiance, "directional light's irradiance");
  }

  void light(const AmbientLightDesc& l) {
    colour(l.intensity, "ambient intensity");
    radiometric(l.intensity, "ambient light's intensity");
  }

  void light(const SpotLightDesc& l) {
    colour(l.intensity, "light intensity");
    colour(l.specular_intensity, "specular intensity");
    radiometric(l.intensity, "spot light's intensity");
    if (!(l.specular_intensity.value == l.intensity.value))  // by default the same value, reported once
      radiometric(l.specular_intensity, "spot light's specular intensity");
    if (!(length(l.direction.value) > 0.0f))
      diag_.error(l.direction.where, "a spot light's direction must not be zero (look_at must differ from position)");
    const float cone = l.cone_angle.value, band = l.cone_delta.value;
    if (!(cone > 0.0f && cone <= 180.0f))
      diag_.error(l.cone_angle.where, "cone_angle must be between 0 (excluded) and 180 degrees, got " + str(cone));
    else if (!(band >= 0.0f && band <= cone))
      diag_.error(l.cone_delta.where, "cone_delta must be between 0 and cone_angle (" + str(cone) + "), got " + str(band));
  }

  void environment(const EnvironmentDesc& e) {
    if (!(e.intensity.value >= 0.0f))
      diag_.error(e.intensity.where, "environment intensity must be >= 0, got " + str(e.intensity.value));
    else if (e.intensity.value > kMaxRadiometric)  // its texels are checked against the bound when loaded
      diag_.error(e.intensity.where, "environment intensity " + str(e.intensity.value) + " exceeds " +
                                         str(kMaxRadiometric) + ": a path's radiance would overflow the float range " +
                                         "(docs/scene-format.md, \"Value limits\")");
    if (!(length(e.up.value) > 0.0f)) diag_.error(e.up.where, "environment up axis must not be zero");
  }

  // The shape's own rule (geometry/shapes/*.h), each problem reported at the
  // field it names (or at the shape).
  void shape(const ShapeDesc& s) {
    for (const ShapeProblem& p : shape_problems(s)) {
      if (p.warning) diag_.warning(s.at(p.field), p.message);
      else diag_.error(s.at(p.field), p.message);
    }
  }

 private:
  void resolution(const Sourced<int>& v, const char* name) {
    if (v.value < 1 || v.value > options_.limits.max_resolution)
      diag_.error(v.where, std::string(name) + " must be between 1 and " +
                               std::to_string(options_.limits.max_resolution) + ", got " + std::to_string(v.value));
  }

  void unit_interval(const Sourced<float>& v, const char* name) {
    if (!(v.value >= 0.0f && v.value <= 1.0f))
      diag_.error(v.where, std::string(name) + " must be between 0 and 1, got " + str(v.value));
  }

  void non_negative(const Sourced<float>& v, const char* name) {
    if (v.value < 0.0f) diag_.error(v.where, std::string(name) + " must be >= 0, got " + str(v.value));
  }

  // A radiometric value: within kMaxRadiometric; the brightest is remembered
  // for the reflectance products.
  void radiometric(const Sourced<RGB>& c, const std::string& name) {
    const float m = c.value.max_component();
    if (m > kMaxRadiometric) {
      diag_.error(c.where, name + " " + str(c.value) + " exceeds " + str(kMaxRadiometric) +
                               ": a path's radiance would overflow the float range (docs/scene-format.md, \"Value "
                               "limits\")");
      return;
    }
    if (m > brightest_) {
      brightest_ = m;
      brightest_name_ = name;
    }
  }

  void colour(const Sourced<RGB>& c, const char* name) {
    if (c.value.r < 0.0f || c.value.g < 0.0f || c.value.b < 0.0f)
      diag_.error(c.where, std::string(name) + " must not be negative, got " + str(c.value));
  }

  const LoadOptions& options_;
  Diagnostics& diag_;
  double brightest_ = 0.0;  // the largest radiometric value within the bound
  std::string brightest_name_;
};

// An infinite plane has infinite area, so an emitting one would have infinite
// power and no density to sample it by: refused, at the shape.
bool emitting_plane(const SceneDescription& scene, const ShapeDesc& s, Diagnostics& diag) {
  if (!std::holds_alternative<InfinitePlane>(s.geometry)) return false;
  if (s.material < 0 || static_cast<std::size_t>(s.material) >= scene.materials.size()) return false;
  const MaterialDesc& m = scene.materials[static_cast<std::size_t>(s.material)];
  const RGB e = m.emission.value;
  if (!(e.r > 0.0f || e.g > 0.0f || e.b > 0.0f)) return false;
  diag.error(s.where, "an infinite plane cannot be a light (its power would be infinite), but its material '" +
                          m.name + "' has emission; use a large quad or disc as the light");
  return true;
}

// An object is placed through instances, which hold bounded geometry: an
// infinite plane in one is refused (a plane is placed directly, transformed or not).
bool plane_in_object(const ObjectDesc& o, const ShapeDesc& s, Diagnostics& diag) {
  if (!std::holds_alternative<InfinitePlane>(s.geometry)) return false;
  diag.error(s.where, "an infinite plane cannot be part of object '" + o.name +
                          "' (instances hold bounded geometry); place the plane under \"shapes\" instead");
  return true;
}

}  // namespace

void validate_scene(const SceneDescription& scene, const LoadOptions& options, Diagnostics& diag) {
  Validator v(options, diag);
  v.camera(scene.camera);
  v.film(scene.film);
  v.render(scene.render);
  for (const MaterialDesc& m : scene.materials) v.material(m);
  for (const LightDesc& l : scene.lights) std::visit([&](const auto& light) { v.light(light); }, l);
  for (const MaterialDesc& m : scene.materials) v.reflectance(m);
  for (const ShapeDesc& s : scene.shapes) {
    v.shape(s);
    emitting_plane(scene, s, diag);
  }
  for (const ObjectDesc& o : scene.objects) {
    for (const ShapeDesc& s : o.shapes) {
      v.shape(s);
      plane_in_object(o, s, diag);
    }
  }
  if (scene.environment) v.environment(*scene.environment);
}

namespace {

bool shapes_usable(const std::vector<ShapeDesc>& shapes, const std::string& where, Diagnostics& diag) {
  bool ok = true;
  for (std::size_t i = 0; i < shapes.size(); ++i) {
    const ShapeDesc& s = shapes[i];
    for (const ShapeProblem& p : shape_problems(s)) {
      if (!p.unusable) continue;
      diag.error(s.at(p.field), where + "shape " + std::to_string(i) +
                                    (s.name.empty() ? "" : " ('" + s.name + "')") + ": " + p.message);
      ok = false;
    }
    if (s.transform && !s.transform->value.finite()) {
      diag.error(s.transform->where, where + "shape " + std::to_string(i) + ": its transform is singular or not finite");
      ok = false;
    }
  }
  return ok;
}

}  // namespace

bool check_shapes_usable(const SceneDescription& scene, Diagnostics& diag) {
  bool ok = shapes_usable(scene.shapes, "", diag);
  for (const ObjectDesc& o : scene.objects) ok = shapes_usable(o.shapes, "object '" + o.name + "': ", diag) && ok;
  for (const InstanceDesc& inst : scene.instances) {
    if (inst.transform && !inst.transform->value.finite()) {
      diag.error(inst.transform->where, "instance: its transform is singular or not finite");
      ok = false;
    }
  }
  for (const ShapeDesc& s : scene.shapes) {
    if (emitting_plane(scene, s, diag)) ok = false;
  }
  for (const ObjectDesc& o : scene.objects) {
    for (const ShapeDesc& s : o.shapes) {
      if (plane_in_object(o, s, diag)) ok = false;
    }
  }
  return ok;
}

}  // namespace pt
