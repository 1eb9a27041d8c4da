#include "app/outputs.h"

#include <cstdlib>
#include <set>

#include "app/options.h"
#include "app/output_checks.h"
#include "core/image.h"
#include "io/image_io.h"
#include "scene/scene_description.h"

namespace pt {

std::string join(const std::vector<std::string>& items, const char* sep) {
  std::string s;
  for (const std::string& item : items) s += (s.empty() ? "" : sep) + item;
  return s;
}

bool check_outputs(const std::vector<std::string>& outputs, std::string& error) {
  std::set<std::string> seen;
  for (const std::string& path : outputs) {
    if (!is_supported_image_path(path)) {
      error = "cannot write '" + path + "': unsupported image extension (supported: " +
              join(supported_image_extensions(), ", ") + ")";
      return false;
    }
    if (!seen.insert(path).second) {
      error = "output '" + path + "' is given more than once";
      return false;
    }
  }
  return true;
}

DisplaySettings display_settings(const Options& o, const FilmDesc& film) {
  DisplaySettings d;
  d.transform = film.display;
  d.exposure = o.exposure.value_or(film.exposure.value);
  d.view = o.view;
  d.display = o.display;
  d.look = o.look;
  d.ocio_config = o.ocio_config;
  if (d.ocio_config.empty()) {
    if (const char* env = std::getenv("OCIO"); env != nullptr) d.ocio_config = env;
  }
  return d;
}

bool write_outputs(const std::vector<std::string>& outputs, const LayeredImage& image, const DisplaySettings& display,
                   const ExrSettings& exr, const ImageMetadata& metadata, OutputStamps& stamps, std::string& error) {
  bool all = true;
  for (const std::string& path : outputs) {
    std::string why;
    const bool ok = write_guarded(
        path, stamps,
        [&](const std::string& p, std::string& e) { return write_layered_image(p, image, display, e, metadata, exr); },
        why);
    if (!ok && all) error = why;
    all = all && ok;
  }
  return all;
}

}  // namespace pt
