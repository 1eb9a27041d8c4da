// Integrator registry: name -> factory. Adding an integrator is one row here.
#include <array>

#include "render/integrators/builtin.h"
#include "render/film/filter.h"
#include "render/integrators/integrator.h"
#include "render/samplers/sampler.h"

namespace pt {

namespace {

using enum AovType;
constexpr AovSet kWhittedAovs =
    kRenderLoopAovs | aov_set(Emission, Ambient, DiffuseDirect, SpecularDirect, SpecularIndirect);
constexpr AovSet kPathAovs =
    kRenderLoopAovs | aov_set(Emission, DiffuseDirect, DiffuseIndirect, SpecularDirect, SpecularIndirect);

// A plain array: adding a row needs no count. The columns: name, factory,
// configurable sampling, AOVs, light model (IntegratorInfo).
constexpr IntegratorInfo kIntegrators[] = {
    {"whitted", make_whitted_integrator, false, kWhittedAovs, LightModel::Classic},
    {"path", make_path_integrator, true, kPathAovs, LightModel::Physical},
    {"binary", make_binary_integrator, false, kRenderLoopAovs, LightModel::None},
    {"normal", make_normal_integrator, false, kRenderLoopAovs, LightModel::None},
    {"depth", make_depth_integrator, false, kRenderLoopAovs, LightModel::None},
    {"signature", make_signature_integrator, false, kRenderLoopAovs, LightModel::None},
    {"bvh-cost", make_bvh_cost_integrator, false, 0, LightModel::None},  // its film holds colours only
};

}  // namespace

const char* IntegratorInfo::sampler_name(SamplerType sampler) const {
  return configurable_sampling ? sampler_type_name(sampler) : "pixel-grid";
}

const char* IntegratorInfo::filter_name(PixelFilterType filter) const {
  return configurable_sampling ? pixel_filter_name(filter) : "box";
}

const char* IntegratorInfo::light_sampler_name(LightSamplerType light_sampler) const {
  switch (lights) {
    case LightModel::Physical: return kLightSamplerNames[static_cast<int>(light_sampler)];
    case LightModel::Classic: return "all";
    case LightModel::None: break;
  }
  return "none";
}

bool IntegratorInfo::equal_passes(SamplerType sampler) const {
  return !configurable_sampling || sampler == SamplerType::Jittered;
}

bool IntegratorInfo::check_aovs(const std::vector<AovRequest>& requested, std::string& error) const {
  for (const AovRequest& r : requested) {
    if (produces(r.type)) continue;
    error = std::string("the ") + name + " integrator cannot produce AOV '" + aov_info(r.type).name + "'; it produces:";
    for (const AovInfo& info : aov_catalogue())
      if (produces(info.type)) error += std::string(" ") + info.name;
    return false;
  }
  return true;
}

std::vector<std::string> integrator_names() {
  std::vector<std::string> names;
  for (const IntegratorInfo& e : kIntegrators) names.emplace_back(e.name);
  return names;
}

const IntegratorInfo* find_integrator(const std::string& name, std::string& error) {
  for (const IntegratorInfo& e : kIntegrators)
    if (name == e.name) return &e;
  error = "unknown integrator '" + name + "'; valid names are:";
  for (const IntegratorInfo& e : kIntegrators) error += std::string(" ") + e.name;
  return nullptr;
}

std::unique_ptr<Integrator> make_integrator(const std::string& name, const IntegratorSettings& settings,
                                            std::string& error) {
  const IntegratorInfo* info = find_integrator(name, error);
  return info != nullptr ? info->make(settings) : nullptr;
}

}  // namespace pt
