#include "scene/mtl.h"

#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <string_view>
#include <system_error>

#include "core/file_access.h"

namespace pt {
namespace {

struct Token {
  std::string_view text;
  std::size_t offset = 0;  // in the file
};

// What we do with a statement: one of ours, or one we report and skip.
enum class Kind { Newmtl, Colour, Number, Illum, Map, Unsupported, Unknown };

struct Statement {
  const char* name;
  Kind kind;
  const char* what;  // for messages
};

constexpr Statement kStatements[] = {
    {"newmtl", Kind::Newmtl, "material"},
    {"Kd", Kind::Colour, "diffuse colour"},
    {"Ks", Kind::Colour, "specular colour"},
    {"Ke", Kind::Colour, "emission"},
    {"Tf", Kind::Colour, "transmission filter"},
    {"Ns", Kind::Number, "specular exponent"},
    {"Ni", Kind::Number, "index of refraction"},
    {"d", Kind::Number, "dissolve (opacity)"},
    {"Tr", Kind::Number, "transparency"},
    {"illum", Kind::Illum, "illumination model"},
    {"map_Kd", Kind::Map, "diffuse texture"},
    {"map_Ks", Kind::Map, "specular texture"},
    {"map_Ns", Kind::Map, "specular exponent texture"},
    {"map_Ke", Kind::Map, "emission texture"},
    {"map_d", Kind::Map, "alpha texture"},
    {"map_bump", Kind::Map, "bump map"},
    {"bump", Kind::Map, "bump map"},
    {"norm", Kind::Map, "normal map"},
    {"map_norm", Kind::Map, "normal map"},
    {"Ka", Kind::Unsupported, "ambient colour"},
    {"map_Ka", Kind::Unsupported, "ambient texture"},
    {"refl", Kind::Unsupported, "reflection map"},
    {"map_refl", Kind::Unsupported, "reflection map"},
    {"disp", Kind::Unsupported, "displacement map"},
    {"decal", Kind::Unsupported, "decal texture"},
    {"sharpness", Kind::Unsupported, "reflection sharpness"},
    {"Km", Kind::Unsupported, "bump multiplier"},
    {"Pr", Kind::Unsupported, "PBR roughness"},
    {"Pm", Kind::Unsupported, "PBR metallic"},
    {"Ps", Kind::Unsupported, "PBR sheen"},
    {"Pc", Kind::Unsupported, "PBR clearcoat"},
    {"Pcr", Kind::Unsupported, "PBR clearcoat roughness"},
    {"aniso", Kind::Unsupported, "PBR anisotropy"},
    {"anisor", Kind::Unsupported, "PBR anisotropy rotation"},
    {"map_Pr", Kind::Unsupported, "PBR roughness texture"},
    {"map_Pm", Kind::Unsupported, "PBR metallic texture"},
    {"map_Ps", Kind::Unsupported, "PBR sheen texture"},
};

bool same_keyword(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (std::tolower(static_cast<unsigned char>(a[i])) != std::tolower(static_cast<unsigned char>(b[i]))) return false;
  }
  return true;
}

// Keywords are matched without regard to case ("map_Bump" is "map_bump").
const Statement* find_statement(std::string_view keyword) {
  for (const Statement& s : kStatements)
    if (same_keyword(s.name, keyword)) return &s;
  return nullptr;
}

// The text of `line` from token i on, without trailing blanks (MTL names
// and file names may hold spaces).
std::string rest_of_line(std::string_view line, const std::vector<Token>& t, std::size_t i) {
  const std::size_t line_start = t[0].offset - static_cast<std::size_t>(t[0].text.data() - line.data());
  std::string s(line.substr(t[i].offset - line_start));
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.pop_back();
  return s;
}

bool parse_float(std::string_view text, float& out) {
  const std::string s(text);
  char* end = nullptr;
  const float v = std::strtof(s.c_str(), &end);
  if (end != s.c_str() + s.size() || !std::isfinite(v)) return false;
  out = v;
  return true;
}

// The number of values each texture option takes (MTL spec; -o, -s and -t
// take one to three numbers).
int option_arguments(std::string_view option) {
  static const std::map<std::string_view, int> kOptions = {
      {"-blendu", 1}, {"-blendv", 1}, {"-boost", 1}, {"-cc", 1}, {"-clamp", 1}, {"-imfchan", 1}, {"-mm", 2},
      {"-o", 3},      {"-s", 3},      {"-t", 3},     {"-texres", 1}, {"-type", 1}, {"-bm", 1}};
  const auto it = kOptions.find(option);
  return it == kOptions.end() ? -1 : it->second;
}

// Reads one file: its statements, and the warnings it collects (each kind
// once, with its count, emitted by finish()).
class MtlReader {
 public:
  MtlReader(std::shared_ptr<const SourceFile> file, std::vector<AssetMaterial>& materials, AssetTextureTable& textures,
            Diagnostics& diag)
      : file_(std::move(file)), materials_(materials), textures_(textures), diag_(diag),
        dir_(std::filesystem::path(file_->path).parent_path().string()) {}

