// Area lights of the Path of Light family. The course requires them but gives
// no keys, so students' files spell them in several ways; each becomes an
// emissive shape (docs/scene-format.md, "Area lights in Path of Light files"),
// which the path integrator samples as an area light.
#include <cmath>
#include <string>
#include <vector>

#include "scene/legacy_common.h"
#include "scene/suggest.h"

namespace pt {
namespace {

// A flat emitter (quad, triangle, planar mesh) shows its whole area face-on; a
// closed convex one (sphere, capped cylinder) shows a quarter of it on average
// over directions (Cauchy's formula; exactly so for a sphere).
bool is_flat(const Shape& geometry) {
  if (std::holds_alternative<Quad>(geometry)) return true;
  const TriangleMesh* m = std::get_if<TriangleMesh>(&geometry);
  if (!m || m->indices.size() < 3) return false;
  const Vec3f a = m->positions[m->indices[0]];
  const Vec3f n = cross(m->positions[m->indices[1]] - a, m->positions[m->indices[2]] - a);
  const Bounds3f b = bounds(*m);
  const float size = length(b.hi - b.lo);
  if (!(length(n) > 0.0f) || !(size > 0.0f)) return false;
  const Vec3f unit = normalize(n);
  for (uint32_t i : m->indices)
    if (std::fabs(dot(m->positions[i] - a, unit)) > 1e-4f * size) return false;
  return true;
}

float area_of(const Shape& geometry) {
  return std::visit([](const auto& s) { return make_area_sampler(s).area; }, geometry);
}

// The emitted radiance that makes the light, seen face-on from afar, as bright
// as the family's point light of the same "id" at its centre: a native point
// light of intensity id / (4 pi) is a physical radiant intensity of id / 4, and
// an emitter of radiance L shows intensity L * (projected area).
RGB radiance_for(const RGB& id, const Shape& geometry) {
  const float area = area_of(geometry);
  const float projected = is_flat(geometry) ? area : 0.25f * area;
  return projected > 0.0f ? id * (0.25f / projected) : RGB(0, 0, 0);
}

// "id" (with "is", which must agree: an emitter has one radiance) or "intensity".
bool read_intensity(ObjectReader& r, Sourced<RGB>& out) {
  if (!r.get("id") && !r.get("intensity")) return r.require("id") != nullptr;  // "missing key 'id'"
  const char* key = find_aliased(r, {"id", "intensity"});
  if (!key || !r.read(key, out)) return false;
  Sourced<RGB> specular;
  if (r.read("is", specular) && specular.where.valid() &&
      (specular.value.r != out.value.r || specular.value.g != out.value.g || specular.value.b != out.value.b)) {
    r.context().diag.warning(specular.where, "an area light has a single emission: 'is' differs from '" +
                                                 std::string(key) + "' and is not used");
  }
  return true;
}

// The corners of the light: v0..v3 (quad, perimeter order), v0..v2 (triangle),
// c1, c2, c3 (parallelogram: c1 the corner shared by the edges to c2 and c3),
// or position (the centre), u, v (directions), width, height.
bool read_light_shape(ImportContext& ctx, ObjectReader& r, ShapeDesc& shape) {
  if (r.get("v0")) {
    Sourced<Vec3f> c[4];
    const int n = r.get("v3") ? 4 : 3;
    if (!read_corners(r, n, c)) return false;
    if (n == 3) {
      shape.geometry = make_triangle(c[0], c[1], c[2]);
    } else {
      shape.geometry = Quad{{c[0], c[1], c[2], c[3]}};
      order_quad_corners(ctx, c, std::get<Quad>(shape.geometry));
    }
    return true;
  }
  if (r.get("c1")) {
    Sourced<Vec3f> c1, c2, c3;
    if (!(r.read_required("c1", c1) & r.read_required("c2", c2) & r.read_required("c3", c3))) return false;
    ctx.diag().warning(c1.where, "area light corners c1, c2, c3 taken as a parallelogram with c1 the corner "
                                 "between c2 and c3 (the fourth corner is c2 + c3 - c1)");
    shape.geometry = Quad{{c1.value, c2.value, c2.value + c3.value - c1.value, c3.value}};
    return true;
  }
  if (r.get("position")) {
    Sourced<Vec3f> centre, u, v;
    Sourced<float> width, height;
    if (!(r.read_required("position", centre) & r.read_required("u", u) & r.read_required("v", v) &
          r.read_required("width", width) & r.read_required("height", height)))
      return false;
    if (!(length(u.value) > 0.0f) || !(length(v.value) > 0.0f)) {
      ctx.diag().error(length(u.value) > 0.0f ? v.where : u.where, "an area light's 'u' and 'v' must not be zero");
      return false;
    }
    ctx.diag().warning(centre.where, "area light 'position' taken as the centre of the rectangle; 'u' and 'v' "
                                     "as the directions of its 'width' and 'height'");
    const Vec3f du = normalize(u.value) * (0.5f * width.value), dv = normalize(v.value) * (0.5f * height.value);
    const Vec3f p = centre.value;
    shape.geometry = Quad{{p - du - dv, p + du - dv, p + du + dv, p - du + dv}};
    return true;
  }
  ctx.diag().error(r.where(), "an area light needs its shape: corners 'v0'..'v3' (quad) or 'v0'..'v2' "
                              "(triangle), 'c1', 'c2', 'c3' (parallelogram), 'position', 'u', 'v', 'width', "
                              "'height' (rectangle), or 'shapeid' (a shape of the scene)");
  return false;
}

// The emissive material of a light shape: `base` emitting `radiance`, sampled
// at `samples` points by the classic integrator (0: its default).
int add_light_material(ImportContext& ctx, const MaterialDesc& base, const RGB& radiance, bool two_sided,
                       const Sourced<int>& samples, SourceLocation where) {
  MaterialDesc m = base;
  m.emission = Sourced<RGB>(radiance, where);
  m.two_sided = Sourced<bool>(two_sided, where);
  m.light_samples = samples;
  m.name = "material " + std::to_string(ctx.scene.materials.size());
  ctx.scene.materials.push_back(std::move(m));
  return static_cast<int>(ctx.scene.materials.size() - 1);
}

// "shapeid": the named shape emits (its own material is kept for reflection).
void make_shape_emit(ImportContext& ctx, ObjectReader& r, const Sourced<std::string>& id,
                     const Sourced<RGB>& intensity, const Sourced<int>& samples) {
  std::vector<std::string> names;
  for (ShapeDesc& shape : ctx.scene.shapes) {
    if (shape.name != id.value) {
      if (!shape.name.empty()) names.push_back(shape.name);
      continue;
    }
    const bool flat = is_flat(shape.geometry);
    const MaterialDesc base = ctx.scene.materials[static_cast<std::size_t>(shape.material)];
    shape.material = add_light_material(ctx, base, radiance_for(intensity.value, shape.geometry),
                                        flat || std::holds_alternative<TriangleMesh>(shape.geometry), samples,
                                        r.where());
    return;
  }
  std::string message = "no shape has the id '" + id.value + "' named by this area light's 'shapeid'";
  message += did_you_mean(id.value, names);
  ctx.diag().error(id.where, std::move(message));
  r.fail();
}

}  // namespace

void read_area_light(ImportContext& ctx, ObjectReader& r) {
  r.set_what("area light");
  r.allow({"method", "sampling"});  // the integrator's own light sampling decides
  Sourced<RGB> intensity;
  const bool have_intensity = read_intensity(r, intensity);
  Sourced<int> samples{0};  // the classic integrator's samples per shading point
  if (r.get("samples") && r.read("samples", samples) && samples.value < 1) {
    ctx.diag().error(samples.where, "an area light's 'samples' must be at least 1");
    r.fail();
  }
  Sourced<std::string> id;
  if (r.get("shapeid")) {
    const bool ok = r.read("shapeid", id);
    r.finish();
    if (ok && have_intensity && r.ok()) make_shape_emit(ctx, r, id, intensity, samples);
    return;
  }
  ShapeDesc shape;
  shape.where = r.where();
  shape.type = "arealight";
  const bool ok = read_light_shape(ctx, r, shape);
  r.finish();
  if (!ok || !have_intensity || !r.ok()) return;
  MaterialDesc black;  // the lamp reflects nothing
  black.kd = Sourced<float>(0.0f, r.where());
  black.where = r.where();
  shape.material =
      add_light_material(ctx, black, radiance_for(intensity.value, shape.geometry), true, samples, r.where());
  shape.name = "area light";
  ctx.scene.shapes.push_back(std::move(shape));
}

}  // namespace pt
