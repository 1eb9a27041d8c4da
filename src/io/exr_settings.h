// How EXR files are written (--exr-compression, --multipart; docs/output.md).
// Pure data: the writers (io/image_io.h) and the image module read it.
#pragma once

#include <string>

namespace pt {

struct ExrSettings {
  // OpenImageIO's name of the OpenEXR compression (exr_compression_names());
  // "dwaa" and "dwab" may carry a level, "dwaa:45" (the default, 45).
  std::string compression = "zip";
  bool multipart = false;  // one part per layer instead of one part for all
  // OpenEXR's compression threads (--threads); 0: every hardware thread.
  int threads = 0;
};

}  // namespace pt