  void read();

 private:
  struct Pending {
    SourceLocation where;
    std::string message;
    int count = 0;
  };
  SourceLocation at(std::size_t offset) const { return location_at(file_, offset); }
  void warn_once(const std::string& key, std::size_t offset, const std::string& message) {
    Pending& p = pending_[key];
    if (p.count++ == 0) {
      p.where = at(offset);
      p.message = message;
      order_.push_back(key);
    }
  }
  void statement(const std::vector<Token>& tokens, const std::string_view line);
  void colour(const Statement& s, const std::vector<Token>& t, AssetMaterial& m);
  void number(const Statement& s, const std::vector<Token>& t, AssetMaterial& m);
  void map(const Statement& s, const std::vector<Token>& t, std::string_view line, AssetMaterial& m);
  void finish();

  std::shared_ptr<const SourceFile> file_;
  std::vector<AssetMaterial>& materials_;
  AssetTextureTable& textures_;
  Diagnostics& diag_;
  std::string dir_;
  AssetMaterial* current_ = nullptr;
  std::map<std::string, Pending> pending_;
  std::vector<std::string> order_;
};

void MtlReader::read() {
  const std::string& text = file_->text;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    std::string_view line(text.data() + start, end - start);
    if (const std::size_t hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
    std::vector<Token> tokens;
    for (std::size_t i = 0; i < line.size();) {
      while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
      const std::size_t b = i;
      while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i]))) ++i;
      if (i > b) tokens.push_back({line.substr(b, i - b), start + b});
    }
    if (!tokens.empty()) statement(tokens, line);
    start = end + 1;
  }
  finish();
}

void MtlReader::statement(const std::vector<Token>& t, const std::string_view line) {
  const Statement* s = find_statement(t[0].text);
  const std::string keyword(t[0].text);
  if (s == nullptr) {
    warn_once("?" + keyword, t[0].offset, "unknown MTL statement '" + keyword + "'; ignored");
    return;
  }
  if (s->kind == Kind::Unsupported) {
    warn_once(s->name, t[0].offset, std::string("'") + s->name + "' (" + s->what + ") is not supported; ignored");
    return;
  }
  if (s->kind == Kind::Newmtl) {
    AssetMaterial m;
    if (t.size() > 1) m.name = rest_of_line(line, t, 1);
    m.where = at(t[0].offset);
    m.model = AssetMaterial::Model::Phong;
    materials_.push_back(std::move(m));
    current_ = &materials_.back();
    return;
  }
  if (current_ == nullptr) {
    warn_once("(outside)", t[0].offset, "statement before any 'newmtl'; ignored");
    return;
  }
  switch (s->kind) {
    case Kind::Colour: colour(*s, t, *current_); break;
    case Kind::Number: number(*s, t, *current_); break;
    case Kind::Map: map(*s, t, line, *current_); break;
    default: {  // illum
      float v = 0;
      if (t.size() != 2 || !parse_float(t[1].text, v) || v != static_cast<float>(static_cast<int>(v)) || v < 0 || v > 10)
        warn_once("illum?", t[0].offset, "'illum' takes an integer from 0 to 10; the statement is ignored");
      else
        current_->illum = static_cast<int>(v);
    }
  }
}

void MtlReader::colour(const Statement& s, const std::vector<Token>& t, AssetMaterial& m) {
  float c[3] = {0, 0, 0};
  const bool ok = (t.size() == 2 || t.size() == 4) && parse_float(t[1].text, c[0]) &&
                  (t.size() == 2 || (parse_float(t[2].text, c[1]) && parse_float(t[3].text, c[2])));
  if (!ok) {
    warn_once(std::string(s.name) + "?", t[0].offset,
              std::string("'") + s.name + "' takes r g b (or one grey value); other forms (spectral, xyz) are not "
                                          "supported; the statement is ignored");
    return;
  }
  const RGB v = t.size() == 2 ? RGB(c[0]) : RGB(c[0], c[1], c[2]);
  const std::string_view n = s.name;
  if (n == "Kd") m.diffuse = v;
  if (n == "Ks") m.specular = v;
  if (n == "Ke") m.emission = v;
  if (n == "Tf") m.transmission_filter = v;
}

