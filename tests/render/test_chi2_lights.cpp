// Light sampling against the densities the integrator uses for MIS
// (chi-square, chi2.h): sphere lights by solid angle (outside) and by area
// (inside), quads, meshes, cylinders, discs, polygons and cones by area
// (parallelograms directly),
// rectangles by solid angle, and the environment map.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "chi2.h"
#include "core/rng.h"
#include "geometry/shapes.h"
#include "render/lights/environment.h"
#include "render/lights/shape_light.h"

namespace pt {
namespace {

using test::DirectionChi2;

Material emitter() {
  Material m;
  m.emission = RGB(1.0f);
  m.two_sided = true;
  return m;
}

// The density of direction wi from p under ShapeLight::sample. Spheres seen
// from outside are sampled inside the cone they subtend: the density is
// ShapeLight::pdf at the first hit, as the integrator evaluates it for MIS.
// Every other shape is sampled uniformly by area, hidden parts included, so a
// direction that crosses the shape k times has the sum of the k area-to-solid-
// angle densities (the integrator's MIS uses the first one: the others are
// occluded and never contribute).
// With `xf` the shape is placed by that transform (an instance's light): the
// ray is intersected in object space and the surface carried to world space.
float light_pdf(const ShapeLight& light, const Shape& shape, Vec3f p, Vec3f wi, const Transform* xf = nullptr) {
  Ray ray;
  ray.origin = p;
  ray.dir = wi;
  if (xf) ray = xf->to_object(ray);
  const bool sphere = std::holds_alternative<Sphere>(shape);
  float sum = 0.0f;
  auto add = [&](uint32_t prim, const PrimHit& hit) {
    SurfaceGeometry g = surface(shape, prim, ray, hit);
    if (xf) g = to_world(g, *xf);
    sum += light.pdf(p, wi, g.p, g.ng);
  };
  if (const auto* m = std::get_if<TriangleMesh>(&shape)) {
    for (uint32_t t = 0; t < m->triangle_count(); ++t) {
      PrimHit h;
      if (intersect(*m, t, ray, h)) add(t, h);
    }
    return sum;
  }
  for (int crossing = 0; crossing < 4; ++crossing) {
    PrimHit h;
    const bool found = std::visit(
        [&](const auto& s) {
          if constexpr (std::is_same_v<std::decay_t<decltype(s)>, TriangleMesh>) {
            return false;
          } else {
            return intersect_primitive(s, 0, ray, h);
          }
        },
        shape);
    if (!found) break;
    add(0, h);
    if (sphere) break;
    ray.tmin = h.t * (1.0f + 1e-5f);
  }
  return sum;
}

test::Chi2Result light_chi2(const Shape& shape, Vec3f p, const Frame& bins = Frame(), int n_theta = 32,
                            const Transform* xf = nullptr) {
  const Material m = emitter();
  const ShapeLight light = xf ? ShapeLight(shape, 0, m, *xf, 0) : ShapeLight(shape, 0, m);
  DirectionChi2 t;
  t.bins = bins;
  t.n_theta = n_theta;
  t.n_phi = 2 * n_theta;
  t.sample = [&](float, Vec2f u, Vec3f& d) {
    LightSample s;
    if (!light.sample(p, u, s)) return false;
    // The sampled point lies along wi, and the sample's density is pdf()'s.
    const Vec3f to_point = normalize(s.p_light - p);
    if (length(to_point - s.wi) > 1e-3f) return false;
    d = s.wi;
    return true;
  };
  t.pdf = [&](Vec3f d) { return light_pdf(light, shape, p, d, xf); };
  return t.run();
}

TEST(LightChi2, SphereBySolidAngleFromOutside) {
  Sphere s;
  s.center = Vec3f(0.3f, -0.2f, 0.5f);
  s.radius = 0.7f;
  for (float distance : {1.2f, 3.0f, 40.0f}) {
    const Vec3f p = s.center + normalize(Vec3f(1, 2, -0.5f)) * (distance * s.radius);
    // A distant sphere subtends a small cone: bin it finely, across its axis.
    const bool narrow = distance > 10.0f;
    const auto r = light_chi2(s, p, narrow ? test::frame_across(s.center - p) : Frame(), narrow ? 128 : 32);
    EXPECT_TRUE(r.passed) << "distance " << distance << " radii: " << r.message;
  }
}

TEST(LightChi2, SphereByAreaFromInside) {
  Sphere s;
  s.radius = 2.0f;
  const auto r = light_chi2(s, Vec3f(0.5f, 0.3f, -0.9f));
  EXPECT_TRUE(r.passed) << r.message;
}

TEST(LightChi2, QuadByArea) {
  Quad q;  // a trapezoid, so the two triangles differ in area
  q.v[0] = Vec3f(-1, -0.5f, 2);
  q.v[1] = Vec3f(1, -0.5f, 2);
  q.v[2] = Vec3f(0.4f, 0.7f, 2.2f);
  q.v[3] = Vec3f(-0.4f, 0.7f, 2.2f);
  const auto r = light_chi2(q, Vec3f(0.1f, 0.2f, 0.0f));
  EXPECT_TRUE(r.passed) << r.message;
}

TEST(LightChi2, MeshByArea) {
  TriangleMesh m;  // three triangles of different sizes, facing different ways
  m.positions = {{-1, 0, 2}, {1, 0, 2}, {0, 1, 2}, {1.5f, -1, 1}, {2, 1, 1.5f}, {1.5f, 0, 0}, {-2, -1, 0}, {-1, -1.5f, 1}};
  m.indices = {0, 1, 2, 3, 4, 5, 6, 7, 0};
  const auto r = light_chi2(m, Vec3f(0, 0, -0.5f));
  EXPECT_TRUE(r.passed) << r.message;
}

// Two triangles sharing an edge that make a parallelogram (a rectangle, as
// area lights usually are, and a slanted one) are sampled as one; the
// density is still uniform by area.
TEST(LightChi2, ParallelogramMeshByArea) {
  TriangleMesh rect;  // the Cornell box's light, scaled, as its two triangles
  rect.positions = {{-0.6f, 1.0f, 0.4f}, {-0.6f, 1.0f, -0.5f}, {0.55f, 1.0f, -0.5f}, {0.55f, 1.0f, 0.4f}};
  rect.indices = {0, 1, 2, 0, 2, 3};
  TriangleMesh slanted;  // another winding and split diagonal, not axis-aligned
  slanted.positions = {{0.2f, -0.4f, 1.8f}, {1.1f, -0.1f, 2.3f}, {0.6f, 0.9f, 1.6f}, {-0.3f, 0.6f, 1.1f}};
  slanted.indices = {1, 2, 3, 3, 0, 1};
  for (const TriangleMesh* m : {&rect, &slanted}) {
    const Material e = emitter();
    EXPECT_TRUE(ShapeLight(*m, 0, e).sampled_as_parallelogram());
  }
  auto r = light_chi2(rect, Vec3f(0.1f, 0.2f, 0.0f));
  EXPECT_TRUE(r.passed) << r.message;
  r = light_chi2(slanted, Vec3f(0.1f, 0.2f, 0.0f));
  EXPECT_TRUE(r.passed) << r.message;
}

TEST(LightChi2, ParallelogramQuadByArea) {
  Quad q;
  q.v[0] = Vec3f(-1, -0.5f, 2);
  q.v[1] = Vec3f(1, -0.3f, 2.2f);
  q.v[2] = Vec3f(1.3f, 0.9f, 2.4f);
  q.v[3] = Vec3f(-0.7f, 0.7f, 2.2f);
  const Material e = emitter();
  EXPECT_TRUE(ShapeLight(q, 0, e).sampled_as_parallelogram());
  const auto r = light_chi2(q, Vec3f(0.1f, 0.2f, 0.0f));
  EXPECT_TRUE(r.passed) << r.message;
}

// A rectangle sampled uniformly by solid angle (spherical rectangle
// sampling): near, far (a narrow cone, binned finely across its axis) and at
// a grazing angle.
TEST(LightChi2, RectangleBySolidAngle) {
  TriangleMesh rect;
  rect.positions = {{-0.6f, 1.0f, 0.4f}, {-0.6f, 1.0f, -0.5f}, {0.55f, 1.0f, -0.5f}, {0.55f, 1.0f, 0.4f}};
  rect.indices = {0, 1, 2, 0, 2, 3};
  const Shape shape = rect;  // the light keeps a pointer to its shape
  const Material m = emitter();
  const ShapeLight light(shape, 0, m, true);
  ASSERT_TRUE(light.sampled_by_solid_angle_as_rectangle());
  const Vec3f centre(-0.025f, 1.0f, -0.05f);
  struct Case {
    Vec3f p;
    bool narrow;
  };
  for (const Case& c : {Case{{0.3f, 0.4f, 0.1f}, false}, Case{{1.5f, -6.0f, 2.0f}, true}}) {
    DirectionChi2 t;
    if (c.narrow) t.bins = test::frame_across(centre - c.p);
    t.n_theta = c.narrow ? 128 : 32;
    t.n_phi = 2 * t.n_theta;
    t.sample = [&](float, Vec2f u, Vec3f& d) {
      LightSample s;
      if (!light.sample(c.p, u, s)) return false;
      // On the rectangle, along wi, with the density pdf() gives.
      if (std::fabs(s.p_light.y - 1.0f) > 1e-4f || length(normalize(s.p_light - c.p) - s.wi) > 1e-3f) return false;
      if (std::fabs(s.pdf - light.pdf(c.p, s.wi, s.p_light, s.n_light)) > 1e-4f * s.pdf) return false;
      d = s.wi;
      return true;
    };
    t.pdf = [&](Vec3f d) { return light_pdf(light, shape, c.p, d); };
    const auto r = t.run();
    EXPECT_TRUE(r.passed) << "from " << c.p.x << "," << c.p.y << "," << c.p.z << ": " << r.message;
  }
  // Seen at a grazing angle the rectangle is a sliver of directions, so the
  // points are tested on the rectangle itself instead (x, z), against the
  // solid-angle density converted to area: pdf cos_light / d^2.
  for (const Vec3f p : {Vec3f(2.5f, 0.8f, -0.3f), Vec3f(0.3f, 0.4f, 0.1f)}) {
    test::PlaneChi2 t;
    t.x0 = -0.6f;
    t.x1 = 0.55f;
    t.y0 = -0.5f;
    t.y1 = 0.4f;
    t.sample = [&](Vec2f u, Vec2f& q) {
      LightSample s;
      if (!light.sample(p, u, s)) return false;
      q = Vec2f(std::clamp(s.p_light.x, -0.6f, 0.5499f), std::clamp(s.p_light.z, -0.5f, 0.3999f));
      return true;
    };
    t.pdf = [&](Vec2f q) {
      const Vec3f x(q.x, 1.0f, q.y), n(0.0f, -1.0f, 0.0f);
      const Vec3f d = x - p;
      const float d2 = length_squared(d);
      const Vec3f wi = d / std::sqrt(d2);
      return light.pdf(p, wi, x, n) * std::fabs(dot(wi, n)) / d2;
    };
    const auto r = t.run();
    EXPECT_TRUE(r.passed) << "points, from " << p.x << "," << p.y << "," << p.z << ": " << r.message;
  }
}

// The solid angle of a rectangle against the closed form: seen from height h
// above a corner, an a x b rectangle subtends atan(a b / (h sqrt(a^2 + b^2 + h^2))).
// Lights placed by instances: a sphere under a similarity (by solid angle,
// its world centre and radius), an ellipsoid (non-uniform scale: by area in
// object space, the density divided by |det M| / |M^T n|), a mirrored,
// sheared quad (a parallelogram still) and a cylinder under a non-uniform scale.
TEST(LightChi2, TransformedShapes) {
  const Transform similar(Affine::translate(1, 0, -0.5) * Affine::rotate(1, 2, 3, 40) * Affine::scale(0.5, 0.5, 0.5));
  const Transform squash(Affine::translate(0.2, 0.1, 0) * Affine::rotate(0, 1, 1, 25) * Affine::scale(1.6, 0.4, 0.9));
  Affine shear;
  shear.m[0][1] = 0.7;
  const Transform mirror(Affine::scale(-1, 1.5, 1) * shear);
  Sphere sphere;
  sphere.radius = 1.0f;
  const Quad quad{{{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}}};
  const Cylinder cyl{{0, 0, -0.5f}, {0, 0, 0.5f}, 0.6f};
  struct Case {
    const char* name;
    Shape shape;
    const Transform* xf;
    Vec3f p;
  };
  // (Curved shapes sampled by area are binned by direction only from inside:
  // seen from outside their density is infinite at the silhouette; see
  // CylinderByArea. The area Jacobian is checked on its own below.)
  const Case cases[] = {{"similar sphere", sphere, &similar, {3, 1, 2}},
                        {"ellipsoid from inside", sphere, &squash, {0.3f, 0.1f, 0.05f}},
                        {"mirrored sheared quad", quad, &mirror, {0.4f, 0.3f, 1.2f}},
                        {"squashed cylinder from inside", cyl, &squash, {0.25f, 0.1f, 0.0f}}};
  for (const Case& c : cases) {
    const auto r = light_chi2(c.shape, c.p, Frame(), 32, c.xf);
    EXPECT_TRUE(r.passed) << c.name << ": " << r.message;
  }
}

// A mesh light under a non-uniform scale (and a mirror) picks each triangle in
// proportion to its world area, i.e. its emitted power: the area density is
// the same 1 / A_world at every sampled point (picking by object-space area
// would give each triangle its own density, |M^T n| / (|det M| A_object)), and
// the directions pass the chi-square test against that density.
TEST(LightChi2, MeshUnderANonUniformScaleByWorldArea) {
  TriangleMesh m;  // three triangles facing x, y and a slant: a scale changes their areas differently
  m.positions = {{0, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 0}, {1, 0, 1}, {2, 0, 0}, {0, 1, 1}, {1, 1, 0}, {1, 2, 1}};
  m.indices = {0, 1, 2, 3, 4, 5, 6, 7, 8};
  const Transform xf(Affine::translate(0.5, -0.2, 0.3) * Affine::rotate(1, 2, 0.5, 35) * Affine::scale(-4, 0.25, 1.5));
  double world_area = 0;
  for (int t = 0; t < 3; ++t) {
    const Vec3f a = xf.point(m.positions[m.indices[3 * t]]), b = xf.point(m.positions[m.indices[3 * t + 1]]),
                c = xf.point(m.positions[m.indices[3 * t + 2]]);
    world_area += 0.5 * length(cross(b - a, c - a));
  }
  const Material mat = emitter();
  const ShapeLight light(m, 0, mat, xf, 0);
  const Vec3f p(2, 3, -4);
  for (int i = 0; i < 64; ++i) {
    LightSample s;
    ASSERT_TRUE(light.sample(p, Vec2f((i + 0.5f) / 64, 0.37f), s));
    const float area_density = s.pdf * std::fabs(dot(s.n_light, s.wi)) / length_squared(s.p_light - p);
    EXPECT_NEAR(area_density * world_area, 1.0, 1e-3) << "sample " << i;
  }
  EXPECT_NEAR(light.power(), kPi * world_area * 2, 1e-3 * light.power());  // two-sided, L = 1
  const auto r = light_chi2(m, p, Frame(), 32, &xf);
  EXPECT_TRUE(r.passed) << r.message;
}

// The area density of a shape sampled in object space: the mean of 1 / p_A
// over its samples is its world area. A unit sphere scaled (a, a, c) is an
// oblate spheroid, area 2 pi a^2 (1 + (1 - e^2) atanh(e) / e), e^2 = 1 - c^2 / a^2;
// a cylinder of radius r, height h scaled (s, s, k) along its axis z has area
// 2 pi r s (h k) + 2 pi (r s)^2.
TEST(ShapeLight, TransformedAreaDensityIntegratesToTheWorldArea) {
  const Material m = emitter();
  const double a = 1.7, c = 0.6;
  const Transform spheroid(Affine::rotate(1, 1, 0, 30) * Affine::scale(a, a, c));
  const double e = std::sqrt(1 - c * c / (a * a));
  const double spheroid_area = 2 * kPi * a * a * (1 + (1 - e * e) * std::atanh(e) / e);
  const Transform stretch(Affine::translate(0.3, 0, 0) * Affine::scale(1.5, 1.5, 0.5));
  const double cylinder_area = 2 * kPi * 0.4 * 1.5 * (2.0 * 0.5) + 2 * kPi * (0.4 * 1.5) * (0.4 * 1.5);
  Sphere unit;
  unit.radius = 1.0f;
  const Shape sphere = unit;
  const Shape cylinder = Cylinder{{0, 0, -1}, {0, 0, 1}, 0.4f};
  struct Case {
    const Shape* shape;
    const Transform* xf;
    double area;
  };
  for (const Case& k : {Case{&sphere, &spheroid, spheroid_area}, Case{&cylinder, &stretch, cylinder_area}}) {
    const ShapeLight light(*k.shape, 0, m, *k.xf, 0);
    const Vec3f p(5, 4, 3);  // outside: sampled by area
    double sum = 0;
    int n = 0;
    for (int i = 0; i < 256; ++i) {
      for (int j = 0; j < 256; ++j) {
        LightSample s;
        if (!light.sample(p, Vec2f((i + 0.5f) / 256, (j + 0.5f) / 256), s)) continue;
        const Vec3f d = s.p_light - p;
        sum += length_squared(d) / (std::fabs(dot(s.n_light, s.wi)) * s.pdf);
        ++n;
      }
    }
    EXPECT_GT(n, 60000);
    EXPECT_NEAR(sum / n, k.area, 2e-3 * k.area);
  }
}

TEST(ShapeLight, TransformedEmitterPowerAndArea) {
  // A unit sphere scaled by 2: its world area is 16 pi, and its power with it.
  const Material m = emitter();
  const Transform twice(Affine::scale(2, 2, 2));
  Sphere sphere;
  sphere.radius = 1.0f;
  const Shape shape = sphere;
  const Shape big = Sphere{{0, 0, 0}, 2.0f, {0, 1, 0}};
  const ShapeLight plain(big, 0, m);
  const ShapeLight placed(shape, 0, m, twice, 3);
  EXPECT_EQ(placed.instance(), 3u);
  EXPECT_NEAR(placed.power(), plain.power(), 1e-4f * plain.power());
}

TEST(SphericalRectangle, SolidAngleMatchesTheClosedForm) {
  for (const Vec3f& s : {Vec3f(1.0f, 2.0f, 0.5f), Vec3f(0.3f, 0.2f, 4.0f), Vec3f(3.0f, 0.5f, 0.05f)}) {
    const float a = s.x, b = s.y, h = s.z;
    const double exact = std::atan(static_cast<double>(a) * b / (h * std::sqrt(double(a) * a + double(b) * b + double(h) * h)));
    SphericalRectangle r;
    // From below the corner, and from above (the frame turns towards p).
    ASSERT_TRUE(make_spherical_rectangle(Vec3f(0, 0, -h), Vec3f(0, 0, 0), Vec3f(a, 0, 0), Vec3f(0, b, 0), r));
    EXPECT_NEAR(r.solid_angle, exact, 1e-5 + 1e-4 * exact);
    ASSERT_TRUE(make_spherical_rectangle(Vec3f(0, 0, h), Vec3f(0, 0, 0), Vec3f(a, 0, 0), Vec3f(0, b, 0), r));
    EXPECT_NEAR(r.solid_angle, exact, 1e-5 + 1e-4 * exact);
  }
  SphericalRectangle r;
  EXPECT_FALSE(make_spherical_rectangle(Vec3f(5, 1, 0), Vec3f(0, 0, 0), Vec3f(1, 0, 0), Vec3f(0, 1, 0), r));  // in the plane
}

TEST(ShapeLight, OneSidedParallelogramLightsOnlyItsFront) {
  TriangleMesh rect;  // faces -y, like the Cornell box's light
  rect.positions = {{-0.6f, 1.0f, 0.4f}, {-0.6f, 1.0f, -0.5f}, {0.55f, 1.0f, -0.5f}, {0.55f, 1.0f, 0.4f}};
  rect.indices = {0, 1, 2, 0, 2, 3};
  const Shape shape = rect;
  Material m;
  m.emission = RGB(17.0f, 12.0f, 4.0f);
  for (bool solid_angle : {false, true}) {
    const ShapeLight light(shape, 0, m, solid_angle);
    ASSERT_TRUE(light.sampled_as_parallelogram());
    LightSample s;
    ASSERT_TRUE(light.sample(Vec3f(0.2f, 0.3f, 0.1f), Vec2f(0.3f, 0.6f), s));
    EXPECT_EQ(s.L, m.emission);
    EXPECT_GT(s.wi.y, 0.0f);
    EXPECT_FALSE(light.sample(Vec3f(0.2f, 1.5f, 0.1f), Vec2f(0.3f, 0.6f), s));  // behind
    EXPECT_FALSE(light.sample(Vec3f(3.0f, 1.0f, 0.1f), Vec2f(0.3f, 0.6f), s));  // in its plane
  }
}

TEST(ShapeLight, OnlyParallelogramsAreSampledAsOne) {
  const Material e = emitter();
  Quad trapezoid;
  trapezoid.v[0] = Vec3f(-1, -0.5f, 2);
  trapezoid.v[1] = Vec3f(1, -0.5f, 2);
  trapezoid.v[2] = Vec3f(0.4f, 0.7f, 2.2f);
  trapezoid.v[3] = Vec3f(-0.4f, 0.7f, 2.2f);
  EXPECT_FALSE(ShapeLight(trapezoid, 0, e).sampled_as_parallelogram());
  TriangleMesh folded;  // a parallelogram's outline folded along its diagonal: not planar
  folded.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0.5f}, {0, 1, 0}};
  folded.indices = {0, 1, 2, 0, 2, 3};
  EXPECT_FALSE(ShapeLight(folded, 0, e).sampled_as_parallelogram());
  TriangleMesh flipped;  // the halves face opposite ways
  flipped.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  flipped.indices = {0, 1, 2, 0, 3, 2};
  EXPECT_FALSE(ShapeLight(flipped, 0, e).sampled_as_parallelogram());
  TriangleMesh apart;  // two triangles that share no edge
  apart.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 0, 0}, {3, 0, 0}, {2, 1, 0}};
  apart.indices = {0, 1, 2, 3, 4, 5};
  EXPECT_FALSE(ShapeLight(apart, 0, e).sampled_as_parallelogram());
}

