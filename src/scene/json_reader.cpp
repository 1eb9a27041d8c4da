#include "scene/json_reader.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "scene/suggest.h"

namespace pt {
namespace {

// What a value is, for "got ..." in messages.
std::string describe(const JsonValue& v) {
  switch (v.type()) {
    case JsonType::Null: return "null";
    case JsonType::Bool: return v.as_bool() ? "true" : "false";
    case JsonType::Number: return "the number " + format_number(v.as_number());
    case JsonType::String: {
      const std::string& s = v.as_string();
      return "the string \"" + (s.size() > 40 ? s.substr(0, 37) + "..." : s) + "\"";
    }
    case JsonType::Array: {
      const std::size_t n = v.as_array().size();
      return "an array of " + std::to_string(n) + (n == 1 ? " value" : " values");
    }
    case JsonType::Object: return "an object";
  }
  return "a value";
}

bool type_error(ReadContext& ctx, const JsonValue& v, std::string_view label, std::string_view expected) {
  ctx.diag.error(ctx.at(v), "expected " + std::string(expected) + " for '" + std::string(label) + "', got " +
                                describe(v));
  return false;
}

// A finite number (non-finite ones were reported by the parser).
bool number_of(ReadContext& ctx, const JsonValue& v, std::string_view label, double& out) {
  if (!v.is_number()) return type_error(ctx, v, label, "a number");
  out = v.as_number();
  return std::isfinite(out);
}

// An array of exactly n numbers.
bool numbers_of(ReadContext& ctx, const JsonValue& v, std::string_view label, std::size_t n, float* out) {
  const std::string expected = "an array of " + std::to_string(n) + " numbers";
  if (!v.is_array()) return type_error(ctx, v, label, expected);
  const JsonValue::Array& a = v.as_array();
  if (a.size() != n) return type_error(ctx, v, label, expected);
  bool ok = true;
  for (std::size_t i = 0; i < n; ++i) {
    double d = 0;
    if (!a[i].is_number()) {
      ctx.diag.error(ctx.at(a[i]), "expected a number in '" + std::string(label) + "', got " + describe(a[i]));
      ok = false;
    } else if (number_of(ctx, a[i], label, d)) {
      if (std::fabs(d) > std::numeric_limits<float>::max()) {
        ctx.diag.error(ctx.at(a[i]), "number " + format_number(d) + " in '" + std::string(label) +
                                         "' is too large for single precision");
        ok = false;
      }
      out[i] = static_cast<float>(d);
    } else {
      ok = false;
    }
  }
  return ok;
}

}  // namespace

bool read_value(ReadContext& ctx, const JsonValue& v, std::string_view label, Sourced<float>& out) {
  double d = 0;
  if (!number_of(ctx, v, label, d)) return false;
  if (std::fabs(d) > std::numeric_limits<float>::max()) {
    ctx.diag.error(ctx.at(v), quoted(label) + " is too large for single precision: " + format_number(d));
    return false;
  }
  out = Sourced<float>(static_cast<float>(d), ctx.at(v));
  return true;
}

bool read_value(ReadContext& ctx, const JsonValue& v, std::string_view label, Sourced<int>& out) {
  double d = 0;
  if (!v.is_number()) return type_error(ctx, v, label, "an integer");
  if (!number_of(ctx, v, label, d)) return false;
  if (d != std::floor(d)) return type_error(ctx, v, label, "an integer");
  if (d < std::numeric_limits<int>::min() || d > std::numeric_limits<int>::max()) {
    ctx.diag.error(ctx.at(v), quoted(label) + " is out of range: " + format_number(d));
    return false;
  }
  out = Sourced<int>(static_cast<int>(d), ctx.at(v));
  return true;
}

bool read_value(ReadContext& ctx, const JsonValue& v, std::string_view label, Sourced<bool>& out) {
  if (!v.is_bool()) return type_error(ctx, v, label, "true or false");
  out = Sourced<bool>(v.as_bool(), ctx.at(v));
  return true;
}

bool read_value(ReadContext& ctx, const JsonValue& v, std::string_view label, Sourced<std::string>& out) {
  if (!v.is_string()) return type_error(ctx, v, label, "a string");
  out = Sourced<std::string>(v.as_string(), ctx.at(v));
  return true;
}

bool read_value(ReadContext& ctx, const JsonValue& v, std::string_view label, Sourced<Vec3f>& out) {
  float f[3] = {0, 0, 0};
  if (!numbers_of(ctx, v, label, 3, f)) return false;
  out = Sourced<Vec3f>(Vec3f(f[0], f[1], f[2]), ctx.at(v));
  return true;
}

bool read_value(ReadContext& ctx, const JsonValue& v, std::string_view label, Sourced<Vec2f>& out) {
  float f[2] = {0, 0};
  if (!numbers_of(ctx, v, label, 2, f)) return false;
  out = Sourced<Vec2f>(Vec2f(f[0], f[1]), ctx.at(v));
  return true;
}

bool read_value(ReadContext& ctx, const JsonValue& v, std::string_view label, Sourced<RGB>& out) {
  float f[3] = {0, 0, 0};
  if (!v.is_array()) return type_error(ctx, v, label, "an RGB colour [r, g, b]");
  if (!numbers_of(ctx, v, label, 3, f)) return false;
  out = Sourced<RGB>(RGB(f[0], f[1], f[2]), ctx.at(v));
  return true;
}

bool expect_object(ReadContext& ctx, const JsonValue& v, std::string_view label) {
  return v.is_object() || type_error(ctx, v, label, "an object");
}

bool expect_array(ReadContext& ctx, const JsonValue& v, std::string_view label) {
  return v.is_array() || type_error(ctx, v, label, "an array");
}

// ---------------------------------------------------------------- ObjectReader

ObjectReader::ObjectReader(ReadContext& ctx, const JsonValue& object, std::string what)
    : ctx_(ctx), object_(object), what_(std::move(what)) {}

const JsonValue* ObjectReader::get(std::string_view key) {
  if (std::find(known_.begin(), known_.end(), key) == known_.end()) known_.emplace_back(key);
  return object_.find(key);
}

const JsonValue* ObjectReader::require(std::string_view key) {
  const JsonValue* v = get(key);
  if (!v) {
    ctx_.diag.error(where(), "missing key '" + std::string(key) + "' in " + what_);
    ok_ = false;
  }
  return v;
}

void ObjectReader::allow(std::initializer_list<std::string_view> keys) {
  for (std::string_view k : keys) get(k);
}

void ObjectReader::finish() {
  if (!object_.is_object()) return;
  for (const JsonMember& m : object_.as_object()) {
    if (m.duplicate || std::find(known_.begin(), known_.end(), m.key) != known_.end()) continue;
    const SourceLocation at = ctx_.doc.location(m.key_offset);
    std::string message = "unknown key '" + m.key + "' in " + what_;
    if (ctx_.unknown_keys == UnknownKeyPolicy::Error) {
      message += did_you_mean(m.key, known_, "; valid keys are " + quoted_list(known_, "and"));
      ctx_.diag.error(at, std::move(message));
      ok_ = false;
    } else {
      message += " (ignored)" + did_you_mean(m.key, known_);
      ctx_.diag.warning(at, std::move(message));
    }
  }
}

int read_choice(ObjectReader& r, std::string_view key, const std::vector<std::string>& names,
                SourceLocation* where) {
  Sourced<std::string> value;
  const JsonValue* v = r.get(key);
  if (!v) return -1;
  if (!read_value(r.context(), *v, key, value)) {
    r.fail();
    return -2;
  }
  if (where) *where = value.where;
  for (std::size_t i = 0; i < names.size(); ++i)
    if (names[i] == value.value) return static_cast<int>(i);
  std::string message = "unknown " + std::string(key) + " '" + value.value + "' in " + r.what();
  message += did_you_mean(value.value, names, "; expected " + quoted_list(names));
  r.context().diag.error(value.where, std::move(message));
  r.fail();
  return -2;
}

}  // namespace pt
