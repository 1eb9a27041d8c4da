// JSON parsing with locations: nlohmann's SAX parser drives a tree builder.
//
// nlohmann's SAX events carry no positions, so the parser reads the text
// through an iterator that counts the bytes consumed. When an event arrives,
// its token has just been read; the token's first byte is found by skipping
// whitespace (and at most one ',' or ':') from where the previous token ended.
// The end of a token is the consumed count, except for numbers: the lexer reads
// one character past a number, so a number ends where its characters end.
#include <cmath>
#include <cstring>
#include <iterator>
#include <string>
#include <unordered_map>

#include <nlohmann/json.hpp>

#include "scene/json.h"

namespace pt {
namespace {

// Input iterator over the text that counts how many bytes the lexer consumed.
class CountingIterator {
 public:
  using iterator_category = std::input_iterator_tag;
  using value_type = char;
  using difference_type = std::ptrdiff_t;
  using pointer = const char*;
  using reference = const char&;

  CountingIterator() = default;
  CountingIterator(const char* p, std::size_t* consumed) : p_(p), consumed_(consumed) {}

  reference operator*() const { return *p_; }
  CountingIterator& operator++() {
    ++p_;
    if (consumed_) ++*consumed_;
    return *this;
  }
  CountingIterator operator++(int) {
    CountingIterator old = *this;
    ++*this;
    return old;
  }
  bool operator==(const CountingIterator& o) const { return p_ == o.p_; }
  bool operator!=(const CountingIterator& o) const { return p_ != o.p_; }

 private:
  const char* p_ = nullptr;
  std::size_t* consumed_ = nullptr;
};

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }
bool is_number_char(char c) {
  return (c >= '0' && c <= '9') || c == '-' || c == '+' || c == '.' || c == 'e' || c == 'E';
}
bool is_word_char(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
         c == '-' || c == '+' || c == '.';
}

bool starts_with_nocase(std::string_view s, std::string_view prefix) {
  if (s.size() < prefix.size()) return false;
  for (std::size_t i = 0; i < prefix.size(); ++i) {
    const char a = static_cast<char>(std::tolower(static_cast<unsigned char>(s[i])));
    if (a != prefix[i]) return false;
  }
  return true;
}

// Builds the JsonValue tree from SAX events (the interface nlohmann::json::sax_parse expects).
class TreeBuilder {
 public:
  using json = nlohmann::json;
  using number_integer_t = json::number_integer_t;
  using number_unsigned_t = json::number_unsigned_t;
  using number_float_t = json::number_float_t;
  using string_t = json::string_t;
  using binary_t = json::binary_t;

  TreeBuilder(const JsonDocument& doc, Diagnostics& diag, const JsonLimits& limits)
      : doc_(doc), text_(doc.file()->text), diag_(diag), limits_(limits) {
    // The lexer skips a UTF-8 byte order mark.
    if (text_.size() >= 3 && std::memcmp(text_.data(), "\xEF\xBB\xBF", 3) == 0) prev_end_ = 3;
  }

  std::size_t* consumed() { return &consumed_; }
  JsonValue take_root() { return std::move(root_); }

  // ---- SAX interface
  bool null() { return add_simple(JsonValue::null(token_start())); }
  bool boolean(bool b) { return add_simple(JsonValue::boolean(b, token_start())); }
  bool number_integer(number_integer_t v) { return add_number(static_cast<double>(v), true); }
  bool number_unsigned(number_unsigned_t v) { return add_number(static_cast<double>(v), true); }
  bool number_float(number_float_t v, const string_t& /*text*/) { return add_number(v, false); }
  bool string(string_t& s) { return add_simple(JsonValue::string(std::move(s), token_start())); }
  bool binary(binary_t& /*unused*/) { return true; }  // never produced by the JSON lexer

  bool start_object(std::size_t /*size*/) { return open(JsonValue::object(token_start())); }
  bool start_array(std::size_t /*size*/) { return open(JsonValue::array(token_start())); }
  bool end_object() { return close(); }
  bool end_array() { return close(); }