TEST(LightChi2, CylinderByArea) {
  // Area sampling of a curved surface has an infinite solid-angle density at
  // its silhouette, which quadrature over direction bins cannot integrate; so
  // the points are tested on the unrolled surface instead: x = phi / 2 pi, and
  // y = t / h on the side (y in [0, 1)), 1 + (r / R)^2 on the cap at p0 and
  // 2 + (r / R)^2 on the cap at p1, where uniform area is uniform in (x, y)
  // with the part's share of the area as the density.
  Cylinder c;
  c.p0 = Vec3f(-0.5f, 0.0f, 1.0f);
  c.p1 = Vec3f(0.5f, 0.3f, 1.6f);
  c.radius = 0.4f;
  const Shape shape = c;
  const Material m = emitter();
  const ShapeLight light(shape, 0, m);
  const Vec3f axis = c.p1 - c.p0;
  const float h = length(axis);
  const Frame frame = Frame::from_normal(axis / h);
  const float side = 2.0f * kPi * c.radius * h / light.area(), cap = kPi * c.radius * c.radius / light.area();
  const Vec3f p(0.2f, -1.0f, 0.0f);
  test::PlaneChi2 t;
  t.x1 = 1.0f;
  t.y1 = 3.0f;
  t.nx = 24;
  t.ny = 36;
  t.sample = [&](Vec2f u, Vec2f& out) {
    LightSample s;
    if (!light.sample(p, u, s)) return false;
    const Vec3f q = frame.to_local(s.p_light - c.p0);
    const float r = std::sqrt(q.x * q.x + q.y * q.y);
    const float phi = spherical_phi(Vec3f(q.x, q.y, 0.0f)) * kInv2Pi;
    // The density of the sample is pdf() at its point (p sees it directly or through the shape).
    if (std::fabs(s.pdf - light.pdf(p, s.wi, s.p_light, s.n_light)) > 1e-3f * s.pdf) return false;
    if (std::fabs(r - c.radius) < 1e-4f && q.z > -1e-4f && q.z < h + 1e-4f && std::fabs(dot(s.n_light, frame.n)) < 1e-3f) {
      out = Vec2f(phi, std::clamp(q.z / h, 0.0f, 0.99999f));
    } else if (std::fabs(q.z) < 1e-4f && r <= c.radius * 1.0001f) {
      out = Vec2f(phi, 1.0f + std::min(r * r / (c.radius * c.radius), 0.99999f));
    } else if (std::fabs(q.z - h) < 1e-4f && r <= c.radius * 1.0001f) {
      out = Vec2f(phi, 2.0f + std::min(r * r / (c.radius * c.radius), 0.99999f));
    } else {
      return false;  // not on the cylinder
    }
    return true;
  };
  t.pdf = [&](Vec2f q) { return q.y < 1.0f ? side : cap; };
  const auto r = t.run();
  EXPECT_TRUE(r.passed) << r.message;
}

