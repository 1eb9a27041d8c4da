// Dispatch over the Shape variant (not on any per-ray path: backends call the
// shape's own routines directly).
#include <utility>
#include <variant>

#include "geometry/shapes.h"

namespace pt {

Bounds3f bounds(const Shape& s) {
  return std::visit([](const auto& shape) { return bounds(shape); }, s);
}

uint32_t primitive_count(const Shape& s) {
  return std::visit([](const auto& shape) { return primitive_count(shape); }, s);
}

SurfaceGeometry surface(const Shape& s, uint32_t prim, const Ray& ray, const PrimHit& hit) {
  return std::visit([&](const auto& shape) { return surface_of_primitive(shape, prim, ray, hit); }, s);
}

UvDerivatives uv_derivatives(const Shape& s, uint32_t prim, const SurfaceGeometry& sg) {
  return std::visit([&](const auto& shape) { return uv_derivatives_of_primitive(shape, prim, sg); }, s);
}

void check(const Shape& s, ShapeChecker& c) {
  std::visit([&](const auto& shape) { check(shape, c); }, s);
}

namespace {

template <std::size_t... I>
ShapeAreaSampler area_sampler(const Shape& s, std::index_sequence<I...>) {
  ShapeAreaSampler out;
  (void)((s.index() == I ? (out.emplace<I>(make_area_sampler(*std::get_if<I>(&s))), true) : false) || ...);
  return out;
}

}  // namespace

ShapeAreaSampler make_area_sampler(const Shape& s) {
  return area_sampler(s, std::make_index_sequence<std::variant_size_v<Shape>>{});
}

}  // namespace pt
