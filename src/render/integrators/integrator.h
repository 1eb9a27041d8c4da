// Integrators turn a RenderScene into pixels on a Film. Chosen by name through
// a registry (name -> factory); an unknown name gets an error listing the valid ones.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "render/film/film.h"
#include "render/render_scene.h"

namespace pt {

class WorkerPool;

struct IntegratorSettings {
  int max_depth = 5;    // recursion limit
  int spp = 1;          // samples per pixel
  uint64_t seed = 0;
  int tile_size = 16;   // pixels per tile side; the image does not depend on it
};

class Integrator {
 public:
  virtual ~Integrator() = default;
  // Renders every pixel of `film`. Parallel over tiles inside `pool`; the
  // result does not depend on the thread count or the tile order.
  virtual void render(const RenderScene& scene, Film& film, WorkerPool& pool) const = 0;
};

// Returns nullptr and sets `error` (listing the valid names) for an unknown name.
std::unique_ptr<Integrator> make_integrator(const std::string& name, const IntegratorSettings& settings,
                                            std::string& error);
std::vector<std::string> integrator_names();

}  // namespace pt