TEST(LightChi2, DiscAndAnnulusByArea) {
  for (const float inner : {0.0f, 0.35f}) {
    const Disc d = make_disc({0.2f, 0.1f, 2.0f}, {0.3f, -0.2f, -1.0f}, 0.8f, inner);
    const auto r = light_chi2(d, Vec3f(0.1f, 0.2f, 0.0f));
    EXPECT_TRUE(r.passed) << "inner radius " << inner << ": " << r.message;
  }
}

TEST(LightChi2, PolygonByArea) {
  // A pentagon with triangles of its fan of different areas.
  const ConvexPolygon p = make_polygon({{-1, -0.5f, 2}, {1, -0.5f, 2}, {1.2f, 0.4f, 2.18f}, {0.2f, 1.0f, 2.3f}, {-0.9f, 0.6f, 2.22f}});
  const auto r = light_chi2(p, Vec3f(0.1f, 0.2f, 0.0f));
  EXPECT_TRUE(r.passed) << r.message;
}

TEST(LightChi2, ConeByArea) {
  // As the cylinder's: points on the unrolled surface, x = phi / 2 pi; on the
  // side y = the area fraction below the point's slant fraction s,
  // (r0 s + (r1 - r0) s^2 / 2) / ((r0 + r1) / 2), in [0, 1); on the caps
  // 1 + (r / r0)^2 and 2 + (r / r1)^2; uniform in (x, y) by part.
  for (const float top : {0.0f, 0.25f}) {
    const Cone c{{-0.5f, 0.0f, 1.0f}, {0.5f, 0.3f, 1.6f}, 0.45f, top};
    const Shape shape = c;
    const Material m = emitter();
    const ShapeLight light(shape, 0, m);
    const Vec3f axis = c.p1 - c.p0;
    const float h = length(axis), r0 = c.radius, r1 = c.top_radius;
    const Frame frame = Frame::from_normal(axis / h);
    const float side = kPi * (r0 + r1) * std::sqrt(h * h + (r0 - r1) * (r0 - r1)) / light.area();
    const float cap0 = kPi * r0 * r0 / light.area(), cap1 = kPi * r1 * r1 / light.area();
    const Vec3f p(0.2f, -1.0f, 0.0f);
    test::PlaneChi2 t;
    t.x1 = 1.0f;
    t.y1 = top > 0.0f ? 3.0f : 2.0f;
    t.nx = 24;
    t.ny = top > 0.0f ? 36 : 24;
    t.sample = [&](Vec2f u, Vec2f& out) {
      LightSample s;
      if (!light.sample(p, u, s)) return false;
      if (std::fabs(s.pdf - light.pdf(p, s.wi, s.p_light, s.n_light)) > 1e-3f * s.pdf) return false;
      const Vec3f q = frame.to_local(s.p_light - c.p0);
      const float r = std::sqrt(q.x * q.x + q.y * q.y);
      const float phi = spherical_phi(Vec3f(q.x, q.y, 0.0f)) * kInv2Pi;
      const float sf = q.z / h;
      if (std::fabs(q.z) < 1e-4f && std::fabs(dot(s.n_light, frame.n) + 1.0f) < 1e-4f) {
        out = Vec2f(phi, 1.0f + std::min(r * r / (r0 * r0), 0.99999f));
      } else if (std::fabs(q.z - h) < 1e-4f && std::fabs(dot(s.n_light, frame.n) - 1.0f) < 1e-4f) {
        out = Vec2f(phi, 2.0f + std::min(r * r / (r1 * r1), 0.99999f));
      } else if (std::fabs(r - (r0 + (r1 - r0) * sf)) < 1e-4f && sf > -1e-4f && sf < 1.0f + 1e-4f) {
        const float y = (r0 * sf + 0.5f * (r1 - r0) * sf * sf) / (0.5f * (r0 + r1));
        out = Vec2f(phi, std::clamp(y, 0.0f, 0.99999f));
      } else {
        return false;  // not on the cone
      }
      return true;
    };
    t.pdf = [&](Vec2f q) { return q.y < 1.0f ? side : (q.y < 2.0f ? cap0 : cap1); };
    const auto r = t.run();
    EXPECT_TRUE(r.passed) << "top radius " << top << ": " << r.message;
  }
}

