#include "core/diagnostics.h"

#include <algorithm>
#include <sstream>

namespace pt {

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

std::string format_diagnostic(const Diagnostic& d) {
  std::ostringstream os;
  os << d.where.to_string() << ": " << severity_name(d.severity) << ": " << d.message << '\n';
  if (d.where.valid()) {
    const std::string text = d.where.file->line_text(d.where.line);
    const std::string num = std::to_string(d.where.line);
    os << ' ' << num << " | " << text << '\n';
    os << ' ' << std::string(num.size(), ' ') << " | ";
    // Keep tabs so the caret lines up under tab-indented text.
    const int col = std::max(1, d.where.col);
    for (int i = 0; i < col - 1 && i < static_cast<int>(text.size()); ++i)
      os << (text[static_cast<std::size_t>(i)] == '\t' ? '\t' : ' ');
    os << "^\n";
  }
  return os.str();
}

std::string Diagnostics::format() const {
  std::ostringstream os;
  for (const Diagnostic& d : items_) os << format_diagnostic(d);
  if (error_count_ > 0)
    os << error_count_ << (error_count_ == 1 ? " error" : " errors") << ", " << warning_count_
       << (warning_count_ == 1 ? " warning" : " warnings") << '\n';
  return os.str();
}

}  // namespace pt
