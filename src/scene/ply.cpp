// PLY reader. The header is parsed into elements and typed properties; the
// body is read by one template over an ASCII or a binary value reader, so the
// element logic (roles of vertex properties, face lists, skipping) is written
// once. Every count is checked against the bytes that remain before anything
// is allocated, and every read is bounds-checked: hostile files produce an
// error message, never undefined behaviour.
#include "scene/ply.h"

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <optional>
#include <sstream>
#include <string_view>
#include <type_traits>
#include <utility>

#include "core/file_access.h"

namespace pt {

namespace {

enum class Format { Ascii, BinaryLittleEndian, BinaryBigEndian };
enum class Type { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

struct Property {
  std::string name;
  bool is_list = false;
  Type count_type = Type::UInt8;  // lists only
  Type type = Type::Float32;      // the value type (list items for lists)
};

struct Element {
  std::string name;
  uint64_t count = 0;
  int line = 0;
  std::vector<Property> properties;
};

struct Header {
  Format format = Format::Ascii;
  std::vector<Element> elements;
  std::size_t body_offset = 0;
};

std::optional<Type> parse_type(std::string_view s) {
  if (s == "char" || s == "int8") return Type::Int8;
  if (s == "uchar" || s == "uint8") return Type::UInt8;
  if (s == "short" || s == "int16") return Type::Int16;
  if (s == "ushort" || s == "uint16") return Type::UInt16;
  if (s == "int" || s == "int32") return Type::Int32;
  if (s == "uint" || s == "uint32") return Type::UInt32;
  if (s == "float" || s == "float32") return Type::Float32;
  if (s == "double" || s == "float64") return Type::Float64;
  return std::nullopt;
}

std::size_t type_size(Type t) {
  switch (t) {
    case Type::Int8:
    case Type::UInt8: return 1;
    case Type::Int16:
    case Type::UInt16: return 2;
    case Type::Int32:
    case Type::UInt32:
    case Type::Float32: return 4;
    case Type::Float64: return 8;
  }
  return 1;
}

bool is_integer(Type t) { return t != Type::Float32 && t != Type::Float64; }

std::vector<std::string_view> split_words(std::string_view line) {
  std::vector<std::string_view> words;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    const std::size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
    if (i > start) words.push_back(line.substr(start, i - start));
  }
  return words;
}

bool fail(PlyError& error, std::string message, int line = 0) {
  error.message = std::move(message);
  error.line = line;
  return false;
}

// ---------------------------------------------------------------- header
// "format <type> <version>"
bool parse_format_line(const std::vector<std::string_view>& w, int line_no, Header& h, PlyError& error) {
  if (w.size() != 3) return fail(error, "expected 'format <type> <version>'", line_no);
  if (w[1] == "ascii") {
    h.format = Format::Ascii;
  } else if (w[1] == "binary_little_endian") {
    h.format = Format::BinaryLittleEndian;
  } else if (w[1] == "binary_big_endian") {
    h.format = Format::BinaryBigEndian;
  } else {
    return fail(error, "unknown format '" + std::string(w[1]) + "'", line_no);
  }
  if (w[2] != "1.0") return fail(error, "unsupported PLY version '" + std::string(w[2]) + "'", line_no);
  return true;
}

// "element <name> <count>"
bool parse_element_line(const std::vector<std::string_view>& w, int line_no, Header& h, PlyError& error) {
  if (w.size() != 3) return fail(error, "expected 'element <name> <count>'", line_no);
  Element e;
  e.name = std::string(w[1]);
  e.line = line_no;
  const auto [end, ec] = std::from_chars(w[2].data(), w[2].data() + w[2].size(), e.count);
  if (ec != std::errc() || end != w[2].data() + w[2].size()) {
    return fail(error, "invalid element count '" + std::string(w[2]) + "'", line_no);
  }
  for (const Element& other : h.elements) {
    if (other.name == e.name) return fail(error, "element '" + e.name + "' is declared twice", line_no);
  }
  h.elements.push_back(std::move(e));
  return true;
}

// "property <type> <name>" or "property list <count type> <item type> <name>"
bool parse_property_line(const std::vector<std::string_view>& w, int line_no, Header& h, PlyError& error) {
  if (h.elements.empty()) return fail(error, "property before any element", line_no);
  Property p;
  if (w.size() >= 2 && w[1] == "list") {
    if (w.size() != 5) return fail(error, "expected 'property list <count type> <item type> <name>'", line_no);
    const auto ct = parse_type(w[2]);
    const auto it = parse_type(w[3]);
    if (!ct) return fail(error, "unknown type '" + std::string(w[2]) + "'", line_no);
    if (!it) return fail(error, "unknown type '" + std::string(w[3]) + "'", line_no);
    if (!is_integer(*ct)) return fail(error, "a list count must have an integer type", line_no);
    p.is_list = true;
    p.count_type = *ct;
    p.type = *it;
    p.name = std::string(w[4]);
  } else {
    if (w.size() != 3) return fail(error, "expected 'property <type> <name>'", line_no);
    const auto t = parse_type(w[1]);
    if (!t) return fail(error, "unknown type '" + std::string(w[1]) + "'", line_no);
    p.type = *t;
    p.name = std::string(w[2]);
  }
  h.elements.back().properties.push_back(std::move(p));
  return true;
}

bool parse_header(std::string_view bytes, Header& h, PlyError& error) {
  std::size_t pos = 0;
  int line_no = 0;
  bool have_format = false;
  for (;;) {
    if (pos >= bytes.size()) {
      if (line_no == 0) return fail(error, "not a PLY file: it is empty", 1);
      return fail(error, "the header has no end_header line", line_no);
    }
    std::size_t nl = bytes.find('\n', pos);
    if (nl == std::string_view::npos) nl = bytes.size();
    std::string_view line = bytes.substr(pos, nl - pos);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    pos = nl + 1;
    ++line_no;
    const std::vector<std::string_view> w = split_words(line);

    if (line_no == 1) {
      if (w.size() != 1 || w[0] != "ply") return fail(error, "not a PLY file: the first line must be 'ply'", 1);
      continue;
    }
    if (w.empty()) continue;
    const std::string_view key = w[0];
    if (key == "comment" || key == "obj_info") continue;
    if (key == "end_header") {
      if (!have_format) return fail(error, "the header has no format line", line_no);
      h.body_offset = std::min(pos, bytes.size());
      return true;
    }
    if (key == "format") {
      if (!parse_format_line(w, line_no, h, error)) return false;
      have_format = true;
      continue;
    }
    if (key == "element") {
      if (!parse_element_line(w, line_no, h, error)) return false;
      continue;
    }
    if (key == "property") {
      if (!parse_property_line(w, line_no, h, error)) return false;
      continue;
    }
    return fail(error, "unexpected header line '" + std::string(line) + "'", line_no);
  }
}

// The fewest bytes one instance of `e` can take in the body (lists empty).
std::size_t min_element_bytes(const Element& e, Format f) {
  std::size_t n = 0;
  for (const Property& p : e.properties) {
    // ASCII: at least one character and one separator per value.
    n += f == Format::Ascii ? 2 : type_size(p.is_list ? p.count_type : p.type);
  }
  return n;
}

// ---------------------------------------------------------------- value readers
class BinaryReader {
 public:
  BinaryReader(std::string_view body, bool swap) : p_(body.data()), end_(body.data() + body.size()), swap_(swap) {}

