// The streaming OBJ reader (obj_reader.h): ObjParser takes one statement at a
// time from LineReader (a fixed buffer over the file) and writes faces
// straight into the current mesh.
#include "scene/obj_reader.h"

#include <algorithm>
#include <array>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <map>
#include <memory>
#include <string_view>
#include <system_error>

#include "core/file_access.h"
#include "core/math.h"

namespace pt {
namespace {

constexpr uint32_t kNone = std::numeric_limits<uint32_t>::max();  // a corner without vt or vn

// Lines of a file through a buffer that grows only for a line longer than it.
class LineReader {
 public:
  explicit LineReader(std::FILE* f) : f_(f), buf_(std::size_t{1} << 20) {}
  // The next line without its end ("\n", "\r\n"); false at the end of the file.
  bool next(std::string_view& line) {
    std::size_t nl;
    while ((nl = find_newline()) == kNotFound) {
      if (eof_) {
        if (begin_ == end_) return false;
        nl = end_;
        break;
      }
      refill();
    }
    line = std::string_view(buf_.data() + begin_, nl - begin_);
    begin_ = nl < end_ ? nl + 1 : nl;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    ++number_;
    return true;
  }
  int number() const { return number_; }  // of the line last returned, 1-based
  bool failed() const { return std::ferror(f_) != 0; }

 private:
  static constexpr std::size_t kNotFound = std::numeric_limits<std::size_t>::max();
  std::size_t find_newline() const {
    for (std::size_t i = scanned_ > begin_ ? scanned_ : begin_; i < end_; ++i)
      if (buf_[i] == '\n') return i;
    return kNotFound;
  }
  void refill() {
    // Keep the partial line, at the start of the buffer, and read after it.
    std::copy(buf_.begin() + static_cast<std::ptrdiff_t>(begin_), buf_.begin() + static_cast<std::ptrdiff_t>(end_),
              buf_.begin());
    end_ -= begin_;
    begin_ = 0;
    scanned_ = end_;
    if (end_ == buf_.size()) buf_.resize(2 * buf_.size());
    const std::size_t n = std::fread(buf_.data() + end_, 1, buf_.size() - end_, f_);
    end_ += n;
    if (n == 0) eof_ = true;
  }
  std::FILE* f_;
  std::vector<char> buf_;
  std::size_t begin_ = 0, end_ = 0, scanned_ = 0;
  bool eof_ = false;
  int number_ = 0;
};

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\v' || c == '\f'; }

// The next whitespace-separated token of `line` from `pos` (empty at the end).
std::string_view next_token(std::string_view line, std::size_t& pos) {
  while (pos < line.size() && is_space(line[pos])) ++pos;
  const std::size_t start = pos;
  while (pos < line.size() && !is_space(line[pos])) ++pos;
  return line.substr(start, pos - start);
}

// 'token', for messages.
std::string quoted(std::string_view token) { return std::string("'").append(token).append("'"); }

std::string_view trimmed(std::string_view s) {
  while (!s.empty() && is_space(s.front())) s.remove_prefix(1);
  while (!s.empty() && is_space(s.back())) s.remove_suffix(1);
  return s;
}

bool parse_float(std::string_view t, float& out) {
  if (!t.empty() && t.front() == '+') t.remove_prefix(1);
  const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), out);
  return ec == std::errc() && end == t.data() + t.size();
}

// A quad's corner to split it from: its concave corner if it has one (the
// angles beside the diagonal from it add up to more than pi), as Assimp 5.2's
// triangulation; else the first.
int quad_start(const std::array<Vec3f, 4>& p) {
  for (int i = 0; i < 4; ++i) {
    const Vec3f v = p[static_cast<std::size_t>(i)];
    const Vec3f left = normalize(p[static_cast<std::size_t>((i + 3) % 4)] - v);
    const Vec3f diag = normalize(p[static_cast<std::size_t>((i + 2) % 4)] - v);
    const Vec3f right = normalize(p[static_cast<std::size_t>((i + 1) % 4)] - v);
    const float angle = std::acos(dot(left, diag)) + std::acos(dot(right, diag));
    if (angle > 3.14159265358979f) return i;
  }
  return 0;
}

