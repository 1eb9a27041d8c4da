#include "render/materials/material.h"

#include <algorithm>

namespace pt {

Material make_material(const MaterialDesc& d, const Texture* texture) {
  Material m;
  m.kd = d.kd;
  m.ks = d.ks;
  m.diffuse = d.diffuse;
  m.specular = d.specular;
  m.exponent = d.exponent;
  m.reflectivity = std::clamp(d.reflectivity.value, 0.0f, 1.0f);
  m.ior = d.ior;
  m.emission = d.emission;
  m.two_sided = d.two_sided;
  m.light_samples = d.light_samples;
  m.type = d.type;
  // The classic integrator reads only the course fields: give the physical
  // types their closest classic meaning (docs/path-tracing.md).
  switch (m.type) {
    case MaterialType::Lambert:
      m.ks = 0.0f;
      m.reflectivity = 0.0f;
      break;
    case MaterialType::Mirror:
      m.kd = 0.0f;
      m.ks = 0.0f;
      m.reflectivity = 1.0f;
      break;
    case MaterialType::Glass:
      break;
    case MaterialType::Phong:
      if (d.refractive) m.type = MaterialType::Glass;  // the course's dielectric
      break;
  }
  m.ka = d.ka ? d.ka->value : m.kd;  // after the classic meanings: a mirror has none
  m.texture = texture;
  return m;
}

}  // namespace pt
