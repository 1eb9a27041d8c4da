// The integrators the registry knows, and the pieces of them that tests check
// directly. Each lives in its own file; registry.cpp maps names to these factories.
#pragma once

#include <cstdint>
#include <memory>

#include "core/color.h"
#include "core/math.h"
#include "render/integrators/integrator.h"

namespace pt {

struct RenderScene;

std::unique_ptr<Integrator> make_whitted_integrator(const IntegratorSettings& settings);
std::unique_ptr<Integrator> make_binary_integrator(const IntegratorSettings& settings);
std::unique_ptr<Integrator> make_normal_integrator(const IntegratorSettings& settings);
std::unique_ptr<Integrator> make_depth_integrator(const IntegratorSettings& settings);
std::unique_ptr<Integrator> make_signature_integrator(const IntegratorSettings& settings);
std::unique_ptr<Integrator> make_path_integrator(const IntegratorSettings& settings);
std::unique_ptr<Integrator> make_bvh_cost_integrator(const IntegratorSettings& settings);

// Radiance arriving along `ray` under the classic recursive model (see
// docs/rendering.md); `max_depth` bounds the number of mirror/refraction bounces.
RGB whitted_radiance(const RenderScene& scene, const Ray& ray, int max_depth);

// Fresnel reflectance of an unpolarised wave at a smooth dielectric interface,
// going from index eta_i into eta_t with cos_i = cos(angle of incidence) in [0, 1].
// Returns 1 for total internal reflection.
float fresnel_dielectric(float cos_i, float eta_i, float eta_t);

// The debug colour of object `id` in the "signature" view: a hash of the id,
// stable across runs and platforms, every channel in [0.15, 1].
RGB signature_colour(uint32_t id);

// The "bvh-cost" view's colour (linear RGB) for a cost `fraction` of the
// image's maximum, 0 to 1 (clamped): the viridis ramp, dark blue to yellow.
RGB cost_colour(float fraction);

// The distance that the "depth" view maps to black: the farthest corner of the
// scene bounds as seen from `eye` (1 if the scene is empty).
float depth_view_range(const Bounds3f& scene_bounds, Vec3f eye);

}  // namespace pt
