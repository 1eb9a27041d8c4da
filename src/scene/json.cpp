// The JSON value tree and documents. The parser is in json_parse.cpp.
#include "scene/json.h"

#include <algorithm>
#include <cassert>
#include <cstddef>
#include <memory>

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

JsonValue JsonValue::make(JsonType type, std::size_t offset, uint32_t extra) {
  assert(offset <= kMaxOffset);
  JsonValue v;
  v.offset_ = static_cast<uint32_t>(offset);
  v.meta_ = static_cast<uint32_t>(type) | extra;
  return v;
}

JsonValue JsonValue::null(std::size_t offset) { return make(JsonType::Null, offset); }

JsonValue JsonValue::boolean(bool b, std::size_t offset) {
  JsonValue v = make(JsonType::Bool, offset);
  v.p_.boolean = b;
  return v;
}

JsonValue JsonValue::number(double d, bool integer, std::size_t offset) {
  JsonValue v = make(JsonType::Number, offset, integer ? kIntegerBit : 0);
  v.p_.number = d;
  return v;
}

JsonValue JsonValue::string(const std::string* s, std::size_t offset) {
  JsonValue v = make(JsonType::String, offset);
  v.p_.string = s;
  return v;
}

JsonValue JsonValue::array(const JsonValue* items, std::size_t count, std::size_t offset) {
  assert(count <= kMaxCount);
  JsonValue v = make(JsonType::Array, offset, static_cast<uint32_t>(count) << kCountShift);
  v.p_.items = items;
  return v;
}

JsonValue JsonValue::object(const JsonMember* members, std::size_t count, std::size_t offset) {
  assert(count <= kMaxCount);
  JsonValue v = make(JsonType::Object, offset, static_cast<uint32_t>(count) << kCountShift);
  v.p_.members = members;
  return v;
}

bool JsonValue::as_bool() const {
  assert(is_bool());
  return p_.boolean;
}

double JsonValue::as_number() const {
  assert(is_number());
  return p_.number;
}

bool JsonValue::is_integer() const { return is_number() && (meta_ & kIntegerBit) != 0; }

const std::string& JsonValue::as_string() const {
  assert(is_string());
  return *p_.string;
}

JsonValue::Array JsonValue::as_array() const {
  assert(is_array());
  return Array(p_.items, meta_ >> kCountShift);
}

JsonValue::Object JsonValue::as_object() const {
  assert(is_object());
  return Object(p_.members, meta_ >> kCountShift);
}

const JsonValue* JsonValue::find(std::string_view key) const {
  if (!is_object()) return nullptr;
  for (const JsonMember& m : as_object())
    if (!m.duplicate && m.key == key) return &m.value;
  return nullptr;
}

void* JsonStorage::allocate(std::size_t bytes) {
  constexpr std::size_t kAlign = alignof(JsonMember) > alignof(JsonValue) ? alignof(JsonMember) : alignof(JsonValue);
  static_assert(kAlign <= alignof(std::max_align_t));
  bytes = (bytes + kAlign - 1) / kAlign * kAlign;
  if (bytes > left_) {
    constexpr std::size_t kLargestBlock = std::size_t{1} << 20;
    const std::size_t size = std::max(bytes, block_bytes_);
    block_bytes_ = std::min(block_bytes_ * 2, kLargestBlock);
    blocks_.push_back(std::make_unique_for_overwrite<std::byte[]>(size));
    next_ = blocks_.back().get();
    left_ = size;
  }
  void* p = next_;
  next_ += bytes;
  left_ -= bytes;
  return p;
}

const std::string* JsonStorage::keep(std::string s) { return &strings_.emplace_back(std::move(s)); }

JsonDocument::JsonDocument(std::shared_ptr<const SourceFile> file) : file_(std::move(file)) {
  line_starts_.push_back(0);
  if (!file_) return;
  // Lines past JsonValue::kMaxOffset are not counted: parse_json refuses such texts.
  const std::string& text = file_->text;
  const std::size_t n = std::min(text.size(), JsonValue::kMaxOffset);
  for (std::size_t i = 0; i < n; ++i)
    if (text[i] == '\n') line_starts_.push_back(static_cast<uint32_t>(i + 1));
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
