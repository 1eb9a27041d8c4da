#include "fuzz_targets.h"

namespace pt::fuzz {

std::vector<Harness> harnesses() {
  return {{"scene", &scene_one_input}, {"ply", &ply_one_input}, {"obj", &obj_one_input},
          {"film_state", &film_state_one_input}, {"checkpoint", &checkpoint_one_input},
          {"shard", &shard_one_input}};
}

}  // namespace pt::fuzz
