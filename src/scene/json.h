// JSON with source locations.
//
// nlohmann-json does not record where values were written, so the scene files
// are parsed with its SAX interface into this small value tree, which keeps the
// byte offset of every value and every object key, and keeps object members in
// file order. JsonDocument turns offsets into file:line:col.
//
// The tree is compact, since a course file holds one object per triangle
// (docs/bench/scale.md): a value is 16 bytes (its payload, offset and type), an
// object member 32; the elements of each array and the members of each object
// are one exact-size run in the document's storage, and every distinct string
// (keys included) is stored once. A JsonValue is a view into its document:
// copies are cheap and valid while the document lives.
//
// parse_json() reports, with locations: syntax errors (the first one ends the
// parse), duplicate keys (the later one is an error, the first gets a note),
// numbers that overflow to infinity, NaN/Infinity spelled out, and nesting
// deeper than JsonLimits::max_depth (which ends the parse, so no tree is ever
// deep enough for recursion to be a danger), and more values than
// JsonLimits::max_values (which ends the parse, bounding the tree's memory).
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/diagnostics.h"

namespace pt {

enum class JsonType { Null, Bool, Number, String, Array, Object };

// "null", "a boolean", "a number", "a string", "an array", "an object".
const char* json_type_name(JsonType type);

struct JsonMember;

class JsonValue {
 public:
  using Array = std::span<const JsonValue>;
  using Object = std::span<const JsonMember>;

  JsonValue() = default;  // null at offset 0

  static JsonValue null(std::size_t offset);
  static JsonValue boolean(bool b, std::size_t offset);
  // `integer`: written without fraction or exponent.
  static JsonValue number(double d, bool integer, std::size_t offset);
  // The string, elements and members are the document's (JsonStorage): they
  // must outlive the value.
  static JsonValue string(const std::string* s, std::size_t offset);
  static JsonValue array(const JsonValue* items, std::size_t count, std::size_t offset);
  static JsonValue object(const JsonMember* members, std::size_t count, std::size_t offset);

  JsonType type() const { return static_cast<JsonType>(meta_ & kTypeMask); }
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
  Array as_array() const;
  Object as_object() const;

  // For objects: the member named `key` (its first definition), else nullptr.
  const JsonValue* find(std::string_view key) const;

  // Elements of one array or members of one object: the count is kept in the
  // value beside its type, so JsonLimits::max_values may not exceed this.
  static constexpr std::size_t kMaxCount = (std::size_t{1} << 28) - 1;
  // Offsets are 32-bit: parse_json refuses longer texts.
  static constexpr std::size_t kMaxOffset = UINT32_MAX;

 private:
  static constexpr uint32_t kTypeMask = 7;
  static constexpr uint32_t kIntegerBit = 8;
  static constexpr int kCountShift = 4;
  static JsonValue make(JsonType type, std::size_t offset, uint32_t extra = 0);

  union Payload {
    double number;
    bool boolean;
    const std::string* string;
    const JsonValue* items;
    const JsonMember* members;
  };
  Payload p_{0.0};
  uint32_t offset_ = 0;
  uint32_t meta_ = 0;  // type (3 bits), integer (1 bit), element or member count (28 bits)
};

struct JsonMember {
  const std::string& key;  // in the document's storage
  JsonValue value;
  uint32_t key_offset = 0;  // offset of the key's opening quote
  // A later definition of a key that appeared before in the same object. It is
  // reported by the parser; readers skip it.
  bool duplicate = false;
};

struct JsonLimits {
  int max_depth = 100;  // arrays and objects nested deeper than this are refused
  // Values (of any type) in one file: the tree takes 16-32 bytes per value, so
  // this bounds its memory (~256 MiB) whatever the file holds ("0,0,0,...").
  // At most JsonValue::kMaxCount.
  std::size_t max_values = std::size_t{1} << 23;
};

// Where a document's arrays, objects and strings live: blocks that never move
// (so moving the document keeps every JsonValue valid) and each distinct
// string once.
class JsonStorage {
 public:
  // `bytes` of uninitialised memory aligned for JsonValue and JsonMember.
  void* allocate(std::size_t bytes);
  // Keeps `s`; the caller looks strings up first so that each is kept once.
  const std::string* keep(std::string s);

 private:
  std::vector<std::unique_ptr<std::byte[]>> blocks_;
  std::byte* next_ = nullptr;
  std::size_t left_ = 0;
  std::size_t block_bytes_ = 4096;  // the next block's size: doubles up to 1 MiB
  std::deque<std::string> strings_;
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
  std::vector<uint32_t> line_starts_;  // offset of the first byte of each line
  std::unique_ptr<JsonStorage> storage_ = std::make_unique<JsonStorage>();
  JsonValue root_;

  friend std::optional<JsonDocument> parse_json(std::shared_ptr<const SourceFile>, Diagnostics&,
                                                const JsonLimits&);
};

}  // namespace pt
