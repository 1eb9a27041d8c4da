// pt-furnace: the white furnace of the microfacet BSDFs, measured on the BSDFs
// themselves (render/materials/bsdf.h): the directional albedo (fraction of
// the energy arriving from wo that is scattered, the refraction scaling of
// radiance undone) by stratified Monte Carlo over the BSDF's own sampling,
// against alpha and the angle of incidence, and its cosine-weighted average
// over the hemisphere. Prints a markdown table (docs/path-tracing.md).
//
//   pt-furnace [--strata N]     N x N samples per entry (default 256)
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "render/materials/bsdf.h"

namespace {

using namespace pt;

int g_strata = 256;

double directional_albedo(const Material& m, float mu) {
  SurfaceGeometry geo;
  geo.ng = geo.ns = Vec3f(0, 0, 1);
  const Vec3f wo(std::sqrt(std::max(0.0f, 1.0f - mu * mu)), 0.0f, mu);
  const Bsdf bsdf(m, geo, wo);
  double sum = 0.0;
  const int n = g_strata;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const Vec2f u((static_cast<float>(i) + 0.5f) / n, (static_cast<float>(j) + 0.5f) / n);
      // The lobe choice: a third, decorrelated stratification.
      const float ul = std::fmod((static_cast<float>(i * n + j) + 0.5f) * 0.6180339887f, 1.0f);
      BsdfSample s;
      if (bsdf.sample(wo, ul, u, s)) sum += s.weight.g * s.eta2;
    }
  }
  return sum / (static_cast<double>(n) * n);
}

// 2 * integral of albedo(mu) mu dmu, midpoint rule over 16 values of mu.
double hemispherical_average(const Material& m) {
  double sum = 0.0;
  const int k = 16;
  for (int i = 0; i < k; ++i) {
    const float mu = (static_cast<float>(i) + 0.5f) / k;
    sum += directional_albedo(m, mu) * mu;
  }
  return 2.0 * sum / k;
}

Material with_alpha(MaterialType type, float alpha) {
  Material m;
  m.type = type;
  m.remap_roughness = false;
  m.uroughness.value = m.vroughness.value = alpha;
  m.ior = 1.5f;
  if (type == MaterialType::Conductor) {
    m.schlick = true;
    m.reflectance.value = RGB(1.0f);  // F = 1: only the microfacets' shadowing loses energy
  }
  return m;
}

void table(const char* title, MaterialType type, const std::vector<float>& mus) {
  std::printf("\n%s\n\n| alpha |", title);
  for (float mu : mus) std::printf(" mu %.2f |", mu);
  std::printf(" hemispherical average |\n|---|");
  for (std::size_t i = 0; i <= mus.size(); ++i) std::printf("---|");
  std::printf("\n");
  for (float alpha : {0.05f, 0.1f, 0.2f, 0.3f, 0.5f, 0.7f, 1.0f}) {
    const Material m = with_alpha(type, alpha);
    std::printf("| %.2f |", alpha);
    for (float mu : mus) std::printf(" %.3f |", directional_albedo(m, mu));
    std::printf(" %.3f |\n", hemispherical_average(m));
  }
}

}  // namespace

int main(int argc, char** argv) {
  for (int i = 1; i + 1 < argc; ++i)
    if (std::strcmp(argv[i], "--strata") == 0) g_strata = std::max(8, std::atoi(argv[i + 1]));
  const std::vector<float> mus = {1.0f, 0.7f, 0.4f, 0.2f, 0.1f};
  table("Conductor, F = 1 (reflectance [1, 1, 1]): directional albedo", MaterialType::Conductor, mus);
  table("Dielectric, index 1.5, from outside: reflected + transmitted energy", MaterialType::Dielectric, mus);
  std::printf("\n(the average runs over mu in (0, 1]; from inside, mu below the critical angle's cosine "
              "reflects totally: see the inside table)\n");
  {
    std::printf("\nDielectric, index 1.5, from inside (mu = cos of the angle to the inward normal)\n\n| alpha |");
    for (float mu : mus) std::printf(" mu %.2f |", mu);
    std::printf("\n|---|");
    for (std::size_t i = 0; i < mus.size(); ++i) std::printf("---|");
    std::printf("\n");
    for (float alpha : {0.05f, 0.1f, 0.2f, 0.3f, 0.5f, 0.7f, 1.0f}) {
      const Material m = with_alpha(MaterialType::Dielectric, alpha);
      std::printf("| %.2f |", alpha);
      for (float mu : mus) std::printf(" %.3f |", directional_albedo(m, -mu));
      std::printf("\n");
    }
  }
  return 0;
}
