#include "core/diagnostics.h"

#include <algorithm>
#include <sstream>

namespace pt {

std::string format_number(double d) {
  std::ostringstream os;
  os.precision(d == static_cast<float>(d) ? 7 : 17);
  os << d;
  return os.str();
}


std::string SourceFile::line_text(int line) const {
  if (line < 1) return {};
  std::size_t start = 0;
  for (int l = 1; l < line; ++l) {
    const std::size_t nl = text.find('\n', start);
    if (nl == std::string::npos) return {};
    start = nl + 1;
  }
  std::size_t end = text.find('\n', start);
  if (end == std::string::npos) end = text.size();
  std::string s = text.substr(start, end - start);
  if (!s.empty() && s.back() == '\r') s.pop_back();
  return s;
}

std::string SourceLocation::to_string() const {
  if (!file) return "<command line>";
  std::ostringstream os;
  os << file->path;
  if (line > 0) os << ':' << line << ':' << col;
  return os.str();
}

SourceLocation location_at(std::shared_ptr<const SourceFile> file, std::size_t offset) {
  SourceLocation loc;
  if (!file) return loc;
  offset = std::min(offset, file->text.size());
  int line = 1;
  std::size_t line_start = 0;
  for (std::size_t i = 0; i < offset; ++i) {
    if (file->text[i] == '\n') {
      ++line;
      line_start = i + 1;
    }
  }
  loc.file = std::move(file);
  loc.line = line;
  loc.col = static_cast<int>(offset - line_start) + 1;
  return loc;
}

void Diagnostics::error(const SourceLocation& where, std::string message) {
  items_.push_back({Severity::Error, where, std::move(message)});
  ++error_count_;
}

void Diagnostics::warning(const SourceLocation& where, std::string message) {
  if (warnings_as_errors_) {
    error(where, std::move(message));
    return;
  }
  items_.push_back({Severity::Warning, where, std::move(message)});
  ++warning_count_;
}

void Diagnostics::note(const SourceLocation& where, std::string message) {
  items_.push_back({Severity::Note, where, std::move(message)});
}

static const char* severity_name(Severity s) {
  switch (s) {
    case Severity::Note: return "note";
    case Severity::Warning: return "warning";
    case Severity::Error: return "error";
  }
  return "error";
}

namespace {

// Lines longer than this are quoted as a window around the column: a minified
// file can hold all of its megabytes on one line.
constexpr std::size_t kMaxQuoted = 256;

bool utf8_continuation(char c) { return (static_cast<unsigned char>(c) & 0xC0) == 0x80; }

}  // namespace

std::string format_diagnostic(const Diagnostic& d) {
  std::ostringstream os;
  os << d.where.to_string() << ": " << severity_name(d.severity) << ": " << d.message << '\n';
  if (d.where.valid()) {
    std::string text = d.where.file->line_text(d.where.line);
    const std::size_t col0 = static_cast<std::size_t>(std::max(1, d.where.col) - 1);  // byte index
    std::size_t begin = 0;
    std::string before, after;
    if (text.size() > kMaxQuoted) {
      begin = std::min(col0 > kMaxQuoted / 2 ? col0 - kMaxQuoted / 2 : 0, text.size() - kMaxQuoted);
      std::size_t end = begin + kMaxQuoted;
      while (begin > 0 && begin < text.size() && utf8_continuation(text[begin])) --begin;  // whole characters
      while (end < text.size() && utf8_continuation(text[end])) ++end;
      if (begin > 0) before = "...";
      if (end < text.size()) after = "...";
      text = text.substr(begin, end - begin);
    }
    // Control characters (a NUL in a string) would garble the terminal.
    for (char& c : text)
      if ((static_cast<unsigned char>(c) < 0x20 && c != '\t') || c == 0x7f) c = '?';
    const std::string num = std::to_string(d.where.line);
    os << ' ' << num << " | " << before << text << after << '\n';
    os << ' ' << std::string(num.size(), ' ') << " | " << std::string(before.size(), ' ');
    // Keep tabs so the caret lines up under tab-indented text.
    for (std::size_t i = begin; i < col0 && i - begin < text.size(); ++i) os << (text[i - begin] == '\t' ? '\t' : ' ');
    os << "^\n";
  }
  return os.str();
}

std::string Diagnostics::format() const {
  // A generated file can hold thousands of identical problems: the first ones
  // are shown, the rest counted (the summary line below still counts all).
  constexpr std::size_t kMaxShown = 100;
  std::ostringstream os;
  for (std::size_t i = 0; i < items_.size() && i < kMaxShown; ++i) os << format_diagnostic(items_[i]);
  if (items_.size() > kMaxShown) os << "(" << items_.size() - kMaxShown << " more not shown)\n";
  if (error_count_ > 0)
    os << error_count_ << (error_count_ == 1 ? " error" : " errors") << ", " << warning_count_
       << (warning_count_ == 1 ? " warning" : " warnings") << '\n';
  return os.str();
}

}  // namespace pt
