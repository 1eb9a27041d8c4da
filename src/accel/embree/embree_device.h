// An Embree device with its error and memory callbacks wired to state owned
// by this object (no globals): errors are recorded, never printed, and the
// bytes Embree holds are counted for AccelStats.
#pragma once

#include <embree3/rtcore.h>

#include <atomic>
#include <cstddef>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace pt::embree {

class Device {
 public:
  // Check valid() afterwards; on failure errors() says why. The device's
  // configuration is Embree's default, or $PT_EMBREE_CONFIG when set (Embree's
  // own keys, e.g. "tri_accel=bvh8.triangle4i", for experiments:
  // tools/bench/accel/embree_layouts.py, docs/geometry.md).
  Device();
  ~Device();
  Device(const Device&) = delete;
  Device& operator=(const Device&) = delete;

  bool valid() const { return device_ != nullptr; }
  RTCDevice get() const { return device_; }

  // Errors reported by Embree so far ("invalid argument: ..."), oldest first.
  std::vector<std::string> errors() const;
  bool has_errors() const;
  // Bytes currently allocated by Embree on this device, and the most it held
  // at any time (the build's peak: its primitive references beside the
  // structure), by its memory monitor: bytes it reserved, not pages touched.
  std::size_t bytes_in_use() const;
  std::size_t peak_bytes() const;
  // "embree 3.13.5 (AVX2)".
  std::string description() const;

 private:
  // Lives on the heap so the callbacks' user pointer stays valid.
  struct State {
    mutable std::mutex mutex;
    std::vector<std::string> errors;
    std::atomic<long long> bytes{0};
    std::atomic<long long> peak{0};
  };
  static void on_error(void* user, RTCError code, const char* message);
  static bool on_memory(void* user, ssize_t bytes, bool post);

  std::unique_ptr<State> state_;
  RTCDevice device_ = nullptr;
};

}  // namespace pt::embree
