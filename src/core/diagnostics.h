// Diagnostics: every problem the renderer reports about its input carries the
// place it came from (file:line:col) and is printed with the offending line
// and a caret under the column, e.g.
//
//   scenes/bad.json:12:17: error: radius must be > 0, got -1
//      12 |       "radius": -1,
//         |                 ^
//
// Library code never exits or prints: it adds to a Diagnostics list and the
// caller decides. Errors are collected so a file reports all its problems in
// one run.
#pragma once

#include <memory>
#include <string>
#include <vector>

namespace pt {

// A number as a short decimal ("0.5", "1e+20"), for messages.
std::string format_number(double d);

// The text of one input file, kept so that diagnostics can quote lines.
struct SourceFile {
  std::string path;  // as given by the user (for messages)
  std::string text;  // whole contents

  // Returns the text of 1-based line `line`, without its newline.
  std::string line_text(int line) const;
};

// A place in a source file. line and col are 1-based; col counts bytes.
// A default-constructed location means "no location" (e.g. a command-line value).
struct SourceLocation {
  std::shared_ptr<const SourceFile> file;
  int line = 0;
  int col = 0;

  bool valid() const { return file != nullptr && line > 0; }
  // "path:line:col", or "path" if there is no line, or "<command line>".
  std::string to_string() const;
};

// Computes line/col for a byte offset into file->text.
SourceLocation location_at(std::shared_ptr<const SourceFile> file, std::size_t offset);

enum class Severity { Note, Warning, Error };

struct Diagnostic {
  Severity severity = Severity::Error;
  SourceLocation where;
  std::string message;
};

class Diagnostics {
 public:
  void error(const SourceLocation& where, std::string message);
  void warning(const SourceLocation& where, std::string message);
  void note(const SourceLocation& where, std::string message);

  bool has_errors() const { return error_count_ > 0; }
  int error_count() const { return error_count_; }
  int warning_count() const { return warning_count_; }
  const std::vector<Diagnostic>& all() const { return items_; }

  // When true, warnings are promoted to errors (strict mode).
  void set_warnings_as_errors(bool on) { warnings_as_errors_ = on; }

  // All diagnostics formatted with the quoted line and caret, in the order
  // they were reported, followed by a summary line if there were errors.
  std::string format() const;

 private:
  std::vector<Diagnostic> items_;
  int error_count_ = 0;
  int warning_count_ = 0;
  bool warnings_as_errors_ = false;
};

// Formats a single diagnostic (with quoted line and caret when it has a location).
std::string format_diagnostic(const Diagnostic& d);

}  // namespace pt
