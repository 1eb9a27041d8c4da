#include "app/render_settings.h"

#include "io/image_metadata.h"
#include "io/run_record.h"
#include "render/film/filter.h"
#include "scene/scene_description.h"

namespace pt {

bool resolve_render_settings(const SceneDescription& desc, const SettingsOverrides& o, RenderSettings& out,
                             Diagnostics& diag) {
  const std::string name = o.integrator.empty() ? desc.render.integrator.value : o.integrator;
  std::string error;
  out.integrator = find_integrator(name, error);
  if (out.integrator == nullptr) {
    diag.error(o.integrator.empty() ? desc.render.integrator.where : SourceLocation{}, error);
    return false;
  }
  if (out.integrator->lights == LightModel::Physical) {
    for (const LightDesc& light : desc.lights) {
      const auto* ambient = std::get_if<AmbientLightDesc>(&light);
      if (ambient == nullptr) continue;
      diag.warning(ambient->where, std::string("an ambient light is not physical: the ") + name +
                                       " integrator leaves it out (its equivalent is a uniform environment: give "
                                       "render.background the ambient colour; docs/path-tracing.md)");
      break;  // once
    }
  }
  IntegratorSettings& s = out.integration;
  s = IntegratorSettings{};
  s.max_depth = o.max_depth >= 0 ? o.max_depth : desc.render.max_depth.value;
  s.seed = o.seed;
  s.filter = parse_pixel_filter(o.filter).value_or(desc.render.filter);
  s.sampler = o.sampler;
  s.clamp = o.clamp >= 0.0f ? o.clamp : desc.render.clamp.value;
  s.roulette_depth = o.roulette_depth;
  s.roulette_threshold = o.roulette_threshold;
  s.film_transparent = o.film_transparent || desc.render.film_transparent.value;
  s.light_guiding = desc.render.light_guiding.value;
  s.path_guiding = desc.render.path_guiding.value;
  out.light_sampler = desc.render.light_sampler.value;
  out.shadow_terminator_offset = desc.render.shadow_terminator_geometry_offset.value;
  BuildOptions size;
  size.width_override = o.width;
  size.height_override = o.height;
  resolve_resolution(desc.film, size, out.width, out.height);
  return true;
}

BuildOptions RenderSettings::build_options(AccelKind accel) const {
  BuildOptions options;
  options.accel = accel;
  // Both sides given: the resolved size exactly (resolve_resolution).
  options.width_override = width;
  options.height_override = height;
  options.light_sampler = light_sampler;
  options.shadow_terminator_offset = shadow_terminator_offset;
  return options;
}

RenderStamp RenderSettings::stamp() const {
  RenderStamp stamp;
  stamp.seed = integration.seed;
  stamp.integrator = integrator_name();
  stamp.sampler = sampler_name();
  stamp.filter = filter_name();
  stamp.light_sampler = light_sampler_name();
  stamp.light_guiding = light_guiding();
  stamp.path_guiding = path_guiding();
  stamp.shadow_terminator_offset = shadow_terminator_offset;
  stamp.max_depth = integration.max_depth;
  stamp.clamp = integration.clamp;
  stamp.film_transparent = integration.film_transparent;
  stamp.software_version = PT_VERSION;
  return stamp;
}

void RenderSettings::describe(RunRecord& record) const {
  record.integrator = integrator_name();
  record.sampler = sampler_name();
  record.width = width;
  record.height = height;
  record.max_depth = integration.max_depth;
  record.seed = integration.seed;
  record.filter = filter_name();
  record.light_sampler = light_sampler_name();
  record.light_guiding = light_guiding();
  record.path_guiding = path_guiding();
  record.shadow_terminator_offset = shadow_terminator_offset;
  record.clamp = integration.clamp;
}

nlohmann::ordered_json RenderSettings::identity() const {
  // The configured sampler and filter (not the registry's names): the keys
  // every checkpoint written so far holds.
  nlohmann::ordered_json id = {{"integrator", integrator_name()},
                                {"width", width},
                                {"height", height},
                                {"max_depth", integration.max_depth},
                                {"seed", integration.seed},
                                {"sampler", sampler_type_name(integration.sampler)},
                                {"filter", pixel_filter_name(integration.filter)},
                                {"clamp", integration.clamp}};
  // Only when set, so that the checkpoints of opaque renders keep their keys.
  if (integration.film_transparent) id["film_transparent"] = true;
  if (light_sampler != LightSamplerType::Bvh)
    id["light_sampler"] = kLightSamplerNames[static_cast<int>(light_sampler)];
  if (integration.light_guiding != kDefaultLightGuiding) id["light_guiding"] = integration.light_guiding;
  if (integration.path_guiding != kDefaultPathGuiding) id["path_guiding"] = integration.path_guiding;
  if (shadow_terminator_offset != kDefaultShadowTerminatorOffset)
    id["shadow_terminator_geometry_offset"] = shadow_terminator_offset;
  return id;
}

}  // namespace pt