// Statements we recognise but do not read: free-form geometry and rendering
// attributes (warned once per keyword).
constexpr const char* kUnsupported[] = {"vp",   "cstype", "deg",   "bmat",       "step",       "curv",
                                        "curv2", "surf",  "parm",  "trim",       "hole",       "scrv",
                                        "sp",   "end",    "con",   "mg",         "bevel",      "c_interp",
                                        "d_interp", "lod", "maplib", "usemap",   "shadow_obj", "trace_obj",
                                        "ctech", "stech", "call",  "csh"};

// `v` moved into an array of exactly its size plus `spare` elements: the
// doubling growth of reading leaves up to half of each array unused.
template <typename T>
void fit(std::vector<T>& v, std::size_t spare) {
  if (v.capacity() == v.size() + spare) return;
  std::vector<T> exact;
  exact.reserve(v.size() + spare);
  exact.assign(v.begin(), v.end());
  v.swap(exact);
}

class ObjParser {
 public:
  ObjParser(const std::string& path, const ObjReadOptions& options, ObjModel& out, Diagnostics& diag)
      : path_(path), options_(options), out_(out), diag_(diag) {
    out_ = ObjModel{};
    out_.materials.emplace_back(kObjDefaultMaterial);
    if (options_.one_mesh) out_.meshes.emplace_back();
  }

  // One line; false after reporting an error.
  bool statement(std::string_view line, int number) {
    line_ = line;
    number_ = number;
    std::size_t pos = 0;
    const std::string_view key = next_token(line, pos);
    if (key.empty() || key.front() == '#') return true;
    key_col_ = col_of(key);
    if (key == "v") return vertex(pos);
    if (key == "vt") return tex_coord(pos);
    if (key == "vn") return normal(pos);
    if (key == "f") return face(pos);
    if (key == "l" || key == "p") return points_or_lines(pos, key == "l");
    if (key == "o") return object(next_token(line, pos));
    if (key == "g") return group(trimmed(line.substr(pos)));
    if (key == "usemtl") return use_material(trimmed(line.substr(pos)));
    if (key == "mtllib") return material_library(trimmed(line.substr(pos)), pos);
    if (key == "s") return true;  // smoothing groups: normals come from vn (as Assimp)
    note_skipped(key);
    return true;
  }

  bool finish();

 private:
  // The file is never held whole: a diagnostic's SourceFile holds its one
  // line, after as many empty lines as precede it (up to kMaxQuotedLine; a
  // problem further down is reported at its line and column, unquoted).
  SourceLocation at(std::size_t col0) const {
    auto file = std::make_shared<SourceFile>();
    file->path = path_;
    if (number_ <= kMaxQuotedLine) file->text = std::string(static_cast<std::size_t>(number_ - 1), '\n').append(line_);
    return SourceLocation{std::move(file), number_, static_cast<int>(col0) + 1};
  }
  static constexpr int kMaxQuotedLine = 1 << 20;
  bool fail(std::size_t col0, const std::string& message) {
    diag_.error(at(col0), message);
    return false;
  }
  std::size_t col_of(std::string_view token) const { return static_cast<std::size_t>(token.data() - line_.data()); }

  // Up to `max` numbers after the keyword, into `v`; their count in `n`.
  bool numbers(std::size_t pos, float* v, int max, int& n, std::string_view what);
  bool vertex(std::size_t pos);
  bool tex_coord(std::size_t pos);
  bool normal(std::size_t pos);
  bool corner(std::string_view token, std::array<uint32_t, 3>& key);
  bool index(std::string_view field, std::size_t col0, std::size_t count, const char* what, uint32_t& out);
  bool face(std::size_t pos);
  bool points_or_lines(std::size_t pos, bool lines);
  bool object(std::string_view name);
  bool group(std::string_view name);
  bool use_material(std::string_view name);
  bool material_library(std::string_view name, std::size_t pos);
  void note_skipped(std::string_view key);

  void new_object(const std::string& name);
  void new_mesh(const std::string& name);
  void ensure_mesh();
  uint32_t vertex_of(const std::array<uint32_t, 3>& key);
  void add_triangle(uint32_t a, uint32_t b, uint32_t c) {
    std::vector<uint32_t>& idx = mesh().indices;
    idx.push_back(a);
    idx.push_back(b);
    idx.push_back(c);
  }
  TriangleMesh& mesh() { return out_.meshes[static_cast<std::size_t>(current_mesh_)].mesh; }
  void end_run();

  const std::string& path_;
  const ObjReadOptions& options_;
  ObjModel& out_;
  Diagnostics& diag_;
  std::string_view line_;
  int number_ = 0;
  std::size_t key_col_ = 0;  // of the statement's keyword

