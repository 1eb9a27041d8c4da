// The three importers: each reads the document in ctx into ctx.scene,
// reporting every problem it finds (it keeps going after errors, skipping only
// the object that is wrong). Validation of values (ranges, degenerate shapes)
// is done afterwards, once, by validate_scene().
#pragma once

#include "scene/import_context.h"

namespace pt {

void import_native(ImportContext& ctx);        // import_native.cpp
void import_path_of_light(ImportContext& ctx); // import_path_of_light.cpp
void import_cgr(ImportContext& ctx);           // import_cgr.cpp

}  // namespace pt
