#include "scene/json_lists.h"

#include <cmath>
#include <string>

#include "scene/suggest.h"

namespace pt {
namespace {

// Stops after this many bad elements in one list (a broken generator can
// otherwise produce millions of identical messages).
constexpr int kMaxListErrors = 10;

// Fast path for well-formed elements: an array of N finite numbers.
template <std::size_t N>
bool plain_numbers(const JsonValue& v, float (&out)[N]) {
  if (!v.is_array() || v.as_array().size() != N) return false;
  for (std::size_t i = 0; i < N; ++i) {
    const JsonValue& x = v.as_array()[i];
    if (!x.is_number() || !std::isfinite(x.as_number()) || std::fabs(x.as_number()) > 3.4e38) return false;
    out[i] = static_cast<float>(x.as_number());
  }
  return true;
}

// Reads [[...], ...]; elements that are not plain go through read_value for
// their messages (labelled "positions[7]").
template <class T, std::size_t N>
bool read_list(ReadContext& ctx, const JsonValue& v, std::string_view label, std::vector<T>& out) {
  if (!expect_array(ctx, v, label)) return false;
  const JsonValue::Array& a = v.as_array();
  out.clear();
  out.reserve(a.size());
  int errors = 0;
  for (std::size_t i = 0; i < a.size() && errors < kMaxListErrors; ++i) {
    float f[N];
    if (plain_numbers(a[i], f)) {
      if constexpr (N == 3) out.push_back(Vec3f(f[0], f[1], f[2]));
      else out.push_back(Vec2f(f[0], f[1]));
      continue;
    }
    Sourced<T> item;
    const std::string item_label = std::string(label) + "[" + std::to_string(i) + "]";
    if (read_value(ctx, a[i], item_label, item)) out.push_back(item.value);
    else ++errors;
  }
  return errors == 0;
}

bool read_index(ReadContext& ctx, const JsonValue& v, std::string_view label, std::size_t vertex_count,
                uint32_t& out) {
  if (v.is_integer() && v.as_number() >= 0 && v.as_number() < static_cast<double>(vertex_count)) {
    out = static_cast<uint32_t>(v.as_number());  // the common case, without building a location
    return true;
  }
  Sourced<int> i;
  if (!read_value(ctx, v, label, i)) return false;
  if (i.value < 0 || static_cast<std::size_t>(i.value) >= vertex_count) {
    ctx.diag.error(i.where, "index " + std::to_string(i.value) + " in '" + std::string(label) +
                                "' is out of range: the mesh has " + std::to_string(vertex_count) + " vertices");
    return false;
  }
  out = static_cast<uint32_t>(i.value);
  return true;
}

}  // namespace

bool read_vec3_list(ReadContext& ctx, const JsonValue& v, std::string_view label, std::vector<Vec3f>& out) {
  return read_list<Vec3f, 3>(ctx, v, label, out);
}

bool read_vec2_list(ReadContext& ctx, const JsonValue& v, std::string_view label, std::vector<Vec2f>& out) {
  return read_list<Vec2f, 2>(ctx, v, label, out);
}

bool read_index_list(ReadContext& ctx, const JsonValue& v, std::string_view label, std::size_t vertex_count,
                     bool allow_flat, std::vector<uint32_t>& out) {
  if (!expect_array(ctx, v, label)) return false;
  const JsonValue::Array& a = v.as_array();
  out.clear();
  const bool flat = allow_flat && !a.empty() && a.front().is_number();
  int errors = 0;
  if (flat) {
    if (a.size() % 3 != 0) {
      ctx.diag.error(ctx.at(v), quoted(label) + " holds " + std::to_string(a.size()) +
                                    " indices, which is not a multiple of 3");
      return false;
    }
    out.resize(a.size());
    for (std::size_t i = 0; i < a.size() && errors < kMaxListErrors; ++i)
      if (!read_index(ctx, a[i], label, vertex_count, out[i])) ++errors;
    return errors == 0;
  }
  out.reserve(a.size() * 3);
  for (std::size_t t = 0; t < a.size() && errors < kMaxListErrors; ++t) {
    const std::string item_label = std::string(label) + "[" + std::to_string(t) + "]";
    const JsonValue& tri = a[t];
    if (!tri.is_array() || tri.as_array().size() != 3) {
      ctx.diag.error(ctx.at(tri), "expected a triangle [i, j, k] in '" + std::string(label) + "'");
      ++errors;
      continue;
    }
    for (const JsonValue& index : tri.as_array()) {
      uint32_t i = 0;
      if (read_index(ctx, index, item_label, vertex_count, i)) out.push_back(i);
      else ++errors;
    }
  }
  return errors == 0;
}

}  // namespace pt