  std::vector<Vec3f> v_, vn_;
  std::vector<Vec2f> vt_;  // flipped: v from the image's top

  int current_object_ = -1, current_mesh_ = -1, current_material_ = -1;
  bool mesh_has_material_ = false;  // Assimp's "NoMaterial" until a material is set
  uint64_t mesh_faces_ = 0;         // faces in the current run
  bool run_normals_ = false, run_uvs_ = false;  // one_mesh: the current run names vn / vt
  bool all_normals_ = true, all_uvs_ = true;    // one_mesh: every run so far did
  std::string active_group_;
  std::map<std::string, int, std::less<>> material_ids_;

  // The current run's vertices by (v, vt, vn): keys_[i] is vertex base_ + i;
  // table_ holds i + 1 (0: empty), open addressing, at most half full.
  std::vector<std::array<uint32_t, 3>> keys_;
  std::vector<uint32_t> table_;
  uint32_t base_ = 0;
  std::vector<uint32_t> corners_;

  std::map<std::string, std::pair<SourceLocation, int>, std::less<>> skipped_;  // keyword -> first, count
};

bool ObjParser::numbers(std::size_t pos, float* v, int max, int& n, std::string_view what) {
  n = 0;
  for (std::string_view t = next_token(line_, pos); !t.empty() && t.front() != '#'; t = next_token(line_, pos)) {
    if (n == max)
      return fail(col_of(t), std::string(what) + " has at most " + std::to_string(max) + " numbers");
    if (!parse_float(t, v[n])) return fail(col_of(t), quoted(t) + " is not a number");
    ++n;
  }
  return true;
}

bool ObjParser::vertex(std::size_t pos) {
  float x[7];
  int n = 0;
  if (!numbers(pos, x, 7, n, "a vertex (v)")) return false;
  if (n != 3 && n != 4 && n != 6)
    return fail(key_col_, "a vertex (v) has 3 numbers (x y z), 4 (x y z w) or 6 (x y z r g b); this one has " +
                         std::to_string(n));
  Vec3f p(x[0], x[1], x[2]);
  if (n == 4) {
    if (x[3] == 0.0f) return fail(key_col_, "a vertex's w is 0 (x y z w: the position is x/w y/w z/w)");
    p = Vec3f(x[0] / x[3], x[1] / x[3], x[2] / x[3]);
  }
  if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
    return fail(key_col_, "the vertex position is not finite");
  v_.push_back(p);
  return true;
}

bool ObjParser::tex_coord(std::size_t pos) {
  float x[3] = {0, 0, 0};
  int n = 0;
  if (!numbers(pos, x, 3, n, "a texture coordinate (vt)")) return false;
  if (n == 0) return fail(key_col_, "a texture coordinate (vt) has 1 to 3 numbers (u v w); this one has none");
  for (float& c : x)
    if (!std::isfinite(c)) c = 0.0f;  // OBJ's default, as Assimp
  vt_.emplace_back(x[0], 1.0f - x[1]);
  return true;
}

bool ObjParser::normal(std::size_t pos) {
  float x[3];
  int n = 0;
  if (!numbers(pos, x, 3, n, "a normal (vn)")) return false;
  if (n != 3) return fail(key_col_, "a normal (vn) has 3 numbers (x y z); this one has " + std::to_string(n));
  const Vec3f v(x[0], x[1], x[2]);
  vn_.push_back(std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) ? v : Vec3f(0.0f));  // zero: ng
  return true;
}

// One field of a corner ("3", "-1") resolved against the `count` elements
// defined so far.
bool ObjParser::index(std::string_view field, std::size_t col0, std::size_t count, const char* what, uint32_t& out) {
  long long i = 0;
  const auto [end, ec] = std::from_chars(field.data(), field.data() + field.size(), i);
  if (ec != std::errc() || end != field.data() + field.size())
    return fail(col0, quoted(field) + " is not an index");
  const long long resolved = i > 0 ? i - 1 : static_cast<long long>(count) + i;
  if (i == 0) return fail(col0, std::string(what) + " index 0: OBJ indices start at 1 (negative ones count back)");
  if (resolved < 0 || resolved >= static_cast<long long>(count))
    return fail(col0, std::string(what) + " " + std::string(field) + " does not exist (" + std::to_string(count) +
                          " defined before this line)");
  out = static_cast<uint32_t>(resolved);
  return true;
}

