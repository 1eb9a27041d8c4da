// Textures of the native format (docs/scene-format.md, "Textures"): the
// top-level "textures" object of named textures, and texture references, the
// values of material keys that take a texture ("texture", "alpha", ...).
#pragma once

#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "scene/import_context.h"

namespace pt {

struct NativeTextures {
  struct Named {
    TextureDesc desc;
    bool ok = true;
    std::optional<int> index;       // in ctx.scene.textures, once a used material refers to it
    std::optional<int> data_index;  // its copy read as data (below), if one is used
    bool encoding_given = false;    // "encoding" written: data references read it as written
  };
  std::vector<Named> named;
  std::map<std::string, std::size_t, std::less<>> by_name;
};

// Reads the top-level "textures": {"name": {texture}, ...}. Problems are reported.
NativeTextures read_native_textures(ImportContext& ctx, const JsonValue& v);

// A texture reference: the name of a texture in "textures", else the path of
// an image file (a texture with every default; one entry per file), or an
// inline texture object. Adds the texture to ctx.scene.textures the first time
// and returns its index; std::nullopt after reporting a problem at `v`.
// `data`: the parameter is a number rather than a colour (roughness, a normal
// or bump map): an image without "encoding" is read as "linear" (no sRGB decoding).
std::optional<int> resolve_texture_ref(ImportContext& ctx, NativeTextures& textures, const JsonValue& v,
                                       std::string_view key, bool data = false);

// Warns about each named texture no used material refers to (it is never read).
void warn_unused_textures(ImportContext& ctx, const NativeTextures& textures);

}  // namespace pt
