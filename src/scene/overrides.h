// `--set key=value` (docs/cli.md): overrides a value of a scene file before it
// is imported and validated, for every format (they are all JSON).
//
// The key is a JSON path into the file: object keys separated by '.', array
// elements as [index]: "render.spp", "camera.fov", "materials.white.diffuse",
// "shapes[3].radius". The value is JSON ("256", "[0.8,0.8,0.8]", "true"); text
// that is not JSON is taken as a string ("box" -> "box").
//
// The override is spliced into the file's text in place of the old value (or
// added as a new member of the object when the last key is not there), keeping
// every other value on its line, so the importer and validator report
// problems as for any file, at file:line:col; each diagnostic located in an overridden
// value is followed by a note naming the --set that put the value there.
#pragma once

#include <string>
#include <vector>

#include "core/diagnostics.h"

namespace pt {

// Where an override put its text: 1-based line, columns [col_begin, col_end).
struct OverrideLine {
  int line = 0;
  int col_begin = 0, col_end = 0;
  std::string argument;  // "key=value" as given
};

// Applies `overrides` ("key=value" each, in order) to `text`, the contents of
// `path`. Returns false after reporting to `diag` (naming the key, and the keys
// or indices that exist there) when one cannot be applied. When `text` is not
// valid JSON it is left alone (the loader reports the syntax error).
bool apply_scene_overrides(const std::string& path, std::string& text, const std::vector<std::string>& overrides,
                           Diagnostics& diag, std::vector<OverrideLine>& lines);

// Adds every diagnostic of `from` to `to`, each one located in an
// overridden value followed by a note saying which --set put the value there.
void forward_with_override_notes(const Diagnostics& from, const std::vector<OverrideLine>& lines,
                                 Diagnostics& to);

}  // namespace pt