// "v", "v/vt", "v//vn" or "v/vt/vn" -> (v, vt, vn) indices (kNone: absent).
bool ObjParser::corner(std::string_view token, std::array<uint32_t, 3>& key) {
  key = {kNone, kNone, kNone};
  if (std::count(token.begin(), token.end(), '/') > 2)
    return fail(col_of(token), std::string("a face corner is v, v/vt, v//vn or v/vt/vn; got ") + quoted(token));
  std::size_t slot = 0, start = 0;
  for (std::size_t i = 0; i <= token.size(); ++i) {
    if (i < token.size() && token[i] != '/') continue;
    const std::string_view field = token.substr(start, i - start);
    const std::size_t col0 = col_of(token) + start;
    // As Assimp: with no vt in the file but some vn, "v/n" names a normal.
    const std::size_t s = slot == 1 && vt_.empty() && !vn_.empty() ? 2 : slot;
    if (!field.empty()) {
      static const char* const kWhat[] = {"vertex", "texture coordinate", "normal"};
      const std::size_t count = s == 0 ? v_.size() : s == 1 ? vt_.size() : vn_.size();
      if (!index(field, col0, count, kWhat[s], key[s])) return false;
    } else if (slot == 0) {
      return fail(col0, "a face corner has no vertex index");
    }
    ++slot;
    start = i + 1;
  }
  return true;
}


// The vertex of the current run for `key`, added the first time.
uint32_t ObjParser::vertex_of(const std::array<uint32_t, 3>& key) {
  if (2 * (keys_.size() + 1) > table_.size()) {
    table_.assign(std::max<std::size_t>(1024, 2 * table_.size()), 0);
    const std::size_t mask = table_.size() - 1;
    for (std::size_t i = 0; i < keys_.size(); ++i) {
      std::size_t h = (keys_[i][0] * 0x9E3779B1u ^ keys_[i][1] * 0x85EBCA77u ^ keys_[i][2] * 0xC2B2AE3Du) & mask;
      while (table_[h] != 0) h = (h + 1) & mask;
      table_[h] = static_cast<uint32_t>(i + 1);
    }
  }
  const std::size_t mask = table_.size() - 1;
  std::size_t h = (key[0] * 0x9E3779B1u ^ key[1] * 0x85EBCA77u ^ key[2] * 0xC2B2AE3Du) & mask;
  for (; table_[h] != 0; h = (h + 1) & mask)
    if (keys_[table_[h] - 1] == key) return base_ + table_[h] - 1;
  table_[h] = static_cast<uint32_t>(keys_.size() + 1);
  keys_.push_back(key);
  TriangleMesh& m = mesh();
  m.positions.push_back(v_[key[0]]);
  // Normals (uvs) start with the first corner that names one: the run's earlier vertices get zero.
  if (key[2] != kNone && m.normals.size() < m.positions.size() - 1) m.normals.resize(m.positions.size() - 1);
  if (!m.normals.empty() || key[2] != kNone) m.normals.push_back(key[2] != kNone ? vn_[key[2]] : Vec3f(0.0f));
  if (key[1] != kNone && m.uvs.size() < m.positions.size() - 1) m.uvs.resize(m.positions.size() - 1);
  if (!m.uvs.empty() || key[1] != kNone) m.uvs.push_back(key[1] != kNone ? vt_[key[1]] : Vec2f());
  return static_cast<uint32_t>(m.positions.size() - 1);
}

