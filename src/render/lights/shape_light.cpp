#include "render/lights/shape_light.h"

#include <cmath>
#include <vector>

namespace pt {

namespace {

// The threshold below which 1 - cos(theta_max) is computed from sin^2 / 2 (pbrt-v4).
constexpr float kSmallSin2 = 0.00068523f;

float triangle_area(Vec3f a, Vec3f b, Vec3f c) { return 0.5f * length(cross(b - a, c - a)); }

// As geometry/quad.cpp: the orientation of cross(v1 - v0, v3 - v0).
Vec3f quad_normal(const Quad& q) {
  Vec3f n = cross(q.v[2] - q.v[0], q.v[3] - q.v[1]);
  if (!(length(n) > 0.0f)) n = cross(q.v[1] - q.v[0], q.v[2] - q.v[0]);
  const float len = length(n);
  return len > 0.0f ? n / len : Vec3f(0, 0, 1);
}

}  // namespace

ShapeLight::ShapeLight(const Shape& shape, uint32_t shape_id, const Material& material)
    : shape_(&shape), shape_id_(shape_id), material_(&material) {
  if (const auto* s = std::get_if<Sphere>(&shape)) {
    area_ = 4.0f * kPi * s->radius * s->radius;
  } else if (const auto* q = std::get_if<Quad>(&shape)) {
    const float a0 = triangle_area(q->v[0], q->v[1], q->v[2]), a1 = triangle_area(q->v[0], q->v[2], q->v[3]);
    area_ = a0 + a1;
    parts_ = Distribution1D({a0, a1});
    const Vec3f n = quad_normal(*q);  // both halves share the quad's normal
    triangles_.push_back({q->v[0], q->v[1] - q->v[0], q->v[2] - q->v[0], n});
    triangles_.push_back({q->v[0], q->v[2] - q->v[0], q->v[3] - q->v[0], n});
  } else if (const auto* m = std::get_if<TriangleMesh>(&shape)) {
    std::vector<float> areas(m->triangle_count());
    triangles_.reserve(areas.size());
    double total = 0.0;
    for (std::size_t t = 0; t < areas.size(); ++t) {
      const uint32_t* idx = &m->indices[3 * t];
      const Vec3f p0 = m->positions[idx[0]], p1 = m->positions[idx[1]], p2 = m->positions[idx[2]];
      const Vec3f c = cross(p1 - p0, p2 - p0);
      const float len = length(c);
      areas[t] = 0.5f * len;
      total += areas[t];
      triangles_.push_back({p0, p1 - p0, p2 - p0, len > 0.0f ? c / len : Vec3f(0, 0, 1)});
    }
    area_ = static_cast<float>(total);
    parts_ = Distribution1D(areas);
  } else if (const auto* c = std::get_if<Cylinder>(&shape)) {
    const float h = length(c->p1 - c->p0), cap = kPi * c->radius * c->radius;
    const float side = 2.0f * kPi * c->radius * h;
    area_ = side + 2.0f * cap;
    parts_ = Distribution1D({side, cap, cap});
  }
  if (!(area_ > 0.0f) || !std::isfinite(area_)) area_ = 0.0f;
}

float ShapeLight::power() const {
  const RGB& L = material_->emission;
  return kPi * area_ * (L.r + L.g + L.b) / 3.0f * (material_->two_sided ? 2.0f : 1.0f);
}

void ShapeLight::sample_area(Vec2f u, Vec3f& q, Vec3f& n) const {
  if (const auto* s = std::get_if<Sphere>(shape_)) {
    n = sample_uniform_sphere(u);
    q = s->center + n * s->radius;
    return;
  }
  float pmf = 0.0f;
  std::size_t part = 0;
  const float x = parts_.sample_continuous(u.x, &pmf, &part);
  // The position of u.x inside its cell, back in [0, 1).
  const float n_parts = static_cast<float>(parts_.size());
  const Vec2f v(std::min(x * n_parts - static_cast<float>(part), kOneMinusEpsilon), u.y);
  if (!triangles_.empty()) {  // a mesh or a quad
    const Triangle& t = triangles_[part];
    const Vec3f b = sample_uniform_triangle(v);
    q = t.p0 + t.e1 * b.y + t.e2 * b.z;
    n = t.n;
  } else if (const auto* c = std::get_if<Cylinder>(shape_)) {
    const Vec3f axis = c->p1 - c->p0;
    const Frame frame = Frame::from_normal(normalize(axis));
    if (part == 0) {
      const float phi = 2.0f * kPi * v.y;
      n = frame.s * std::cos(phi) + frame.t * std::sin(phi);
      q = c->p0 + axis * v.x + n * c->radius;
    } else {
      const Vec2f d = sample_uniform_disk_concentric(v);
      const Vec3f centre = part == 1 ? c->p0 : c->p1;
      q = centre + (frame.s * d.x + frame.t * d.y) * c->radius;
      n = part == 1 ? -frame.n : frame.n;
    }
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
  s.delta = false;
  s.infinite = false;
  const auto* sphere = std::get_if<Sphere>(shape_);
  if (sphere && length_squared(p - sphere->center) > sphere->radius * sphere->radius * 1.0001f) {
    sample_sphere_cone(*sphere, p, u, s);
  } else {
    sample_area(u, s.p_light, s.n_light);
    const Vec3f d = s.p_light - p;
    const float d2 = length_squared(d);
    if (!(d2 > 0.0f)) return false;
    s.wi = d / std::sqrt(d2);
    const float cos_l = std::fabs(dot(s.n_light, s.wi));
    if (!(cos_l > 0.0f)) return false;
    s.pdf = d2 / (cos_l * area_);
  }
  if (!(s.pdf > 0.0f) || !std::isfinite(s.pdf)) return false;
  s.L = material_->emitted(s.n_light, -s.wi);
  return true;
}

float ShapeLight::pdf(Vec3f p, Vec3f wi, Vec3f q, Vec3f n) const {
  if (!(area_ > 0.0f)) return 0.0f;
  if (const auto* sphere = std::get_if<Sphere>(shape_)) {
    const float dc2 = length_squared(p - sphere->center);
    const float r2 = sphere->radius * sphere->radius;
    if (dc2 > r2 * 1.0001f) {
      const float sin2_max = r2 / dc2;
      const float cos_max = std::sqrt(std::max(0.0f, 1.0f - sin2_max));
      const float omc = sin2_max < kSmallSin2 ? 0.5f * sin2_max : sin2_max / (1.0f + cos_max);
      return uniform_cone_pdf(omc);
    }
  }
  const float d2 = length_squared(q - p);
  const float cos_l = std::fabs(dot(n, wi));
  if (!(cos_l > 0.0f)) return 0.0f;
  return d2 / (cos_l * area_);
}

}  // namespace pt
