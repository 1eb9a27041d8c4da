#include "render/lights/shape_light.h"

#include <algorithm>
#include <cmath>
#include <type_traits>
#include <variant>
#include <vector>

namespace pt {

namespace {

// The threshold below which 1 - cos(theta_max) is computed from sin^2 / 2 (pbrt-v4).
constexpr float kSmallSin2 = 0.00068523f;

}  // namespace

ShapeLight::ShapeLight(const Shape& shape, uint32_t shape_id, const Material& material,
                       std::shared_ptr<const ShapeAreaSampler> sampler)
    : shape_(&shape), shape_id_(shape_id), material_(&material), sampler_(std::move(sampler)) {
  area_ = std::visit([](const auto& s) { return s.area; }, *sampler_);
  if (!(area_ > 0.0f) || !std::isfinite(area_)) area_ = 0.0f;
  if (area_ > 0.0f) detect_parallelogram();
}

ShapeLight::ShapeLight(const Shape& shape, uint32_t shape_id, const Material& material, bool solid_angle_rectangles)
    : ShapeLight(shape, shape_id, material, std::make_shared<const ShapeAreaSampler>(make_area_sampler(shape))) {
  rectangle_ = solid_angle_rectangles && parallelogram_ &&
               std::fabs(dot(para_.e1, para_.e2)) <= 1e-4f * length(para_.e1) * length(para_.e2);
}

ShapeLight::ShapeLight(const Shape& shape, uint32_t shape_id, const Material& material, const Transform& transform,
                       uint32_t instance, std::shared_ptr<const ShapeAreaSampler> sampler)
    : ShapeLight(shape, shape_id, material,
                 sampler ? std::move(sampler) : std::make_shared<const ShapeAreaSampler>(make_area_sampler(shape))) {
  instance_ = instance;
  transform_ = &transform;
  if (const auto* sphere = std::get_if<Sphere>(&shape); sphere && transform.similarity) {
    world_sphere_ = *sphere;
    world_sphere_.center = transform.point(sphere->center);
    world_sphere_.radius = sphere->radius * transform.scale;
    has_world_sphere_ = true;
  }
  if (parallelogram_) {  // an affine map keeps a parallelogram one
    para_.p0 = transform.point(para_.p0);
    para_.e1 = transform.vector(para_.e1);
    para_.e2 = transform.vector(para_.e2);
    para_.n = normalize(transform.normal(para_.n));
    area_ = length(cross(para_.e1, para_.e2));
    if (!(area_ > 0.0f) || !std::isfinite(area_)) area_ = 0.0f;
  } else if (area_ > 0.0f && !transform.similarity) {
    weigh_triangles_by_world_area(transform);
  }
}

const TriangleAreaSampler* ShapeLight::triangle_sampler() const {
  return std::visit(
      [](const auto& s) -> const TriangleAreaSampler* {
        if constexpr (std::is_same_v<std::decay_t<decltype(s)>, TriangleAreaSampler>) {
          return &s;
        } else {
          return nullptr;
        }
      },
      *sampler_);
}

void ShapeLight::weigh_triangles_by_world_area(const Transform& transform) {
  const TriangleAreaSampler* sampler = triangle_sampler();
  if (sampler == nullptr) return;
  std::vector<float> areas(sampler->triangles.size());
  double total = 0.0;
  for (std::size_t i = 0; i < areas.size(); ++i) {
    const Triangle& t = sampler->triangles[i];
    areas[i] = 0.5f * length(cross(transform.vector(t.e1), transform.vector(t.e2)));
    total += areas[i];
  }
  world_parts_ = Distribution1D(areas);
  area_ = static_cast<float>(total);
  if (!(area_ > 0.0f) || !std::isfinite(area_)) area_ = 0.0f;
  world_triangles_ = true;
}

const Sphere* ShapeLight::cone_sphere() const {
  if (transform_ == nullptr) return std::get_if<Sphere>(shape_);
  return has_world_sphere_ ? &world_sphere_ : nullptr;
}

float ShapeLight::area_at(Vec3f n) const {
  if (transform_ == nullptr || parallelogram_ || world_triangles_) return area_;
  return area_ * std::fabs(transform_->det) / length(transform_->transpose_vector(n));
}

bool ShapeLight::spherical_rectangle(Vec3f p, SphericalRectangle& r) const {
  return rectangle_ && make_spherical_rectangle(p, para_.p0, para_.e1, para_.e2, r) &&
         r.solid_angle >= kMinSphericalRectangle;
}

bool ShapeLight::make_parallelogram(Vec3f a, Vec3f b, Vec3f c, Vec3f d, Vec3f n, Triangle& out) {
  const Vec3f e1 = b - a, e2 = d - a;
  const float size = length(e1) + length(e2);
  // The diagonals bisect each other: a + c = b + d.
  if (!(length(a + c - b - d) <= 1e-5f * size)) return false;
  const Vec3f c12 = cross(e1, e2);
  const float len = length(c12);
  if (!(len > 0.0f) || !(dot(c12, n) > 0.9999f * len)) return false;  // planar, and facing n
  out = {a, e1, e2, n};
  return true;
}

void ShapeLight::detect_parallelogram() {
  const TriangleAreaSampler* sampler = triangle_sampler();
  if (sampler == nullptr) return;
  const std::vector<Triangle>& tris = sampler->triangles;
  if (const auto* q = std::get_if<Quad>(shape_)) {
    parallelogram_ = make_parallelogram(q->v[0], q->v[1], q->v[2], q->v[3], tris[0].n, para_);
    return;
  }
  const auto* m = std::get_if<TriangleMesh>(shape_);
  if (!m || m->triangle_count() != 2) return;
  if (!(dot(tris[0].n, tris[1].n) > 0.9999f)) return;  // both halves face the same way
  const uint32_t* t0 = &m->indices[0];
  const uint32_t* t1 = &m->indices[3];
  // The corner of each triangle that the other lacks; the other two are shared.
  int own0 = -1, own1 = -1, shared = 0;
  for (int i = 0; i < 3; ++i) {
    const bool in1 = t0[i] == t1[0] || t0[i] == t1[1] || t0[i] == t1[2];
    if (in1) ++shared;
    else own0 = i;
    if (t1[i] != t0[0] && t1[i] != t0[1] && t1[i] != t0[2]) own1 = i;
  }
  if (shared != 2 || own0 < 0 || own1 < 0) return;
  // Around the quad: own0, the next corner of t0, own1, the corner after that.
  const Vec3f a = m->positions[t0[own0]];
  const Vec3f b = m->positions[t0[(own0 + 1) % 3]];
  const Vec3f c = m->positions[t1[own1]];
  const Vec3f d = m->positions[t0[(own0 + 2) % 3]];
  // Orient e1 x e2 along the triangles' normal.
  const Vec3f n = tris[0].n;
  parallelogram_ = make_parallelogram(a, b, c, d, n, para_) || make_parallelogram(a, d, c, b, n, para_);
}

float ShapeLight::world_area() const {
  // A transformed curved shape's world area is estimated (exact for
  // similarities; triangles are measured in world space): it only sets how
  // often the light is chosen.
  return transform_ == nullptr || parallelogram_ || world_triangles_
             ? area_
             : area_ * std::cbrt(transform_->det * transform_->det);
}

float ShapeLight::power() const {
  const RGB& L = material_->emission;
  return kPi * world_area() * (L.r + L.g + L.b) / 3.0f * (material_->two_sided ? 2.0f : 1.0f);
}

DirectionCone ShapeLight::normal_cone() const {
  if (parallelogram_) return DirectionCone::around(para_.n);  // already in world space
  const auto world = [&](Vec3f n) { return transform_ ? normalize(transform_->normal(n)) : n; };
  if (const auto* disc = std::get_if<DiscAreaSampler>(sampler_.get())) return DirectionCone::around(world(disc->disc.normal));
  const TriangleAreaSampler* tris = triangle_sampler();
  if (tris == nullptr) return DirectionCone::all();  // curved: normals every way
  DirectionCone cone;
  Vec3f first;
  bool flat = true;
  for (const Triangle& t : tris->triangles) {
    if (!(length_squared(cross(t.e1, t.e2)) > 0.0f)) continue;  // never sampled, never hit
    if (cone.empty) first = t.n;
    flat = flat && t.n == first;
    cone = cone_union(cone, DirectionCone::around(t.n));
  }
  if (cone.empty) return DirectionCone::all();
  if (flat) return DirectionCone::around(world(first));
  if (transform_ == nullptr) return cone;
  // A transform turns the normals: bound them again in world space.
  DirectionCone out;
  for (const Triangle& t : tris->triangles)
    if (length_squared(cross(t.e1, t.e2)) > 0.0f) out = cone_union(out, DirectionCone::around(world(t.n)));
  return out;
}

bool ShapeLight::bounds(LightBounds& out) const {
  if (!(area_ > 0.0f)) return false;
  const RGB& L = material_->emission;
  const float radiance = (L.r + L.g + L.b) / 3.0f;
  Bounds3f b = pt::bounds(*shape_);
  if (transform_ != nullptr) b = transform_->bounds(b);
  if (b.empty() || !is_finite(b.lo) || !is_finite(b.hi) || !(radiance > 0.0f)) return false;
  out.bounds = b;
  out.normals = normal_cone();
  // Radiant intensity along the axis: at most L A for a light whose normals
  // share a hemisphere; one whose normals point every way shows less of its
  // area to any direction (a sphere a quarter: Cauchy's mean for convex shapes).
  const bool one_way = out.normals.cos_theta > 0.0f;
  out.intensity = radiance * world_area() * (one_way ? 1.0f : 0.25f);
  out.cos_theta_e = 0.0f;  // surfaces emit over the hemisphere of each normal
  out.two_sided = material_->two_sided;
  return std::isfinite(out.intensity) && out.intensity > 0.0f;
}

void ShapeLight::sample_area(Vec2f u, Vec3f& q, Vec3f& n, int& prim) const {
  prim = -1;
  if (parallelogram_) {
    q = para_.p0 + para_.e1 * u.x + para_.e2 * u.y;
    n = para_.n;
    return;
  }
  std::size_t part = 0;
  if (const TriangleAreaSampler* t = triangle_sampler()) {
    t->sample(world_triangles_ ? world_parts_ : t->parts, u, q, n, &part);
  } else {
    std::visit([&](const auto& sampler) { sampler.sample(u, q, n); }, *sampler_);
  }
  // A mesh's triangle is its primitive; every other shape is one primitive.
  prim = std::holds_alternative<TriangleMesh>(*shape_) ? static_cast<int>(part) : 0;
  if (transform_ != nullptr) {
    q = transform_->point(q);
    n = normalize(transform_->normal(n));
  }
}

bool ShapeLight::sample_sphere_cone(const Sphere& s, Vec3f p, Vec2f u, LightSample& out) const {
  const Vec3f to_centre = s.center - p;
  const float dc2 = length_squared(to_centre);
  const float dc = std::sqrt(dc2);
  const float sin2_max = s.radius * s.radius / dc2;
  const float cos_max = std::sqrt(std::max(0.0f, 1.0f - sin2_max));
  const float one_minus_cos_max = sin2_max < kSmallSin2 ? 0.5f * sin2_max : sin2_max / (1.0f + cos_max);
  const Frame frame = Frame::from_normal(to_centre / dc);
  const Vec3f local = sample_uniform_cone(u, one_minus_cos_max);
  // The point where the direction meets the sphere: the angle alpha at the
  // centre between -axis and the point follows from the law of sines.
  // sin^2(theta) from the sample's own components: 1 - cos^2 would cancel
  // catastrophically for a small, distant sphere (theta ~ 1e-3), turning the
  // point and its normal around and losing the sample's emission.
  const float cos_theta = local.z;
  const float sin2_theta = std::min(sin2_max, local.x * local.x + local.y * local.y);
  const float sin_max = std::sqrt(sin2_max);
  const float cos_alpha = sin2_theta / sin_max +
                          cos_theta * std::sqrt(std::max(0.0f, 1.0f - sin2_theta / sin2_max));
  const float sin_alpha = std::sqrt(std::max(0.0f, 1.0f - cos_alpha * cos_alpha));
  const float sin_theta = std::sqrt(sin2_theta);
  const float cos_phi = sin_theta > 0.0f ? local.x / sin_theta : 1.0f;
  const float sin_phi = sin_theta > 0.0f ? local.y / sin_theta : 0.0f;
  // The point's offset from the centre leans the same way (phi) as the direction.
  const Vec3f n_local(sin_alpha * cos_phi, sin_alpha * sin_phi, -cos_alpha);
  out.n_light = frame.from_local(n_local);
  out.p_light = s.center + out.n_light * s.radius;
  out.wi = frame.from_local(local);
  out.pdf = uniform_cone_pdf(one_minus_cos_max);
  return true;
}

bool ShapeLight::sample(Vec3f p, Vec2f u, LightSample& s) const {
  if (!(area_ > 0.0f)) return false;
  // A one-sided flat light sends nothing to the points behind its plane.
  if (parallelogram_ && !material_->two_sided && !(dot(p - para_.p0, para_.n) > 0.0f)) return false;
  const Sphere* sphere = cone_sphere();
  SphericalRectangle rect;
  int prim = -1;
  if (sphere && length_squared(p - sphere->center) > sphere->radius * sphere->radius * 1.0001f) {
    sample_sphere_cone(*sphere, p, u, s);
    prim = 0;
  } else if (spherical_rectangle(p, rect)) {
    s.p_light = sample_spherical_rectangle(rect, u);
    s.n_light = para_.n;
    const Vec3f d = s.p_light - p;
    const float d2 = length_squared(d);
    if (!(d2 > 0.0f)) return false;
    s.wi = d / std::sqrt(d2);
    s.pdf = 1.0f / rect.solid_angle;
  } else {
    sample_area(u, s.p_light, s.n_light, prim);
    const Vec3f d = s.p_light - p;
    const float d2 = length_squared(d);
    if (!(d2 > 0.0f)) return false;
    s.wi = d / std::sqrt(d2);
    const float cos_l = std::fabs(dot(s.n_light, s.wi));
    if (!(cos_l > 0.0f)) return false;
    s.pdf = d2 / (cos_l * area_at(s.n_light));
  }
  if (!(s.pdf > 0.0f) || !std::isfinite(s.pdf)) return false;
  s.L = material_->emitted(s.n_light, -s.wi,
                           material_->emission_texture ? tex_coord_at(s.p_light, s.n_light, prim) : TexCoord());
  return true;
}

TexCoord ShapeLight::tex_coord_at(Vec3f q, Vec3f n, int prim) const {
  if (transform_ != nullptr) {
    q = transform_->inverse_point(q);
    n = normalize(transform_->transpose_vector(n));
  }
  // From just off the surface along n, back onto q: the nearest hit of the
  // primitive is q itself (h is far below any shape's size, far above float spacing).
  const float h = 1e-3f * (1.0f + std::max(std::fabs(q.x), std::max(std::fabs(q.y), std::fabs(q.z))));
  const uint32_t first = prim >= 0 ? static_cast<uint32_t>(prim) : 0u;
  const uint32_t last = prim >= 0 ? first + 1 : std::min(primitive_count(*shape_), 2u);
  for (const float side : {1.0f, -1.0f}) {
    const Ray ray{q + n * (side * h), n * -side, 0.0f, 4.0f * h};
    for (uint32_t i = first; i < last; ++i) {
      PrimHit hit;
      const bool found =
          std::visit([&](const auto& shape) { return intersect_primitive(shape, i, ray, hit); }, *shape_);
      if (!found) continue;
      const SurfaceGeometry g = surface(*shape_, i, ray, hit);
      return TexCoord(g.uv, {}, {}, g.p);
    }
  }
  return TexCoord();  // never met (a degenerate sample): the texture's lookup at uv (0, 0)
}

float ShapeLight::pdf(Vec3f p, Vec3f wi, Vec3f q, Vec3f n) const {
  if (!(area_ > 0.0f)) return 0.0f;
  if (const Sphere* sphere = cone_sphere()) {
    const float dc2 = length_squared(p - sphere->center);
    const float r2 = sphere->radius * sphere->radius;
    if (dc2 > r2 * 1.0001f) {
      const float sin2_max = r2 / dc2;
      const float cos_max = std::sqrt(std::max(0.0f, 1.0f - sin2_max));
      const float omc = sin2_max < kSmallSin2 ? 0.5f * sin2_max : sin2_max / (1.0f + cos_max);
      return uniform_cone_pdf(omc);
    }
  }
  SphericalRectangle rect;
  if (spherical_rectangle(p, rect)) return 1.0f / rect.solid_angle;
  const float d2 = length_squared(q - p);
  const float cos_l = std::fabs(dot(n, wi));
  if (!(cos_l > 0.0f)) return 0.0f;
  return d2 / (cos_l * area_at(n));
}

}  // namespace pt
