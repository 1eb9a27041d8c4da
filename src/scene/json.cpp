// The JSON value tree and documents. The parser is in json_parse.cpp.
#include "scene/json.h"

#include <algorithm>
#include <cassert>

namespace pt {

const char* json_type_name(JsonType type) {
  switch (type) {
    case JsonType::Null: return "null";
    case JsonType::Bool: return "a boolean";
    case JsonType::Number: return "a number";
    case JsonType::String: return "a string";
    case JsonType::Array: return "an array";
    case JsonType::Object: return "an object";
  }
  return "a value";
}

// Defined here, where JsonMember is complete.
JsonValue::~JsonValue() = default;
JsonValue::JsonValue(const JsonValue&) = default;
JsonValue::JsonValue(JsonValue&&) noexcept = default;
JsonValue& JsonValue::operator=(const JsonValue&) = default;
JsonValue& JsonValue::operator=(JsonValue&&) noexcept = default;

JsonValue JsonValue::null(std::size_t offset) {
  JsonValue v;
  v.offset_ = offset;
  return v;
}

JsonValue JsonValue::boolean(bool b, std::size_t offset) {
  JsonValue v;
  v.data_ = b;
  v.offset_ = offset;
  return v;
}

JsonValue JsonValue::number(double d, bool integer, std::size_t offset) {
  JsonValue v;
  v.data_ = Number{d, integer};
  v.offset_ = offset;
  return v;
}

JsonValue JsonValue::string(std::string s, std::size_t offset) {
  JsonValue v;
  v.data_ = std::move(s);
  v.offset_ = offset;
  return v;
}

JsonValue JsonValue::array(std::size_t offset) {
  JsonValue v;
  v.data_ = Array{};
  v.offset_ = offset;
  return v;
}

JsonValue JsonValue::object(std::size_t offset) {
  JsonValue v;
  v.data_ = Object{};
  v.offset_ = offset;
  return v;
}

bool JsonValue::as_bool() const {
  assert(is_bool());
  return std::get<bool>(data_);
}

double JsonValue::as_number() const {
  assert(is_number());
  return std::get<Number>(data_).value;
}

bool JsonValue::is_integer() const { return is_number() && std::get<Number>(data_).integer; }

const std::string& JsonValue::as_string() const {
  assert(is_string());
  return std::get<std::string>(data_);
}

const JsonValue::Array& JsonValue::as_array() const {
  assert(is_array());
  return std::get<Array>(data_);
}

JsonValue::Array& JsonValue::as_array() {
  assert(is_array());
  return std::get<Array>(data_);
}

const JsonValue::Object& JsonValue::as_object() const {
  assert(is_object());
  return std::get<Object>(data_);
}

JsonValue::Object& JsonValue::as_object() {
  assert(is_object());
  return std::get<Object>(data_);
}

const JsonValue* JsonValue::find(std::string_view key) const {
  if (!is_object()) return nullptr;
  for (const JsonMember& m : as_object())
    if (!m.duplicate && m.key == key) return &m.value;
  return nullptr;
}

JsonDocument::JsonDocument(std::shared_ptr<const SourceFile> file) : file_(std::move(file)) {
  line_starts_.push_back(0);
  if (!file_) return;
  const std::string& text = file_->text;
  for (std::size_t i = 0; i < text.size(); ++i)
    if (text[i] == '\n') line_starts_.push_back(i + 1);
}

SourceLocation JsonDocument::location(std::size_t offset) const {
  SourceLocation loc;
  if (!file_) return loc;
  offset = std::min(offset, file_->text.size());
  // The last line start <= offset.
  const auto it = std::upper_bound(line_starts_.begin(), line_starts_.end(), offset);
  const std::size_t line = static_cast<std::size_t>(it - line_starts_.begin());  // 1-based
  loc.file = file_;
  loc.line = static_cast<int>(line);
  loc.col = static_cast<int>(offset - line_starts_[line - 1]) + 1;
  return loc;
}

}  // namespace pt
