#include "accel/embree/embree_device.h"

#include <cstdlib>
#include <string>

namespace pt::embree {

namespace {

const char* error_name(RTCError code) {
  switch (code) {
    case RTC_ERROR_NONE: return "no error";
    case RTC_ERROR_UNKNOWN: return "unknown error";
    case RTC_ERROR_INVALID_ARGUMENT: return "invalid argument";
    case RTC_ERROR_INVALID_OPERATION: return "invalid operation";
    case RTC_ERROR_OUT_OF_MEMORY: return "out of memory";
    case RTC_ERROR_UNSUPPORTED_CPU: return "unsupported CPU";
    case RTC_ERROR_CANCELLED: return "cancelled";
  }
  return "error";
}

// Embree 3 does not report the ISA it dispatches to; it picks the best one it
// was compiled for that the CPU supports. The native packet widths it reports
// tell which wide ISAs are available; the CPU tells which one it uses.
std::string isa_name(RTCDevice device) {
  __builtin_cpu_init();
  const bool ray16 = rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED) != 0;
  const bool ray8 = rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_NATIVE_RAY8_SUPPORTED) != 0;
  if (ray16 && __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq") &&
      __builtin_cpu_supports("avx512cd") && __builtin_cpu_supports("avx512bw") &&
      __builtin_cpu_supports("avx512vl")) {
    return "AVX512";
  }
  if (ray8 && __builtin_cpu_supports("avx2")) return "AVX2";
  if (ray8 && __builtin_cpu_supports("avx")) return "AVX";
  if (__builtin_cpu_supports("sse4.2")) return "SSE4.2";
  return "SSE2";
}

}  // namespace

Device::Device() : state_(std::make_unique<State>()) {
  const char* config = std::getenv("PT_EMBREE_CONFIG");
  device_ = rtcNewDevice(config != nullptr && *config != '\0' ? config : nullptr);
  if (device_ == nullptr) {
    const RTCError code = rtcGetDeviceError(nullptr);
    state_->errors.push_back(std::string("cannot create an Embree device: ") + error_name(code));
    return;
  }
  rtcSetDeviceErrorFunction(device_, &Device::on_error, state_.get());
  rtcSetDeviceMemoryMonitorFunction(device_, &Device::on_memory, state_.get());
}

Device::~Device() {
  if (device_ != nullptr) rtcReleaseDevice(device_);
}

void Device::on_error(void* user, RTCError code, const char* message) {
  auto* state = static_cast<State*>(user);
  std::string text = error_name(code);
  if (message != nullptr && *message != '\0') text += std::string(": ") + message;
  const std::lock_guard<std::mutex> lock(state->mutex);
  state->errors.push_back(std::move(text));
}

bool Device::on_memory(void* user, ssize_t bytes, bool /*post*/) {
  auto* state = static_cast<State*>(user);
  const long long now = state->bytes.fetch_add(bytes, std::memory_order_relaxed) + bytes;
  long long peak = state->peak.load(std::memory_order_relaxed);
  while (now > peak && !state->peak.compare_exchange_weak(peak, now, std::memory_order_relaxed)) {
  }
  return true;  // never refuse an allocation
}

std::vector<std::string> Device::errors() const {
  const std::lock_guard<std::mutex> lock(state_->mutex);
  return state_->errors;
}

bool Device::has_errors() const {
  const std::lock_guard<std::mutex> lock(state_->mutex);
  return !state_->errors.empty();
}

std::size_t Device::bytes_in_use() const {
  const long long b = state_->bytes.load(std::memory_order_relaxed);
  return b > 0 ? static_cast<std::size_t>(b) : 0;
}

std::size_t Device::peak_bytes() const {
  const long long b = state_->peak.load(std::memory_order_relaxed);
  return b > 0 ? static_cast<std::size_t>(b) : 0;
}

std::string Device::description() const {
  if (device_ == nullptr) return "embree (no device)";
  const auto major = rtcGetDeviceProperty(device_, RTC_DEVICE_PROPERTY_VERSION_MAJOR);
  const auto minor = rtcGetDeviceProperty(device_, RTC_DEVICE_PROPERTY_VERSION_MINOR);
  const auto patch = rtcGetDeviceProperty(device_, RTC_DEVICE_PROPERTY_VERSION_PATCH);
  return "embree " + std::to_string(major) + "." + std::to_string(minor) + "." + std::to_string(patch) + " (" +
         isa_name(device_) + ")";
}

}  // namespace pt::embree