bool ObjParser::face(std::size_t pos) {
  std::array<uint32_t, 3> key{};
  corners_.clear();
  std::size_t n = 0;
  std::array<std::array<uint32_t, 3>, 4> first{};
  std::vector<std::array<uint32_t, 3>> more;
  for (std::string_view t = next_token(line_, pos); !t.empty() && t.front() != '#'; t = next_token(line_, pos)) {
    if (!corner(t, key)) return false;
    if (n < 4) first[n] = key; else more.push_back(key);
    ++n;
  }
  if (n < 3) {
    if (n == 0) return fail(key_col_, "a face (f) names no vertices");
    (n == 1 ? out_.points : out_.lines) += 1;  // as Assimp sorts them: a point, a line
    return true;
  }
  ensure_mesh();
  ++mesh_faces_;
  for (std::size_t i = 0; i < n; ++i) {
    const std::array<uint32_t, 3>& k = i < 4 ? first[i] : more[i - 4];
    run_normals_ = run_normals_ || k[2] != kNone;
    run_uvs_ = run_uvs_ || k[1] != kNone;
    corners_.push_back(vertex_of(k));
  }
  if (mesh().positions.size() >= std::numeric_limits<uint32_t>::max() ||
      mesh().indices.size() > std::numeric_limits<uint32_t>::max() - 3 * n)
    return fail(key_col_, "the mesh has more vertices or triangles than a mesh can index (2^32 - 1 vertices, 2^32 / 3 triangles)");
  std::size_t s = 0;
  if (n == 4) s = static_cast<std::size_t>(quad_start({v_[first[0][0]], v_[first[1][0]], v_[first[2][0]], v_[first[3][0]]}));
  if (n == 4) {
    add_triangle(corners_[s], corners_[(s + 1) % 4], corners_[(s + 2) % 4]);
    add_triangle(corners_[s], corners_[(s + 2) % 4], corners_[(s + 3) % 4]);
  } else {
    for (std::size_t i = 1; i + 1 < n; ++i) add_triangle(corners_[0], corners_[i], corners_[i + 1]);
  }
  return true;
}

bool ObjParser::points_or_lines(std::size_t pos, bool lines) {
  uint64_t n = 0;
  for (std::string_view t = next_token(line_, pos); !t.empty() && t.front() != '#'; t = next_token(line_, pos)) ++n;
  if (lines && n > 0) out_.lines += n - 1;
  if (!lines) out_.points += n;
  return true;
}

// A run of faces ends: the table starts again, and one_mesh notes what it lacked.
void ObjParser::end_run() {
  if (mesh_faces_ > 0) {
    const auto material = static_cast<std::size_t>(out_.meshes[static_cast<std::size_t>(current_mesh_)].material);
    out_.material_used.resize(out_.materials.size());
    out_.material_used[material] = true;
    all_normals_ = all_normals_ && run_normals_;
    all_uvs_ = all_uvs_ && run_uvs_;
  }
  mesh_faces_ = 0;
  run_normals_ = run_uvs_ = false;
  keys_.clear();
  std::fill(table_.begin(), table_.end(), 0u);
  if (current_mesh_ >= 0) base_ = static_cast<uint32_t>(mesh().positions.size());
}

void ObjParser::new_mesh(const std::string& name) {
  end_run();
  mesh_has_material_ = false;
  if (options_.one_mesh) {
    current_mesh_ = 0;
    return;
  }
  out_.meshes.push_back(ObjMesh{name, 0, {}});
  current_mesh_ = static_cast<int>(out_.meshes.size() - 1);
  base_ = 0;
  if (current_object_ >= 0) out_.objects[static_cast<std::size_t>(current_object_)].meshes.push_back(current_mesh_);
}

// As Assimp's createObject: a new object and its first mesh, of the current material.
void ObjParser::new_object(const std::string& name) {
  out_.objects.push_back(ObjObject{name, {}});
  current_object_ = static_cast<int>(out_.objects.size()) - 1;
  new_mesh(name);
  if (current_material_ >= 0) {
    out_.meshes[static_cast<std::size_t>(current_mesh_)].material = current_material_;
    mesh_has_material_ = true;
  }
}

// Faces before any o/g go into "defaultobject"; the mesh keeps the default
// material until a usemtl names one (which then holds for its earlier faces
// too, as in Assimp).
void ObjParser::ensure_mesh() {
  if (current_object_ < 0) new_object(kObjDefaultObject);
}

bool ObjParser::object(std::string_view name) {
  if (name.empty()) return true;
  for (std::size_t i = 0; i < out_.objects.size(); ++i) {
    if (out_.objects[i].name == name) {  // an object named again: its faces go on in the current mesh (Assimp)
      current_object_ = static_cast<int>(i);
      return true;
    }
  }
  new_object(std::string(name));
  return true;
}

bool ObjParser::group(std::string_view name) {
  if (name.empty() || name == active_group_) return true;
  active_group_ = std::string(name);
  new_object(active_group_);  // every group is an object of its own (Assimp)
  return true;
}