  std::size_t remaining() const { return static_cast<std::size_t>(end_ - p_); }
  std::string where() const { return {}; }

  bool read(Type t, double& out) {
    const std::size_t n = type_size(t);
    if (remaining() < n) return false;
    unsigned char b[8];
    std::memcpy(b, p_, n);
    p_ += n;
    if (swap_) {
      for (std::size_t i = 0; i < n / 2; ++i) std::swap(b[i], b[n - 1 - i]);
    }
    switch (t) {
      case Type::Int8: out = static_cast<int8_t>(b[0]); break;
      case Type::UInt8: out = b[0]; break;
      case Type::Int16: out = load<int16_t>(b); break;
      case Type::UInt16: out = load<uint16_t>(b); break;
      case Type::Int32: out = load<int32_t>(b); break;
      case Type::UInt32: out = load<uint32_t>(b); break;
      case Type::Float32: out = load<float>(b); break;
      case Type::Float64: out = load<double>(b); break;
    }
    return true;
  }

  bool skip(Type t, uint64_t count) {
    const std::size_t n = type_size(t);
    if (count > remaining() / n) return false;
    p_ += count * n;
    return true;
  }

  // The most list items that can still follow.
  uint64_t max_items(Type t) const { return remaining() / type_size(t); }

  bool swapped() const { return swap_; }
  // The next n bytes, consumed; nullptr (nothing consumed) if fewer remain.
  const char* take(std::size_t n) {
    if (remaining() < n) return nullptr;
    const char* p = p_;
    p_ += n;
    return p;
  }

