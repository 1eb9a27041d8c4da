#include "app/versions.h"

#include <string>

#include <OpenColorIO/OpenColorIO.h>
#include <OpenEXR/OpenEXRConfig.h>
#include <embree3/rtcore.h>
#include <oneapi/tbb/version.h>

#include "imagelib/image_library.h"

namespace pt {
namespace {

std::string embree_version(RTCDevice device) {
  if (device == nullptr) return RTC_VERSION_STRING " (headers; no device)";
  const long v = static_cast<long>(rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_VERSION));
  return std::to_string(v / 10000) + "." + std::to_string(v / 100 % 100) + "." + std::to_string(v % 100);
}

std::string embree_tasking(RTCDevice device) {
  if (device == nullptr) return "unknown";
  switch (rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_TASKING_SYSTEM)) {
    case 0: return "internal";
    case 1: return "TBB";
    case 2: return "PPL";
    default: return "unknown";
  }
}

// Embree 3 does not report its ISA; the widest native ray packet it supports
// tells it (4: SSE, 8: AVX/AVX2, 16: AVX-512).
std::string embree_packets(RTCDevice device) {
  if (device == nullptr) return "unknown";
  std::string s;
  const std::pair<RTCDeviceProperty, const char*> sizes[] = {{RTC_DEVICE_PROPERTY_NATIVE_RAY4_SUPPORTED, "4"},
                                                             {RTC_DEVICE_PROPERTY_NATIVE_RAY8_SUPPORTED, "8"},
                                                             {RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED, "16"}};
  for (const auto& [property, name] : sizes)
    if (rtcGetDeviceProperty(device, property) != 0) {
      if (!s.empty()) s += ' ';
      s += name;
    }
  return s.empty() ? "none" : s;
}

std::string compiler() {
#if defined(__clang__)
  return "clang " __clang_version__;
#elif defined(__GNUC__)
  return "gcc " __VERSION__;
#else
  return "unknown";
#endif
}

}  // namespace

SoftwareVersions software_versions() {
  SoftwareVersions v;
  v.pathtracer = PT_VERSION;
  RTCDevice device = rtcNewDevice("verbose=0");
  v.embree = embree_version(device);
  v.embree_tasking = embree_tasking(device);
  v.embree_native_packets = embree_packets(device);
  if (device != nullptr) rtcReleaseDevice(device);
  // OpenImageIO's own answer once the image module is loaded (a render that
  // wrote an image); before that, and in --version, which loads nothing, the
  // version the module was built with.
  const ImageLibrary* images = loaded_image_library();
  v.openimageio = images != nullptr ? images->version() : PT_OIIO_BUILD_VERSION;
  v.image_module = image_module_path(&v.image_module_origin);
  v.openexr = OPENEXR_VERSION_STRING;
  v.opencolorio = OCIO_NAMESPACE::GetVersion();
  v.tbb = TBB_runtime_version();
  v.compiler = compiler();
  v.compiler_flags = PT_CXX_FLAGS;
  v.build_type = PT_BUILD_TYPE;
  return v;
}

}  // namespace pt
