// libFuzzer entry point of the scene harness (fuzz_targets.h).
#include "fuzz_targets.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  return pt::fuzz::scene_one_input(data, size);
}
