#include "scene/loader.h"

#include <filesystem>
#include <fstream>
#include <memory>
#include <system_error>

#include "core/file_access.h"
#include "scene/asset_reader.h"
#include "scene/detect.h"
#include "scene/import_asset.h"
#include "scene/importers.h"
#include "scene/json.h"
#include "scene/overrides.h"
#include "scene/validate.h"

namespace fs = std::filesystem;

namespace pt {
namespace {

// Scene files larger than this are refused before they are read.
constexpr std::uintmax_t kMaxSceneFileBytes = 256ull << 20;

// A location naming only the file (for problems with the file as a whole).
SourceLocation file_only(const std::string& path) {
  SourceLocation loc;
  loc.file = std::make_shared<const SourceFile>(SourceFile{path, {}});
  return loc;
}

std::string too_large_message(std::uintmax_t bytes) {
  return "the file is " + std::to_string(bytes >> 20) + " MiB; scene files larger than " +
         std::to_string(kMaxSceneFileBytes >> 20) + " MiB are refused (put large meshes in PLY files)";
}

}  // namespace

namespace {

// Something other than a directory is there: a file, or a FIFO, a device, a
// symbolic link loop, which the reader then names as what it is (why_unreadable)
// rather than as a missing file.
bool names_a_file(const fs::path& p) {
  std::error_code ec;
  const fs::file_status link = fs::symlink_status(p, ec);
  if (ec || !fs::exists(link)) return false;
  return !fs::is_directory(p, ec);
}

}  // namespace

std::optional<std::string> resolve_scene_path(const std::string& scene_path, const std::string& written) {
  if (written.empty()) return std::nullopt;
  const fs::path w(written);
  if (w.is_absolute()) return names_a_file(w) ? std::optional<std::string>(written) : std::nullopt;
  const fs::path in_scene_dir = fs::path(scene_path).parent_path() / w;
  if (names_a_file(in_scene_dir)) return in_scene_dir.string();
  if (names_a_file(w)) return written;
  return std::nullopt;
}

std::optional<SceneDescription> load_scene(const std::string& path, const LoadOptions& options,
                                           Diagnostics& diag) {
  std::error_code ec;
  if (!names_a_file(path) && !fs::is_directory(path, ec)) {
    diag.error(file_only(path), "scene file not found");
    return std::nullopt;
  }
  if (fs::is_directory(path, ec)) {
    diag.error(file_only(path), "is a directory, not a scene file");
    return std::nullopt;
  }
  if (const std::string why = why_unreadable(path); !why.empty()) {
    diag.error(file_only(path), "cannot read the scene file: " + why);
    return std::nullopt;
  }
  // A model file as the scene: a native scene that imports it (import_asset.h).
  if (asset_format_of(path)) {
    std::optional<SceneDescription> scene =
        load_scene_from_string(path + " (the scene made for it)", model_scene_text(path), options, diag);
    if (scene) light_model_scene(*scene, diag);
    return scene;
  }
  const std::uintmax_t size = fs::file_size(path, ec);
  if (ec) {
    diag.error(file_only(path), "cannot read the scene file: " + ec.message());
    return std::nullopt;
  }
  if (size > kMaxSceneFileBytes) {
    diag.error(file_only(path), too_large_message(size));
    return std::nullopt;
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    diag.error(file_only(path), "cannot open the scene file");
    return std::nullopt;
  }
  std::string text(static_cast<std::size_t>(size), '\0');
  in.read(text.data(), static_cast<std::streamsize>(size));
  text.resize(static_cast<std::size_t>(in.gcount()));
  return load_scene_from_string(path, std::move(text), options, diag);
}

namespace {

std::optional<SceneDescription> load_text(const std::string& path, std::string text, const LoadOptions& options,
                                          Diagnostics& diag) {
  const int errors_before = diag.error_count();
  auto file = std::make_shared<const SourceFile>(SourceFile{path, std::move(text)});
  const std::optional<JsonDocument> doc = parse_json(file, diag);
  if (!doc) return std::nullopt;
  const std::optional<SceneFormat> format = detect_scene_format(*doc, diag);
  if (!format) return std::nullopt;

  SceneDescription scene;
  scene.source_path = path;
  scene.format = *format;
  const bool legacy = *format != SceneFormat::Native;
  ReadContext read{*doc, diag,
                   legacy && !options.strict ? UnknownKeyPolicy::Warning : UnknownKeyPolicy::Error};
  ImportContext ctx{read, options, scene, {}, {}};
  switch (*format) {
    case SceneFormat::Native: import_native(ctx); break;
    case SceneFormat::PathOfLight: import_path_of_light(ctx); break;
    case SceneFormat::Cgr: import_cgr(ctx); break;
  }
  // The model importer's code and constants leave the resident set: nothing
  // after loading runs them, and they would sit under the acceleration
  // structure's build (asset_reader.h).
  release_importer_pages();
  validate_scene(scene, options, diag);
  if (diag.error_count() > errors_before) return std::nullopt;
  return scene;
}

}  // namespace

std::optional<SceneDescription> load_scene_from_string(const std::string& path, std::string text,
                                                       const LoadOptions& options, Diagnostics& diag) {
  if (text.size() > kMaxSceneFileBytes) {
    diag.error(file_only(path), too_large_message(text.size()));
    return std::nullopt;
  }
  if (options.overrides.empty()) return load_text(path, std::move(text), options, diag);
  std::vector<OverrideLine> lines;
  if (!apply_scene_overrides(path, text, options.overrides, diag, lines)) return std::nullopt;
  Diagnostics inner;  // forwarded with a note on each diagnostic about an overridden value
  std::optional<SceneDescription> scene = load_text(path, std::move(text), options, inner);
  const int errors_before = diag.error_count();
  forward_with_override_notes(inner, lines, diag);
  if (!scene || diag.error_count() > errors_before) return std::nullopt;
  return scene;
}

}  // namespace pt
