// libFuzzer entry point of the film_state harness (fuzz_targets.h).
#include "fuzz_targets.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  return pt::fuzz::film_state_one_input(data, size);
}
