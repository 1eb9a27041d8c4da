// Integrator registry: name -> factory. Adding an integrator is one row here.
#include <array>

#include "render/integrators/builtin.h"
#include "render/integrators/integrator.h"

namespace pt {

namespace {

struct Entry {
  const char* name;
  std::unique_ptr<Integrator> (*make)(const IntegratorSettings&);
};

// A plain array: adding a row needs no count.
constexpr Entry kIntegrators[] = {
    {"whitted", make_whitted_integrator},
    {"path", make_path_integrator},
    {"binary", make_binary_integrator},
    {"normal", make_normal_integrator},
    {"depth", make_depth_integrator},
    {"signature", make_signature_integrator},
    {"bvh-cost", make_bvh_cost_integrator},
};

}  // namespace

std::vector<std::string> integrator_names() {
  std::vector<std::string> names;
  for (const Entry& e : kIntegrators) names.emplace_back(e.name);
  return names;
}

std::unique_ptr<Integrator> make_integrator(const std::string& name, const IntegratorSettings& settings,
                                            std::string& error) {
  for (const Entry& e : kIntegrators)
    if (name == e.name) return e.make(settings);
  error = "unknown integrator '" + name + "'; valid names are:";
  for (const Entry& e : kIntegrators) error += std::string(" ") + e.name;
  return nullptr;
}

}  // namespace pt
