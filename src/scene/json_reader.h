// Typed, checked access to the JSON tree for the importers.
//
// Every read converts one value, reports a wrong type or range at the value's
// location ("expected a number for 'radius', got a string"), and stores the
// value together with its location in a Sourced<T>. ObjectReader also
// remembers which keys were asked for, so that finish() can report every key
// of the object that no one read: an error with "did you mean" in the native
// format, a warning in the course formats (an error in strict mode).
//
// Non-finite numbers are reported once, by the parser; readers reject them
// silently.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "core/diagnostics.h"
#include "scene/json.h"
#include "scene/scene_description.h"

namespace pt {

enum class UnknownKeyPolicy { Error, Warning };

struct ReadContext {
  const JsonDocument& doc;
  Diagnostics& diag;
  UnknownKeyPolicy unknown_keys = UnknownKeyPolicy::Error;

  SourceLocation at(const JsonValue& v) const { return doc.location(v); }
};

// Single-value conversions. `label` names the value in messages (usually its
// key). On a problem: report at the value, leave `out` alone, return false.
bool read_value(ReadContext& ctx, const JsonValue& v, std::string_view label, Sourced<float>& out);
bool read_value(ReadContext& ctx, const JsonValue& v, std::string_view label, Sourced<int>& out);
bool read_value(ReadContext& ctx, const JsonValue& v, std::string_view label, Sourced<bool>& out);
bool read_value(ReadContext& ctx, const JsonValue& v, std::string_view label, Sourced<std::string>& out);
bool read_value(ReadContext& ctx, const JsonValue& v, std::string_view label, Sourced<Vec3f>& out);
bool read_value(ReadContext& ctx, const JsonValue& v, std::string_view label, Sourced<Vec2f>& out);
bool read_value(ReadContext& ctx, const JsonValue& v, std::string_view label, Sourced<RGB>& out);

// Reports "expected an object for 'label', got ..." unless `v` is an object.
bool expect_object(ReadContext& ctx, const JsonValue& v, std::string_view label);
bool expect_array(ReadContext& ctx, const JsonValue& v, std::string_view label);

class ObjectReader {
 public:
  // `object` must be an object (see expect_object). `what` names it in
  // messages: "sphere", "camera", "material 'glass'".
  ObjectReader(ReadContext& ctx, const JsonValue& object, std::string what);

  // The value of `key`, or nullptr if absent. Either way `key` becomes known.
  const JsonValue* get(std::string_view key);
  // Like get(), but a missing key is an error ("missing key 'radius' in sphere").
  const JsonValue* require(std::string_view key);
  // Marks keys as known without reading them (accepted and ignored).
  void allow(std::initializer_list<std::string_view> keys);

  // Optional key: if present, converts it into `out`; if absent, `out` keeps
  // its default. Returns false only if the key is present and bad.
  template <class T>
  bool read(std::string_view key, Sourced<T>& out) {
    const JsonValue* v = get(key);
    return !v || note(read_value(ctx_, *v, key, out));
  }
  // Required key: absent is an error too.
  template <class T>
  bool read_required(std::string_view key, Sourced<T>& out) {
    const JsonValue* v = require(key);
    return v && note(read_value(ctx_, *v, key, out));
  }

  // Reports every key present but never asked for. Call once, after all reads.
  void finish();

  // False once any read through this reader failed (type error, missing key).
  bool ok() const { return ok_; }
  // Marks the object as failed (for problems the caller found itself).
  void fail() { ok_ = false; }
  const std::string& what() const { return what_; }
  void set_what(std::string what) { what_ = std::move(what); }
  SourceLocation where() const { return ctx_.at(object_); }
  ReadContext& context() { return ctx_; }

 private:
  bool note(bool ok) {
    ok_ = ok_ && ok;
    return ok;
  }

  ReadContext& ctx_;
  const JsonValue& object_;
  std::string what_;
  std::vector<std::string> known_;
  bool ok_ = true;
};

// A string key whose value must be one of `names` (error with "did you mean"
// otherwise). Returns the index of the match, -1 if the key is absent, -2 if bad.
int read_choice(ObjectReader& r, std::string_view key, const std::vector<std::string>& names,
                SourceLocation* where = nullptr);

}  // namespace pt
