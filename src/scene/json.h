// JSON with source locations.
//
// nlohmann-json does not record where values were written, so the scene files
// are parsed with its SAX interface into this small value tree, which keeps the
// byte offset of every value and every object key, and keeps object members in
// file order. JsonDocument turns offsets into file:line:col.
//
// parse_json() reports, with locations: syntax errors (the first one ends the
// parse), duplicate keys (the later one is an error, the first gets a note),
// numbers that overflow to infinity, NaN/Infinity spelled out, and nesting
// deeper than JsonLimits::max_depth (which ends the parse, so no tree is ever
// deep enough for recursion to be a danger), and more values than
// JsonLimits::max_values (which ends the parse, bounding the tree's memory).
#pragma once

#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "core/diagnostics.h"

namespace pt {

enum class JsonType { Null, Bool, Number, String, Array, Object };

// "null", "a boolean", "a number", "a string", "an array", "an object".
const char* json_type_name(JsonType type);

struct JsonMember;

class JsonValue {
 public:
  using Array = std::vector<JsonValue>;
  using Object = std::vector<JsonMember>;

  JsonValue() = default;  // null at offset 0
  ~JsonValue();
  JsonValue(const JsonValue&);
  JsonValue(JsonValue&&) noexcept;
  JsonValue& operator=(const JsonValue&);
  JsonValue& operator=(JsonValue&&) noexcept;

  static JsonValue null(std::size_t offset);
  static JsonValue boolean(bool b, std::size_t offset);
  // `integer`: written without fraction or exponent.
  static JsonValue number(double d, bool integer, std::size_t offset);
  static JsonValue string(std::string s, std::size_t offset);
  static JsonValue array(std::size_t offset);
  static JsonValue object(std::size_t offset);

  JsonType type() const { return static_cast<JsonType>(data_.index()); }
  // Byte offset of the value's first character in the source text.
  std::size_t offset() const { return offset_; }

  bool is_null() const { return type() == JsonType::Null; }
  bool is_bool() const { return type() == JsonType::Bool; }
  bool is_number() const { return type() == JsonType::Number; }
  bool is_string() const { return type() == JsonType::String; }
  bool is_array() const { return type() == JsonType::Array; }
  bool is_object() const { return type() == JsonType::Object; }

  // Accessors; calling one for the wrong type is a programming error (asserts).
  bool as_bool() const;
  double as_number() const;
  bool is_integer() const;  // a number written without fraction or exponent
  const std::string& as_string() const;
  const Array& as_array() const;
  Array& as_array();
  const Object& as_object() const;
  Object& as_object();

  // For objects: the member named `key` (its first definition), else nullptr.
  const JsonValue* find(std::string_view key) const;

 private:
  struct Number {
    double value = 0;
    bool integer = false;
  };
  // The index order matches JsonType.
  std::variant<std::monostate, bool, Number, std::string, Array, Object> data_;
  std::size_t offset_ = 0;
};

struct JsonMember {
  std::string key;
  std::size_t key_offset = 0;  // offset of the key's opening quote
  JsonValue value;
  // A later definition of a key that appeared before in the same object. It is
  // reported by the parser; readers skip it.
  bool duplicate = false;
};

struct JsonLimits {
  int max_depth = 100;  // arrays and objects nested deeper than this are refused
  // Values (of any type) in one file: the tree takes ~50 bytes per value, so
  // this bounds its memory (~400 MiB) whatever the file holds ("0,0,0,...").
  std::size_t max_values = std::size_t{1} << 23;
};

class JsonDocument;

// Parses file->text. Returns std::nullopt if the text is not JSON (syntax error,
// nesting too deep); otherwise the document, even if non-fatal problems
// (duplicate keys, numbers out of range) were reported to `diag` -- so that the
// caller can go on and report the file's other problems too.
std::optional<JsonDocument> parse_json(std::shared_ptr<const SourceFile> file, Diagnostics& diag,
                                       const JsonLimits& limits = {});

// A parsed file: the tree plus what is needed to turn offsets into locations.
class JsonDocument {
 public:
  explicit JsonDocument(std::shared_ptr<const SourceFile> file);

  const JsonValue& root() const { return root_; }
  const std::shared_ptr<const SourceFile>& file() const { return file_; }

  SourceLocation location(std::size_t offset) const;
  SourceLocation location(const JsonValue& v) const { return location(v.offset()); }

 private:
  std::shared_ptr<const SourceFile> file_;
  std::vector<std::size_t> line_starts_;  // offset of the first byte of each line
  JsonValue root_;

  friend std::optional<JsonDocument> parse_json(std::shared_ptr<const SourceFile>, Diagnostics&,
                                                const JsonLimits&);
};

}  // namespace pt