// A synthetic environment: a smooth gradient, a bright spot and a black band.
// The rows at the poles are black: uniform sampling inside a texel gives a
// pole texel the (integrable) density 1/sin(theta), which quadrature over the
// test's bins cannot integrate accurately.
Texture synthetic_environment(int w, int h) {
  std::vector<RGB> pixels(static_cast<std::size_t>(w * h));
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      RGB c(0.2f + 0.8f * x / w, 0.5f, 0.3f + 0.5f * y / h);
      if (x >= w / 4 && x < w / 4 + 3 && y >= h / 3 && y < h / 3 + 2) c = RGB(40.0f, 30.0f, 10.0f);
      if (y == h - 3 || y == 0 || y == h - 1) c = RGB(0.0f);
      pixels[static_cast<std::size_t>(y * w + x)] = c;
    }
  }
  return Texture(w, h, std::move(pixels));
}

TEST(LightChi2, EnvironmentMap) {
  struct Case {
    Vec3f up;
    float rotation;
  };
  for (const Case& c : {Case{{0, 1, 0}, 0.0f}, Case{{0.3f, 0.2f, 1.0f}, 75.0f}}) {
    const EnvironmentMap env(synthetic_environment(48, 24), c.up, c.rotation, 2.0f);
    DirectionChi2 t;
    t.n_theta = 32;
    t.n_phi = 64;
    t.sample = [&](float, Vec2f u, Vec3f& d) {
      LightSample s;
      if (!env.sample(u, s)) return false;
      // The sample carries the density pdf() gives and the radiance radiance() gives.
      if (std::fabs(s.pdf - env.pdf(s.wi)) > 1e-3f * s.pdf) return false;
      if (!(s.L == env.radiance(s.wi))) return false;
      d = s.wi;
      return true;
    };
    t.pdf = [&](Vec3f d) { return env.pdf(d); };
    const auto r = t.run();
    EXPECT_TRUE(r.passed) << "up " << c.up.x << "," << c.up.y << "," << c.up.z << ": " << r.message;
  }
}

