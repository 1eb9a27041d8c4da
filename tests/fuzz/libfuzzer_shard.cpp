// libFuzzer entry point of the shard-file harness (fuzz_targets.h).
#include "fuzz_targets.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  return pt::fuzz::shard_one_input(data, size);
}
