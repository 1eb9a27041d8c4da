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
#include <memory>
#include <optional>
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
// Each open array or object collects its elements in a frame of its own; when
// it closes they are copied, at their exact count, into the document's
// storage. Frames are kept for reuse, so that their buffers are allocated
// once per depth, not once per container.
class TreeBuilder {
 public:
  using json = nlohmann::json;
  using number_integer_t = json::number_integer_t;
  using number_unsigned_t = json::number_unsigned_t;
  using number_float_t = json::number_float_t;
  using string_t = json::string_t;
  using binary_t = json::binary_t;

  TreeBuilder(const JsonDocument& doc, JsonStorage& storage, Diagnostics& diag, const JsonLimits& limits)
      : doc_(doc), storage_(storage), text_(doc.file()->text), diag_(diag), limits_(limits) {
    // The lexer skips a UTF-8 byte order mark.
    if (text_.size() >= 3 && std::memcmp(text_.data(), "\xEF\xBB\xBF", 3) == 0) prev_end_ = 3;
  }

  std::size_t* consumed() { return &consumed_; }
  JsonValue root() const { return root_; }

  // ---- SAX interface
  bool null() { return add_simple(JsonValue::null(token_start())); }
  bool boolean(bool b) { return add_simple(JsonValue::boolean(b, token_start())); }
  bool number_integer(number_integer_t v) { return add_number(static_cast<double>(v), true); }
  bool number_unsigned(number_unsigned_t v) { return add_number(static_cast<double>(v), true); }
  bool number_float(number_float_t v, const string_t& /*text*/) { return add_number(v, false); }
  bool string(string_t& s) { return add_simple(JsonValue::string(intern(std::move(s)), token_start())); }
  bool binary(binary_t& /*unused*/) { return true; }  // never produced by the JSON lexer

  bool start_object(std::size_t /*size*/) { return open(true); }
  bool start_array(std::size_t /*size*/) { return open(false); }
  bool end_object() { return close(); }
  bool end_array() { return close(); }

  bool key(string_t& k) {
    const std::size_t start = token_start();
    prev_end_ = consumed_;
    const std::string* key = intern(std::move(k));
    const std::optional<uint32_t> first = stack_[depth_ - 1].find(key);
    pending_duplicate_ = first.has_value();
    if (first) {
      diag_.error(doc_.location(start), "duplicate key '" + *key + "'");
      diag_.note(doc_.location(*first), "'" + *key + "' is first defined here");
    }
    pending_key_ = key;
    pending_key_offset_ = static_cast<uint32_t>(start);
    return true;
  }

  bool parse_error(std::size_t position, const std::string& /*last_token*/,
                   const nlohmann::detail::exception& ex) {
    report_syntax_error(position, ex.what());
    return false;
  }

 private:
  // Objects look keys up by address (each distinct key is kept once); an
  // object with many members builds an index.
  static constexpr std::size_t kIndexedMembers = 32;

  struct Frame {
    bool object = false;
    std::size_t offset = 0;
    // The key this container is the value of, in the enclosing object (it is
    // added there when it closes, after keys of its own).
    const std::string* key = nullptr;
    uint32_t key_offset = 0;
    bool duplicate = false;
    std::vector<JsonValue> items;
    std::vector<JsonMember> members;
    std::unordered_map<const std::string*, uint32_t> index;  // key -> offset, past kIndexedMembers

    // The offset of the first definition of `name` in this object, if any.
    std::optional<uint32_t> find(const std::string* name) const {
      if (members.size() > kIndexedMembers) {
        const auto it = index.find(name);
        return it == index.end() ? std::nullopt : std::optional<uint32_t>(it->second);
      }
      for (const JsonMember& m : members)
        if (&m.key == name) return m.key_offset;
      return std::nullopt;
    }
    void add(JsonMember m) {
      members.push_back(std::move(m));
      if (members.size() == kIndexedMembers + 1) {
        for (const JsonMember& e : members) index.emplace(&e.key, e.key_offset);
      } else if (members.size() > kIndexedMembers + 1) {
        index.emplace(&members.back().key, members.back().key_offset);
      }
    }
  };

