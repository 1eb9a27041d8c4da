#include "scene/overrides.h"

#include <algorithm>
#include <memory>
#include <optional>

#include <nlohmann/json.hpp>

#include "scene/json.h"
#include "scene/suggest.h"

namespace pt {
namespace {

struct Segment {
  bool is_index = false;
  std::string key;
  std::size_t index = 0;
};

SourceLocation set_location(const std::string& argument) {
  SourceLocation loc;
  loc.file = std::make_shared<const SourceFile>(SourceFile{"--set " + argument, {}});
  return loc;
}

// "a.b[2].c" -> a, b, [2], c. False for an empty key, empty segment or bad index.
bool split_key(const std::string& key, std::vector<Segment>& out, std::string& why) {
  std::size_t i = 0;
  while (i < key.size()) {
    if (key[i] == '[') {
      const std::size_t close = key.find(']', i);
      const std::string digits = close == std::string::npos ? "" : key.substr(i + 1, close - i - 1);
      if (digits.empty() || !std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; }) ||
          digits.size() > 9) {
        why = "bad array index in '" + key + "' (write [N] with N a number from 0)";
        return false;
      }
      out.push_back({true, {}, std::stoul(digits)});
      i = close + 1;
      if (i < key.size() && key[i] == '.') ++i;
      continue;
    }
    const std::size_t end = key.find_first_of(".[", i);
    const std::string name = key.substr(i, end == std::string::npos ? std::string::npos : end - i);
    if (name.empty()) {
      why = "empty key segment in '" + key + "'";
      return false;
    }
    out.push_back({false, name, 0});
    i = end == std::string::npos ? key.size() : end;
    if (i < key.size() && key[i] == '.') {
      ++i;
      if (i == key.size()) {
        why = "'" + key + "' ends with '.'";
        return false;
      }
    }
  }
  if (out.empty()) why = "empty key";
  return !out.empty();
}

// The offset just past the JSON value starting at `pos` (the text is valid JSON).
std::size_t value_end(const std::string& text, std::size_t pos) {
  int depth = 0;
  std::size_t i = pos;
  do {
    const char c = text[i];
    if (c == '"') {
      for (++i; i < text.size() && text[i] != '"'; ++i)
        if (text[i] == '\\') ++i;
      ++i;
    } else if (c == '{' || c == '[') {
      ++depth;
      ++i;
    } else if (c == '}' || c == ']') {
      --depth;
      ++i;
    } else if (depth > 0) {
      ++i;
    } else {
      while (i < text.size() && std::string_view(",}] \t\r\n").find(text[i]) == std::string_view::npos) ++i;
    }
  } while (depth > 0 && i < text.size());
  return i;
}

std::string path_text(const std::vector<Segment>& segs, std::size_t n) {
  if (n == 0) return "the top level of the scene file";
  std::string s;
  for (std::size_t i = 0; i < n; ++i) {
    if (segs[i].is_index) {
      s += '[';
      s += std::to_string(segs[i].index);
      s += ']';
    } else {
      if (!s.empty()) s += '.';
      s += segs[i].key;
    }
  }
  return pt::quoted(s);
}

std::vector<std::string> keys_of(const JsonValue& object) {
  std::vector<std::string> keys;
  for (const JsonMember& m : object.as_object())
    if (!m.duplicate) keys.push_back(m.key);
  return keys;
}