// The map's density integrates to 1 over the sphere (uniform directions:
// E[pdf * 4 pi] = 1), and every sample's texel has non-zero probability.
TEST(Environment, DensityIntegratesToOne) {
  const EnvironmentMap env(synthetic_environment(48, 24), Vec3f(0.3f, 0.2f, 1.0f), 75.0f, 2.0f);
  Rng rng(5);
  constexpr int kN = 1000000;  // the spot makes the estimate's sigma about 0.0035
  double sum = 0.0;
  for (int k = 0; k < kN; ++k)
    sum += static_cast<double>(env.pdf(sample_uniform_sphere({rng.next_float(), rng.next_float()}))) * 4.0 * kPi;
  EXPECT_NEAR(sum / kN, 1.0, 0.02);
}

TEST(Environment, OrientationAndRotation) {
  // up = +Y: -Z at the image centre, +X at u = 3/4, the zenith on the top row.
  const EnvironmentMap env(synthetic_environment(48, 24), Vec3f(0, 1, 0), 0.0f, 1.0f);
  Vec2f uv = env.direction_to_uv(Vec3f(0, 0, -1));
  EXPECT_NEAR(uv.x, 0.5f, 1e-5f);
  EXPECT_NEAR(uv.y, 0.5f, 1e-5f);
  uv = env.direction_to_uv(Vec3f(1, 0, 0));
  EXPECT_NEAR(uv.x, 0.75f, 1e-5f);
  EXPECT_NEAR(env.direction_to_uv(Vec3f(0, 1, 0)).y, 0.0f, 1e-5f);
  // Turning the map by +90 degrees (counter-clockwise seen from above) brings
  // what was at -Z to -X... and what was at +X to -Z.
  const EnvironmentMap turned(synthetic_environment(48, 24), Vec3f(0, 1, 0), 90.0f, 1.0f);
  EXPECT_NEAR(turned.direction_to_uv(Vec3f(-1, 0, 0)).x, 0.5f, 1e-5f);
  EXPECT_NEAR(turned.direction_to_uv(Vec3f(0, 0, -1)).x, 0.75f, 1e-5f);
  // uv_to_direction inverts direction_to_uv.
  for (Vec2f p : {Vec2f(0.1f, 0.3f), Vec2f(0.8f, 0.9f), Vec2f(0.5f, 0.05f)}) {
    const Vec2f back = turned.direction_to_uv(turned.uv_to_direction(p));
    EXPECT_NEAR(back.x, p.x, 1e-4f);
    EXPECT_NEAR(back.y, p.y, 1e-4f);
  }
}

}  // namespace
}  // namespace pt