  const std::string* intern(std::string s) {
    if (const auto it = strings_.find(s); it != strings_.end()) return it->second;
    const std::string* kept = storage_.keep(std::move(s));
    strings_.emplace(*kept, kept);
    return kept;
  }

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
    return count(v.offset()) && add(v);
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
    return count(start) && add(JsonValue::number(d, integer, start));
  }

  bool open(bool object) {
    const std::size_t start = token_start();
    prev_end_ = consumed_;
    if (static_cast<int>(depth_) >= limits_.max_depth) {
      diag_.error(doc_.location(start), "arrays and objects are nested more than " +
                                            std::to_string(limits_.max_depth) + " levels deep");
      return false;
    }
    if (!count(start)) return false;
    if (depth_ == stack_.size()) stack_.emplace_back();
    Frame& f = stack_[depth_++];
    f.object = object;
    f.offset = start;
    f.key = pending_key_;
    f.key_offset = pending_key_offset_;
    f.duplicate = pending_duplicate_;
    return true;
  }

  // The container is complete: its elements move to the document's storage,
  // exactly as many as it has.
  bool close() {
    prev_end_ = consumed_;
    Frame& f = stack_[--depth_];
    JsonValue done;
    if (f.object) {
      auto* members = static_cast<JsonMember*>(storage_.allocate(f.members.size() * sizeof(JsonMember)));
      for (std::size_t i = 0; i < f.members.size(); ++i) new (members + i) JsonMember(f.members[i]);
      done = JsonValue::object(members, f.members.size(), f.offset);
      f.members.clear();
      f.index.clear();
    } else {
      auto* items = static_cast<JsonValue*>(storage_.allocate(f.items.size() * sizeof(JsonValue)));
      std::uninitialized_copy(f.items.begin(), f.items.end(), items);
      done = JsonValue::array(items, f.items.size(), f.offset);
      f.items.clear();
    }
    pending_key_ = f.key;
    pending_key_offset_ = f.key_offset;
    pending_duplicate_ = f.duplicate;
    return add(done);
  }

  // Counts a value; past JsonLimits::max_values, reports it and returns false.
  bool count(std::size_t offset) {
    if (++values_ <= max_values_) return true;
    diag_.error(doc_.location(offset), "the file holds more than " + std::to_string(max_values_) +
                                           " values; put large meshes in PLY files");
    return false;
  }

  // Appends `v` to the open container (or makes it the root).
  bool add(const JsonValue& v) {
    if (depth_ == 0) {
      root_ = v;
      return true;
    }
    Frame& top = stack_[depth_ - 1];
    if (!top.object) {
      top.items.push_back(v);
    } else {
      top.add(JsonMember{*pending_key_, v, pending_key_offset_, pending_duplicate_});
    }
    return true;
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
  JsonStorage& storage_;
  const std::string& text_;
  Diagnostics& diag_;
  const JsonLimits& limits_;
  const std::size_t max_values_ = std::min(limits_.max_values, JsonValue::kMaxCount);

  std::size_t consumed_ = 0;  // bytes the lexer has read
  std::size_t values_ = 0;    // values added to the tree
  std::size_t prev_end_ = 0;  // one past the previous token
  std::vector<Frame> stack_;  // frames of the open arrays and objects (and spare ones, for reuse)
  std::size_t depth_ = 0;     // open arrays and objects: stack_[0, depth_)
  std::unordered_map<std::string_view, const std::string*> strings_;  // each distinct string, kept once
  JsonValue root_;
  const std::string* pending_key_ = nullptr;
  uint32_t pending_key_offset_ = 0;
  bool pending_duplicate_ = false;
};

}  // namespace

std::optional<JsonDocument> parse_json(std::shared_ptr<const SourceFile> file, Diagnostics& diag,
                                       const JsonLimits& limits) {
  JsonDocument doc(std::move(file));
  const std::string& text = doc.file()->text;
  if (text.size() > JsonValue::kMaxOffset) {
    diag.error(doc.location(0), "the file is " + std::to_string(text.size() >> 20) +
                                    " MiB; JSON texts of 4 GiB or more are refused");
    return std::nullopt;
  }
  TreeBuilder builder(doc, *doc.storage_, diag, limits);
  const CountingIterator first(text.data(), builder.consumed());
  const CountingIterator last(text.data() + text.size(), nullptr);
  const bool ok = nlohmann::json::sax_parse(first, last, &builder, nlohmann::json::input_format_t::json,
                                            /*strict=*/true, /*ignore_comments=*/false);
  if (!ok) return std::nullopt;
  doc.root_ = builder.root();
  return doc;
}

}  // namespace pt