 private:
  template <class T>
  static T load(const unsigned char* b) {
    T v;
    std::memcpy(&v, b, sizeof(T));
    return v;
  }

  const char* p_;
  const char* end_;
  bool swap_;
};

class AsciiReader {
 public:
  AsciiReader(std::string_view body, int first_line) : s_(body), line_(first_line) {}

  std::size_t remaining() const { return s_.size() - pos_; }
  std::string where() const { return " (line " + std::to_string(line_) + ")"; }

  // Reads one whitespace-separated number. Integer types accept only integers.
  bool read(Type t, double& out) {
    skip_space();
    const std::size_t start = pos_;
    while (pos_ < s_.size() && !is_space(s_[pos_])) ++pos_;
    if (pos_ == start) return false;
    std::string_view tok = s_.substr(start, pos_ - start);
    if (tok.front() == '+') tok.remove_prefix(1);
    const char* b = tok.data();
    const char* e = b + tok.size();
    if (is_integer(t)) {
      int64_t v = 0;
      const auto [end, ec] = std::from_chars(b, e, v);
      if (ec != std::errc() || end != e) return bad(tok);
      out = static_cast<double>(v);
    } else {
      const auto [end, ec] = std::from_chars(b, e, out);
      if (ec == std::errc::result_out_of_range) {
        out = std::numeric_limits<double>::infinity();  // reported as non-finite by the caller
      } else if (ec != std::errc() || end != e) {
        return bad(tok);
      }
    }
    return true;
  }

  bool skip(Type t, uint64_t count) {
    double unused;
    for (uint64_t i = 0; i < count; ++i) {
      if (!read(t, unused)) return false;
    }
    return true;
  }

  uint64_t max_items(Type) const { return remaining() / 2 + 1; }

  // Set when the last failed read found a malformed token (not the end of file).
  const std::string& bad_token() const { return bad_token_; }

 private:
  static bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v'; }
  void skip_space() {
    while (pos_ < s_.size() && is_space(s_[pos_])) {
      if (s_[pos_] == '\n') ++line_;
      ++pos_;
    }
  }
  bool bad(std::string_view tok) {
    bad_token_ = std::string(tok.substr(0, 40));
    return false;
  }