// Applies one override to `text`. Returns false after reporting.
bool apply_one(const std::string& path, std::string& text, const std::string& argument, Diagnostics& diag,
               std::vector<OverrideLine>& lines) {
  const SourceLocation where = set_location(argument);
  const std::size_t eq = argument.find('=');
  if (eq == std::string::npos) {
    diag.error(where, "expected key=value, e.g. render.spp=256");
    return false;
  }
  const std::string key = argument.substr(0, eq), value = argument.substr(eq + 1);
  std::vector<Segment> segs;
  std::string why;
  if (!split_key(key, segs, why)) {
    diag.error(where, why);
    return false;
  }
  nlohmann::json parsed = nlohmann::json::parse(value, nullptr, false);
  if (parsed.is_discarded()) parsed = value;  // a bare word is a string
  const std::string new_text = parsed.dump();

  auto file = std::make_shared<const SourceFile>(SourceFile{path, text});
  Diagnostics parse_diag;
  const std::optional<JsonDocument> doc = parse_json(file, parse_diag);
  if (!doc || parse_diag.has_errors()) return true;  // the loader reports the file's own errors

  const JsonValue* v = &doc->root();
  for (std::size_t i = 0; i < segs.size(); ++i) {
    const Segment& s = segs[i];
    const bool last = i + 1 == segs.size();
    if (s.is_index) {
      if (!v->is_array()) {
        diag.error(where, "cannot index " + path_text(segs, i) + " with [" + std::to_string(s.index) + "]: it is " +
                              json_type_name(v->type()) + ", not an array");
        return false;
      }
      const auto& items = v->as_array();
      if (s.index >= items.size()) {
        diag.error(where, path_text(segs, i) + " has " + std::to_string(items.size()) + " elements" +
                              (items.empty() ? std::string()
                                             : " (indices 0 to " + std::to_string(items.size() - 1) + ")") +
                              ", no [" + std::to_string(s.index) + "]");
        return false;
      }
      v = &items[s.index];
      continue;
    }
    if (!v->is_object()) {
      diag.error(where, "cannot look up '" + s.key + "' in " + path_text(segs, i) + ": it is " +
                            json_type_name(v->type()) + ", not an object");
      return false;
    }
    const JsonValue* member = v->find(s.key);
    if (member == nullptr && last) {  // a new member: inserted after the object's '{'
      const std::size_t brace = v->offset() + 1;
      const bool empty = v->as_object().empty();
      const std::string member_text = nlohmann::json(s.key).dump() + ": " + new_text + (empty ? "" : ", ");
      text.insert(brace, member_text);
      const SourceLocation at = location_at(file, brace);
      lines.push_back({at.line, at.col, at.col + static_cast<int>(member_text.size()), argument});
      return true;
    }
    if (member == nullptr) {
      const std::vector<std::string> keys = keys_of(*v);
      const std::string guess = closest_match(s.key, keys);
      diag.error(where, path_text(segs, i) + " has no key " + pt::quoted(s.key) +
                            (guess.empty() ? "" : "; did you mean " + pt::quoted(guess) + "?") +
                            (keys.empty() ? " (it is empty)" : " (its keys: " + pt::quoted_list(keys, "and") + ")"));
      return false;
    }
    v = member;
  }
  const std::size_t begin = v->offset(), end = value_end(text, begin);
  const auto newlines = std::count(text.begin() + static_cast<std::ptrdiff_t>(begin),
                                   text.begin() + static_cast<std::ptrdiff_t>(end), '\n');
  const SourceLocation at = location_at(file, begin);
  lines.push_back({at.line, at.col, at.col + static_cast<int>(new_text.size()), argument});
  text.replace(begin, end - begin, new_text + std::string(static_cast<std::size_t>(newlines), '\n'));
  return true;
}

}  // namespace

bool apply_scene_overrides(const std::string& path, std::string& text, const std::vector<std::string>& overrides,
                           Diagnostics& diag, std::vector<OverrideLine>& lines) {
  bool ok = true;
  for (const std::string& argument : overrides) ok = apply_one(path, text, argument, diag, lines) && ok;
  return ok;
}

void forward_with_override_notes(const Diagnostics& from, const std::vector<OverrideLine>& lines, Diagnostics& to) {
  for (const Diagnostic& d : from.all()) {
    switch (d.severity) {
      case Severity::Error: to.error(d.where, d.message); break;
      case Severity::Warning: to.warning(d.where, d.message); break;
      case Severity::Note: to.note(d.where, d.message); break;
    }
    if (d.severity == Severity::Note || !d.where.valid()) continue;
    for (const OverrideLine& l : lines)
      if (l.line == d.where.line && d.where.col >= l.col_begin && d.where.col < l.col_end)
        to.note(set_location(l.argument), "this value comes from --set " + l.argument);
  }
}

}  // namespace pt
