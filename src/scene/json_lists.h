// Reading long lists (inline mesh data) from JSON, with every bad element
// reported at its own location.
#pragma once

#include <cstdint>
#include <string_view>
#include <vector>

#include "scene/json_reader.h"

namespace pt {

// [[x, y, z], ...]
bool read_vec3_list(ReadContext& ctx, const JsonValue& v, std::string_view label, std::vector<Vec3f>& out);
// [[u, v], ...]
bool read_vec2_list(ReadContext& ctx, const JsonValue& v, std::string_view label, std::vector<Vec2f>& out);
// Triangle indices: [[i, j, k], ...], or, if `allow_flat`, also [i, j, k, i, j, k, ...].
// Each index is checked to be an integer in [0, vertex_count).
bool read_index_list(ReadContext& ctx, const JsonValue& v, std::string_view label, std::size_t vertex_count,
                     bool allow_flat, std::vector<uint32_t>& out);

}  // namespace pt