  std::string_view s_;
  std::size_t pos_ = 0;
  int line_;
  std::string bad_token_;
};

std::string read_failure(const BinaryReader&, const char* what, uint64_t index, uint64_t count) {
  return std::string("the file ends inside ") + what + " " + std::to_string(index) + " of " + std::to_string(count);
}

std::string read_failure(const AsciiReader& r, const char* what, uint64_t index, uint64_t count) {
  if (!r.bad_token().empty()) {
    return std::string(what) + " " + std::to_string(index) + ": '" + r.bad_token() + "' is not a valid number" +
           r.where();
  }
  return std::string("the file ends inside ") + what + " " + std::to_string(index) + " of " + std::to_string(count);
}

// ---------------------------------------------------------------- body
constexpr int kNoRole = -1;

// Vertex property roles: 0..2 position, 3..5 normal, 6..7 uv.
std::vector<int> vertex_roles(const Element& e, bool& has_normals, bool& has_uvs) {
  std::vector<int> roles(e.properties.size(), kNoRole);
  auto find = [&](std::string_view name) -> int {
    for (std::size_t i = 0; i < e.properties.size(); ++i) {
      if (!e.properties[i].is_list && e.properties[i].name == name) return static_cast<int>(i);
    }
    return kNoRole;
  };
  const int x = find("x"), y = find("y"), z = find("z");
  if (x != kNoRole) roles[x] = 0;
  if (y != kNoRole) roles[y] = 1;
  if (z != kNoRole) roles[z] = 2;
  const int nx = find("nx"), ny = find("ny"), nz = find("nz");
  has_normals = nx != kNoRole && ny != kNoRole && nz != kNoRole;
  if (has_normals) {
    roles[nx] = 3;
    roles[ny] = 4;
    roles[nz] = 5;
  }
  has_uvs = false;
  for (const auto& [un, vn] : {std::pair{"u", "v"}, std::pair{"s", "t"}, std::pair{"texture_u", "texture_v"},
                               std::pair{"texture_s", "texture_t"}}) {
    const int u = find(un), v = find(vn);
    if (u != kNoRole && v != kNoRole) {
      roles[u] = 6;
      roles[v] = 7;
      has_uvs = true;
      break;
    }
  }
  return roles;
}

// Vertex i from its values by role (0..2 position, 3..5 normal, 6..7 uv) into
// the mesh's arrays (normals and uvs only where the mesh has them); false if
// the position is not finite.
inline bool store_vertex(const float v[8], uint64_t i, TriangleMesh& out) {
  const Vec3f pos{v[0], v[1], v[2]};
  if (!is_finite(pos)) return false;
  out.positions[i] = pos;
  if (!out.normals.empty()) {
    const Vec3f n{v[3], v[4], v[5]};
    out.normals[i] = is_finite(n) ? n : Vec3f(0.0f);  // a zero normal falls back to the geometric one
  }
  if (!out.uvs.empty()) {
    const Vec2f uv{v[6], v[7]};
    out.uvs[i] = (std::isfinite(uv.x) && std::isfinite(uv.y)) ? uv : Vec2f{};
  }
  return true;
}

bool all_float32(const Element& e) {
  return std::all_of(e.properties.begin(), e.properties.end(),
                     [](const Property& p) { return !p.is_list && p.type == Type::Float32; });
}

// The common binary layout (every vertex property a float, the host's byte
// order: the 10M-triangle benchmark's, docs/bench/scale.md): each vertex read
// from its fixed-size record at once rather than value by value, with the same
// results and messages.
bool read_float_vertices(BinaryReader& r, const Element& e, const std::vector<int>& roles, TriangleMesh& out,
                         PlyError& error) {
  const std::size_t stride = 4 * e.properties.size();
  std::size_t offset[8] = {};
  bool used[8] = {};
  for (std::size_t k = 0; k < roles.size(); ++k) {
    if (roles[k] == kNoRole) continue;
    offset[roles[k]] = 4 * k;
    used[roles[k]] = true;
  }
  const bool extra = !out.normals.empty() || !out.uvs.empty();
  const char* records = r.take(stride * e.count);
  if (records == nullptr) {  // as the value-by-value reader reports it: the first vertex the file cuts
    return fail(error, read_failure(r, "vertex", r.remaining() / stride, e.count));
  }
  float v[8] = {};
  for (uint64_t i = 0; i < e.count; ++i) {
    const char* record = records + i * stride;
    for (int k = 0; k < 3; ++k) std::memcpy(&v[k], record + offset[k], 4);
    if (extra) {
      for (int k = 3; k < 8; ++k) {
        if (used[k]) std::memcpy(&v[k], record + offset[k], 4);
      }
    }
    if (!store_vertex(v, i, out)) return fail(error, "vertex " + std::to_string(i) + " has a non-finite position");
  }
  return true;
}

template <class Reader>
bool read_vertices(Reader& r, const Element& e, TriangleMesh& out, PlyError& error) {
  bool has_normals = false, has_uvs = false;
  const std::vector<int> roles = vertex_roles(e, has_normals, has_uvs);
  for (int axis = 0; axis < 3; ++axis) {
    if (std::find(roles.begin(), roles.end(), axis) == roles.end()) {
      return fail(error, std::string("the vertex element has no '") + "xyz"[axis] + "' property", e.line);
    }
  }
  // Counts were checked against the file size: these allocations are bounded.
  // One spare position: the Embree backend can then share the buffer (it reads
  // 16 bytes for the last vertex) instead of copying it.
  out.positions.reserve(e.count + 1);
  out.positions.resize(e.count);
  if (has_normals) out.normals.resize(e.count);
  if (has_uvs) out.uvs.resize(e.count);
  if constexpr (std::is_same_v<Reader, BinaryReader>) {
    if (all_float32(e) && !r.swapped()) return read_float_vertices(r, e, roles, out, error);
  }
  double v[8] = {};
  for (uint64_t i = 0; i < e.count; ++i) {
    for (std::size_t k = 0; k < e.properties.size(); ++k) {
      const Property& p = e.properties[k];
      if (p.is_list) {
        double n = 0;
        if (!r.read(p.count_type, n) || n < 0 || !r.skip(p.type, static_cast<uint64_t>(n))) {
          return fail(error, read_failure(r, "vertex", i, e.count));
        }
        continue;
      }
      double value = 0;
      if (!r.read(p.type, value)) return fail(error, read_failure(r, "vertex", i, e.count));
      if (roles[k] != kNoRole) v[roles[k]] = value;
    }
    float f[8];
    for (int k = 0; k < 8; ++k) f[k] = static_cast<float>(v[k]);
    if (!store_vertex(f, i, out)) {
      return fail(error, "vertex " + std::to_string(i) + " has a non-finite position" + r.where());
    }
  }
  return true;
}

std::string bad_index(uint64_t face, int64_t index, uint64_t vertex_count) {
  return "face " + std::to_string(face) + " refers to vertex " + std::to_string(index) + " but there are only " +
         std::to_string(vertex_count) + " vertices";
}

// Fan triangulation; faces with fewer than three vertices add nothing.
void add_fan(const uint32_t* polygon, std::size_t n, TriangleMesh& out) {
  for (std::size_t j = 1; j + 1 < n; ++j) {
    out.indices.push_back(polygon[0]);
    out.indices.push_back(polygon[j]);
    out.indices.push_back(polygon[j + 1]);
  }
}

// The common binary face layout (one list property, a uchar count and 32-bit
// indices, the host's byte order): triangles are read three indices at once
// and written straight into the index array, other polygons fanned; the same
// results and messages as the value-by-value reader.
bool read_int_faces(BinaryReader& r, const Element& e, bool is_signed, uint64_t vertex_count, TriangleMesh& out,
                    PlyError& error) {
  std::vector<uint32_t>& indices = out.indices;
  std::size_t w = indices.size();
  indices.resize(w + 3 * e.count);  // one triangle a face; grown for larger polygons
  // A signed index below 0 is, as unsigned, above any vertex count (< 2^32).
  const uint64_t limit = is_signed ? std::min<uint64_t>(vertex_count, 0x80000000u) : vertex_count;
  auto check = [&](uint64_t face, const uint32_t* polygon, std::size_t n) {
    for (std::size_t j = 0; j < n; ++j) {
      if (polygon[j] >= limit) {
        const int64_t index = is_signed ? static_cast<int64_t>(static_cast<int32_t>(polygon[j])) : polygon[j];
        return fail(error, bad_index(face, index, vertex_count));
      }
    }
    return true;
  };
  uint32_t polygon[256];
  for (uint64_t i = 0; i < e.count; ++i) {
    const char* count = r.take(1);
    const std::size_t n = count != nullptr ? static_cast<unsigned char>(*count) : 0;
    const char* items = count != nullptr ? r.take(4 * n) : nullptr;
    if (items == nullptr) return fail(error, read_failure(r, "face", i, e.count));
    if (n == 3) {
      std::memcpy(polygon, items, 12);
      if (!check(i, polygon, 3)) return false;
      std::memcpy(&indices[w], polygon, 12);
      w += 3;
      continue;
    }
    std::memcpy(polygon, items, 4 * n);
    if (!check(i, polygon, n)) return false;
    const std::size_t need = n >= 3 ? 3 * (n - 2) : 0;
    if (w + need > indices.size()) indices.resize(std::max(2 * indices.size(), w + need));
    for (std::size_t j = 1; j + 1 < n; ++j, w += 3) {
      indices[w] = polygon[0];
      indices[w + 1] = polygon[j];
      indices[w + 2] = polygon[j + 1];
    }
  }
  indices.resize(w);
  return true;
}

template <class Reader>
bool read_faces(Reader& r, const Element& e, uint64_t vertex_count, TriangleMesh& out, PlyError& error) {
  int list = kNoRole;
  for (std::size_t k = 0; k < e.properties.size(); ++k) {
    const Property& p = e.properties[k];
    if (p.name == "vertex_indices" || p.name == "vertex_index") {
      if (!p.is_list) return fail(error, "'" + p.name + "' must be a list property", e.line);
      if (!is_integer(p.type)) return fail(error, "'" + p.name + "' must have an integer item type", e.line);
      list = static_cast<int>(k);
      break;
    }
  }
  if (list == kNoRole) return fail(error, "the face element has no 'vertex_indices' list", e.line);
  out.indices.reserve(3 * e.count);  // bounded: e.count was checked against the file size
  if constexpr (std::is_same_v<Reader, BinaryReader>) {
    const Property& p = e.properties[static_cast<std::size_t>(list)];
    if (e.properties.size() == 1 && !r.swapped() && p.count_type == Type::UInt8 &&
        (p.type == Type::Int32 || p.type == Type::UInt32)) {
      return read_int_faces(r, e, p.type == Type::Int32, vertex_count, out, error);
    }
  }
  std::vector<uint32_t> polygon;
  for (uint64_t i = 0; i < e.count; ++i) {
    for (std::size_t k = 0; k < e.properties.size(); ++k) {
      const Property& p = e.properties[k];
      double n = 0;
      if (!r.read(p.is_list ? p.count_type : p.type, n)) return fail(error, read_failure(r, "face", i, e.count));
      if (!p.is_list) continue;
      if (n < 0) return fail(error, "face " + std::to_string(i) + ": negative list length" + r.where());
      const auto count = static_cast<uint64_t>(n);
      if (count > r.max_items(p.type)) return fail(error, read_failure(r, "face", i, e.count));
      if (static_cast<int>(k) != list) {
        if (!r.skip(p.type, count)) return fail(error, read_failure(r, "face", i, e.count));
        continue;
      }
      polygon.clear();
      for (uint64_t j = 0; j < count; ++j) {
        double idx = 0;
        if (!r.read(p.type, idx)) return fail(error, read_failure(r, "face", i, e.count));
        if (idx < 0 || idx >= static_cast<double>(vertex_count)) {
          return fail(error, bad_index(i, static_cast<int64_t>(idx), vertex_count) + r.where());
        }
        polygon.push_back(static_cast<uint32_t>(idx));
      }
      add_fan(polygon.data(), polygon.size(), out);
    }
  }
  return true;
}

template <class Reader>
bool read_body(Reader& r, const Header& h, TriangleMesh& out, PlyError& error) {
  uint64_t vertex_count = 0;
  for (const Element& e : h.elements) {
    if (e.name == "vertex") vertex_count = e.count;
  }
  for (const Element& e : h.elements) {
    if (e.name == "vertex") {
      if (!read_vertices(r, e, out, error)) return false;
    } else if (e.name == "face") {
      if (!read_faces(r, e, vertex_count, out, error)) return false;
    } else if (!e.properties.empty()) {
      for (uint64_t i = 0; i < e.count; ++i) {
        for (const Property& p : e.properties) {
          double n = 0;
          if (!r.read(p.is_list ? p.count_type : p.type, n)) {
            return fail(error, read_failure(r, e.name.c_str(), i, e.count));
          }
          if (p.is_list && (n < 0 || !r.skip(p.type, static_cast<uint64_t>(n)))) {
            return fail(error, read_failure(r, e.name.c_str(), i, e.count));
          }
        }
      }
    }
  }
  return true;
}

}  // namespace

bool parse_ply(const std::string& bytes, TriangleMesh& out, PlyError& error) {
  out = TriangleMesh{};
  error = PlyError{};
  Header h;
  if (!parse_header(bytes, h, error)) return false;

  bool has_vertex = false, has_face = false;
  for (const Element& e : h.elements) {
    has_vertex = has_vertex || e.name == "vertex";
    has_face = has_face || e.name == "face";
  }
  if (!has_vertex) return fail(error, "the header declares no vertex element");
  if (!has_face) return fail(error, "the header declares no face element (point clouds cannot be rendered)");

  // Refuse counts the remaining bytes cannot hold, before allocating anything.
  const std::size_t body = bytes.size() - h.body_offset;
  const std::size_t budget = h.format == Format::Ascii ? body + 1 : body;
  std::size_t needed = 0;
  for (const Element& e : h.elements) {
    const std::size_t per = min_element_bytes(e, h.format);
    if (per == 0) continue;
    if (e.count > (budget - std::min(needed, budget)) / per) {
      return fail(error,
                  "the header declares " + std::to_string(e.count) + " " + e.name + " elements but only " +
                      std::to_string(body) + " bytes of data follow",
                  e.line);
    }
    needed += static_cast<std::size_t>(e.count) * per;
    if (e.name == "vertex" && e.count > std::numeric_limits<uint32_t>::max()) {
      return fail(error, "too many vertices for 32-bit indices", e.line);
    }
  }

  const std::string_view rest(bytes.data() + h.body_offset, body);
  if (h.format == Format::Ascii) {
    int header_lines = 0;
    for (std::size_t i = 0; i < h.body_offset; ++i) header_lines += bytes[i] == '\n';
    AsciiReader reader(rest, header_lines + 1);
    return read_body(reader, h, out, error);
  }
  const bool file_little = h.format == Format::BinaryLittleEndian;
  const bool host_little = std::endian::native == std::endian::little;
  BinaryReader reader(rest, file_little != host_little);
  return read_body(reader, h, out, error);
}

bool load_ply(const std::string& path, TriangleMesh& out, PlyError& error) {
  if (const std::string why = why_unreadable(path); !why.empty())
    return fail(error, "cannot open '" + path + "': " + why);
  std::ifstream in(path, std::ios::binary);
  if (!in) return fail(error, "cannot open '" + path + "'");
  // One buffer of the file's size (a large mesh's file is its largest
  // allocation while it loads); a stream without a size (a pipe) is read whole.
  std::string bytes;
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::is_regular_file(path, ec) ? std::filesystem::file_size(path, ec) : 0;
  if (!ec && size > 0) {
    bytes.resize(size);
    in.read(bytes.data(), static_cast<std::streamsize>(size));
    bytes.resize(static_cast<std::size_t>(in.gcount()));
  } else {
    std::ostringstream ss;
    ss << in.rdbuf();
    bytes = std::move(ss).str();
  }
  if (in.bad()) return fail(error, "cannot read '" + path + "'");
  return parse_ply(bytes, out, error);
}

}  // namespace pt