bool ObjParser::use_material(std::string_view name) {
  if (name.empty()) return true;
  if (current_material_ >= 0 && out_.materials[static_cast<std::size_t>(current_material_)] == name) return true;
  auto it = material_ids_.find(name);
  if (it == material_ids_.end()) {  // defined in no library (so far): a material of that name, reported later
    out_.materials.emplace_back(name);
    it = material_ids_.emplace(std::string(name), static_cast<int>(out_.materials.size() - 1)).first;
  }
  current_material_ = it->second;
  if (current_mesh_ < 0) return true;  // the first face's object takes it
  ObjMesh& m = out_.meshes[static_cast<std::size_t>(current_mesh_)];
  if (mesh_has_material_ && m.material != current_material_ && mesh_faces_ > 0) new_mesh(std::string(name));
  out_.meshes[static_cast<std::size_t>(current_mesh_)].material = current_material_;
  mesh_has_material_ = true;
  return true;
}

bool ObjParser::material_library(std::string_view name, std::size_t pos) {
  if (name.empty() || !options_.mtllib) return true;
  const std::size_t col0 = line_.find_first_not_of(" \t", pos);
  for (const std::string& m : options_.mtllib(std::string(name), at(col0 == std::string_view::npos ? pos : col0))) {
    if (material_ids_.count(m)) continue;
    out_.materials.push_back(m);
    material_ids_.emplace(m, static_cast<int>(out_.materials.size() - 1));
  }
  return true;
}

void ObjParser::note_skipped(std::string_view key) {
  auto it = skipped_.find(key);
  if (it == skipped_.end()) it = skipped_.emplace(std::string(key), std::make_pair(at(key_col_), 0)).first;
  ++it->second.second;
}

bool ObjParser::finish() {
  for (const auto& [key, first] : skipped_) {
    bool known = false;
    for (const char* k : kUnsupported) known = known || key == k;
    const std::string count = std::to_string(first.second) + (first.second == 1 ? " statement" : " statements");
    diag_.warning(first.first, known ? "OBJ statement '" + key + "' is not supported (free-form geometry and render "
                                           "attributes are left out; " + count + ")"
                                     : "unknown OBJ statement '" + key + "' left out (" + count + ")");
  }
  end_run();
  // The file's element arrays and the run's table are done with: freed before
  // the meshes are copied to their exact sizes, which then reuse the space.
  v_ = {};
  vn_ = {};
  vt_ = {};
  keys_ = {};
  table_ = {};
  out_.material_used.resize(out_.materials.size());
  for (ObjMesh& m : out_.meshes) {
    std::vector<Vec3f>& p = m.mesh.positions;
    if (options_.one_mesh && !all_normals_) m.mesh.normals = {};
    if (options_.one_mesh && !all_uvs_) m.mesh.uvs = {};
    // A run whose later vertices named no vt/vn: zero for them too.
    if (!m.mesh.normals.empty()) m.mesh.normals.resize(p.size());
    if (!m.mesh.uvs.empty()) m.mesh.uvs.resize(p.size());
    fit(p, 1);  // one spare: the Embree backend can share the buffer
    fit(m.mesh.indices, 0);
    fit(m.mesh.normals, 0);
    fit(m.mesh.uvs, 0);
  }
  return true;
}

SourceLocation whole_file(const std::string& path) {
  SourceLocation loc;
  loc.file = std::make_shared<const SourceFile>(SourceFile{path, {}});
  return loc;
}

}  // namespace

bool read_obj(const std::string& path, const ObjReadOptions& options, ObjModel& out, Diagnostics& diag) {
  if (const std::string why = why_not_read(path, options.max_bytes, "OBJ"); !why.empty()) {
    diag.error(whole_file(path), why);
    return false;
  }
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!f) {
    diag.error(whole_file(path), "cannot read the file: " + std::string(std::strerror(errno)));
    return false;
  }
  ObjParser parser(path, options, out, diag);
  LineReader lines(f.get());
  std::string joined;  // a statement continued over lines ending in '\'
  int first = 0;
  for (std::string_view line; lines.next(line);) {
    if (!line.empty() && line.back() == '\\') {
      if (joined.empty()) first = lines.number();
      joined.append(line.substr(0, line.size() - 1)).push_back(' ');
      continue;
    }
    if (!joined.empty()) {
      joined.append(line);
      if (!parser.statement(joined, first)) return false;
      joined.clear();
    } else if (!parser.statement(line, lines.number())) {
      return false;
    }
  }
  if (!joined.empty() && !parser.statement(joined, first)) return false;
  if (lines.failed()) {
    diag.error(whole_file(path), "cannot read the file: a read error after line " + std::to_string(lines.number()));
    return false;
  }
  return parser.finish();
}

}  // namespace pt