  bool key(string_t& k) {
    const std::size_t start = token_start();
    prev_end_ = consumed_;
    Frame& top = stack_.back();
    const auto [it, inserted] = top.keys.emplace(k, start);
    pending_duplicate_ = !inserted;
    if (!inserted) {
      diag_.error(doc_.location(start), "duplicate key '" + k + "'");
      diag_.note(doc_.location(it->second), "'" + k + "' is first defined here");
    }
    pending_key_ = std::move(k);
    pending_key_offset_ = start;
    return true;
  }

  bool parse_error(std::size_t position, const std::string& /*last_token*/,
                   const nlohmann::detail::exception& ex) {
    report_syntax_error(position, ex.what());
    return false;
  }

 private:
  struct Frame {
    JsonValue* value;
    std::unordered_map<std::string, std::size_t> keys;  // objects: key -> offset of its first definition
  };

  // First byte of the token the lexer has just read.
  std::size_t token_start() const {
    std::size_t i = std::min(prev_end_, text_.size());
    const std::size_t end = std::min(consumed_, text_.size());
    while (i < end && is_space(text_[i])) ++i;
    if (i < end && (text_[i] == ',' || text_[i] == ':')) {
      ++i;
      while (i < end && is_space(text_[i])) ++i;
    }
    return i;
  }

  bool add_simple(JsonValue v) {
    prev_end_ = consumed_;
    return add(std::move(v)) != nullptr;
  }

  bool add_number(double d, bool integer) {
    const std::size_t start = token_start();
    std::size_t end = start;
    while (end < text_.size() && is_number_char(text_[end])) ++end;
    prev_end_ = end;
    if (!std::isfinite(d)) {  // defensive: nlohmann reports overflow itself (out_of_range.406)
      diag_.error(doc_.location(start), "number '" + text_.substr(start, end - start) +
                                            "' is out of range (it overflows to infinity)");
    }
    return add(JsonValue::number(d, integer, start)) != nullptr;
  }

  bool open(JsonValue v) {
    const std::size_t start = v.offset();
    prev_end_ = consumed_;
    if (static_cast<int>(stack_.size()) >= limits_.max_depth) {
      diag_.error(doc_.location(start), "arrays and objects are nested more than " +
                                            std::to_string(limits_.max_depth) + " levels deep");
      return false;
    }
    JsonValue* added = add(std::move(v));
    if (added == nullptr) return false;
    stack_.push_back(Frame{added, {}});
    return true;
  }

  bool close() {
    prev_end_ = consumed_;
    // The container is complete: its spare capacity (up to half of it, from
    // push_back's doubling) is given back. A course file of small objects
    // (a triangle's three 3-vectors, a material's nine members) keeps about
    // a third less this way.
    JsonValue& done = *stack_.back().value;
    if (done.is_array()) {
      done.as_array().shrink_to_fit();
    } else {
      done.as_object().shrink_to_fit();
    }
    stack_.pop_back();
    return true;
  }

  // Appends `v` to the open container (or makes it the root); returns where it
  // now lives, or nullptr (after reporting it) past JsonLimits::max_values.
  JsonValue* add(JsonValue v) {
    if (++values_ > limits_.max_values) {
      diag_.error(doc_.location(v.offset()), "the file holds more than " + std::to_string(limits_.max_values) +
                                                 " values; put large meshes in PLY files");
      return nullptr;
    }
    if (stack_.empty()) {
      root_ = std::move(v);
      return &root_;
    }
    JsonValue& top = *stack_.back().value;
    if (top.is_array()) {
      top.as_array().push_back(std::move(v));
      return &top.as_array().back();
    }
    JsonMember m;
    m.key = std::move(pending_key_);
    m.key_offset = pending_key_offset_;
    m.value = std::move(v);
    m.duplicate = pending_duplicate_;
    top.as_object().push_back(std::move(m));
    return &top.as_object().back().value;
  }