void MtlReader::number(const Statement& s, const std::vector<Token>& t, AssetMaterial& m) {
  float v = 0;
  if (t.size() < 2 || !parse_float(t.back().text, v)) {
    warn_once(std::string(s.name) + "?", t[0].offset,
              std::string("'") + s.name + "' (" + s.what + ") takes a number; the statement is ignored");
    return;
  }
  const std::string_view n = s.name;
  if (n == "Ns") m.shininess = v;
  if (n == "Ni") m.ior = v;
  if (n == "d" || n == "Tr") {  // "d -halo 0.5": the last token is the value
    m.opacity = n == "d" ? v : 1.0f - v;
    m.opacity_where = at(t[0].offset);
  }
}

void MtlReader::map(const Statement& s, const std::vector<Token>& t, std::string_view line, AssetMaterial& m) {
  std::size_t i = 1;
  bool transformed = false;
  float bm = 1.0f;
  while (i < t.size() && t[i].text.size() > 1 && t[i].text[0] == '-') {
    const int n = option_arguments(t[i].text);
    const std::string option(t[i].text);
    if (n < 0) break;  // a file name that starts with '-'
    if (option == "-o" || option == "-s") transformed = true;
    const bool bump = s.name == std::string_view("map_bump") || s.name == std::string_view("bump");
    if (option == "-bm" && (!bump || i + 1 >= t.size() || !parse_float(t[i + 1].text, bm)))
      warn_once("option -bm", t[i].offset, "texture option '-bm' takes a number and applies to bump maps only; ignored");
    if (option != "-bm" && option != "-o" && option != "-s")
      warn_once("option " + option, t[i].offset, "texture option '" + option + "' is not supported; ignored");
    ++i;
    for (int k = 0; k < n && i < t.size(); ++k) {
      float v = 0;
      if (k > 0 && !parse_float(t[i].text, v)) break;  // -o/-s/-t take one to three numbers
      ++i;
    }
  }
  if (i >= t.size()) {
    warn_once(std::string(s.name) + "?", t[0].offset, std::string("'") + s.name + "' names no file; ignored");
    return;
  }
  const std::string name = rest_of_line(line, t, i);
  AssetTextureRef ref;
  ref.where = at(t[i].offset);
  ref.transformed = transformed;
  ref.scale = bm;
  ref.texture = textures_.file(name, ref.where, dir_);
  const std::string_view n = s.name;
  if (n == "map_Kd") m.diffuse_map = ref;
  if (n == "map_Ks") m.specular_map = ref;
  if (n == "map_Ns") m.shininess_map = ref;
  if (n == "map_Ke") m.emission_map = ref;
  if (n == "map_d") m.opacity_map = ref;
  if (n == "map_bump" || n == "bump") m.bump_map = ref;
  if (n == "norm" || n == "map_norm") m.normal_map = ref;
}

void MtlReader::finish() {
  for (const std::string& key : order_) {
    const Pending& p = pending_[key];
    diag_.warning(p.where, p.message + (p.count > 1 ? " (" + std::to_string(p.count) + " statements)" : ""));
  }
}

}  // namespace

bool read_mtl(const std::string& path, std::vector<AssetMaterial>& materials, AssetTextureTable& textures,
              Diagnostics& diag, std::string& error) {
  if (const std::string why = why_unreadable(path); !why.empty()) {
    error = why;
    return false;
  }
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec || size > kMaxMtlFileBytes) {
    error = ec ? ec.message() : "the file is larger than " + std::to_string(kMaxMtlFileBytes >> 20) + " MiB";
    return false;
  }
  std::ifstream in(path, std::ios::binary);
  std::string text(static_cast<std::size_t>(size), '\0');
  in.read(text.data(), static_cast<std::streamsize>(size));
  text.resize(static_cast<std::size_t>(in.gcount()));
  MtlReader(std::make_shared<const SourceFile>(SourceFile{path, std::move(text)}), materials, textures, diag).read();
  return true;
}

}  // namespace pt
