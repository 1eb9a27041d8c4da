#include "scene/detect.h"

#include <string>

namespace pt {

std::optional<SceneFormat> detect_scene_format(const JsonDocument& doc, Diagnostics& diag) {
  const JsonValue& root = doc.root();
  if (!root.is_object()) {
    diag.error(doc.location(root), std::string("a scene file must hold a JSON object, got ") +
                                       json_type_name(root.type()));
    return std::nullopt;
  }
  if (const JsonValue* format = root.find("format")) {
    if (format->is_string() && format->as_string() == kNativeFormatName) return SceneFormat::Native;
    diag.error(doc.location(*format), std::string("unknown scene format; the native format is marked \"format\": \"") +
                                          kNativeFormatName + "\"");
    return std::nullopt;
  }

  const JsonValue* scene = root.find("scene");
  const JsonValue* camera = root.find("camera");
  const bool has_camera = camera && camera->is_object();
  if (scene && scene->is_object()) {
    if (root.find("rendermode") || (has_camera && (camera->find("lookAt") || camera->find("upVector"))))
      return SceneFormat::Cgr;
    if (has_camera && (camera->find("lookat") || camera->find("up"))) return SceneFormat::PathOfLight;
    diag.error(doc.location(root),
               "cannot tell which course format this is: it has a top-level \"scene\" object, but neither "
               "\"rendermode\" nor a camera with \"lookAt\"/\"upVector\" (CGR) nor a camera with "
               "\"lookat\"/\"up\" (Path of Light)");
    return std::nullopt;
  }
  diag.error(doc.location(root),
             std::string("unrecognised scene file; expected one of: a native scene (top-level \"format\": \"") +
                 kNativeFormatName + "\", \"version\": " + std::to_string(kNativeFormatVersion) +
                 "), a CGR course file (top-level \"scene\" object with \"rendermode\" or camera "
                 "\"lookAt\"/\"upVector\") or a Path of Light course file (top-level \"scene\" object with "
                 "camera \"lookat\"/\"up\")");
  return std::nullopt;
}

}  // namespace pt