  void report_syntax_error(std::size_t position, const std::string& what) {
    // nlohmann: "[json.exception.parse_error.101] parse error at line L, column C:
    //            syntax error while parsing CONTEXT - DETAIL; last read: 'TOKEN'"
    std::string detail = what;
    if (const std::size_t dash = detail.find(" - "); dash != std::string::npos) detail = detail.substr(dash + 3);
    if (const std::size_t last = detail.find("; last read:"); last != std::string::npos) detail.resize(last);

    std::size_t at = token_start();
    std::string_view rest = std::string_view(text_).substr(std::min(at, text_.size()));
    std::string_view unsigned_rest = rest;
    if (!unsigned_rest.empty() && (unsigned_rest[0] == '-' || unsigned_rest[0] == '+'))
      unsigned_rest.remove_prefix(1);
    const bool in_string = detail.rfind("invalid string", 0) == 0;
    const bool nan_or_inf =
        !in_string && (starts_with_nocase(unsigned_rest, "nan") || starts_with_nocase(unsigned_rest, "inf"));
    // Problems inside a string or number are shown at the offending character.
    if (!nan_or_inf && (in_string || detail.rfind("invalid number", 0) == 0) && position > 0) {
      at = std::min(position - 1, text_.size());
      rest = std::string_view(text_).substr(at);
    }

    std::string message;
    if (!in_string && at < text_.size() && text_[at] == '\0') {
      // Outside strings nlohmann reads a NUL as the end of the input.
      message = "the file holds a NUL byte here; it is not a JSON text file";
    } else if (what.find("out_of_range.406") != std::string::npos) {
      // nlohmann refuses numbers that overflow a double ("1e999") before any event.
      std::size_t n = 0;
      while (n < rest.size() && is_number_char(rest[n])) ++n;
      message = "number '" + std::string(rest.substr(0, n)) + "' is out of range (it overflows to infinity)";
    } else if (text_.find_first_not_of(" \t\r\n") == std::string::npos) {
      message = "the file is empty; expected a JSON object";
    } else if (nan_or_inf) {
      message = "NaN and Infinity are not valid JSON numbers; write a finite number";
    } else if (detail.rfind("invalid literal", 0) == 0) {
      std::size_t n = 0;
      while (n < rest.size() && is_word_char(rest[n])) ++n;
      message = "invalid literal '" + std::string(rest.substr(0, std::max<std::size_t>(n, 1))) +
                "'; expected a number, a string, true, false, null, an array or an object";
    } else {
      message = "JSON syntax error: " + detail;
      if (detail.find("unexpected end of input") != std::string::npos) message += " (is the file truncated?)";
      else if (detail.find("expected end of input") != std::string::npos) message += " (text after the scene's closing brace)";
      else if (detail.find("expected '}'") != std::string::npos || detail.find("expected ']'") != std::string::npos)
        message += " (missing ','?)";
    }

    // At the end of the input, point just after the last thing written.
    if (at >= text_.size()) {
      const std::size_t last = text_.find_last_not_of(" \t\r\n");
      at = last == std::string::npos ? 0 : last + 1;
    }
    diag_.error(doc_.location(at), std::move(message));
  }

  const JsonDocument& doc_;
  const std::string& text_;
  Diagnostics& diag_;
  const JsonLimits& limits_;

  std::size_t consumed_ = 0;  // bytes the lexer has read
  std::size_t values_ = 0;    // values added to the tree
  std::size_t prev_end_ = 0;  // one past the previous token
  std::vector<Frame> stack_;  // open arrays and objects
  JsonValue root_;
  std::string pending_key_;
  std::size_t pending_key_offset_ = 0;
  bool pending_duplicate_ = false;
};

}  // namespace

std::optional<JsonDocument> parse_json(std::shared_ptr<const SourceFile> file, Diagnostics& diag,
                                       const JsonLimits& limits) {
  JsonDocument doc(std::move(file));
  TreeBuilder builder(doc, diag, limits);
  const std::string& text = doc.file()->text;
  const CountingIterator first(text.data(), builder.consumed());
  const CountingIterator last(text.data() + text.size(), nullptr);
  const bool ok = nlohmann::json::sax_parse(first, last, &builder, nlohmann::json::input_format_t::json,
                                            /*strict=*/true, /*ignore_comments=*/false);
  if (!ok) return std::nullopt;
  doc.root_ = builder.take_root();
  return doc;
}

}  // namespace pt
