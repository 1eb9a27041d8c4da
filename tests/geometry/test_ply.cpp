#include <gtest/gtest.h>

#include <bit>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <array>
#include <limits>
#include <vector>

#include "scene/ply.h"

namespace pt {
namespace {

// Builds a binary PLY body value by value in the chosen byte order.
class Bytes {
 public:
  explicit Bytes(bool big_endian) : big_(big_endian) {}
  template <class T>
  Bytes& put(T v) {
    unsigned char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    const bool host_big = std::endian::native == std::endian::big;
    if (big_ != host_big) {
      for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(b[i], b[sizeof(T) - 1 - i]);
    }
    data_.append(reinterpret_cast<const char*>(b), sizeof(T));
    return *this;
  }
  const std::string& str() const { return data_; }

 private:
  bool big_;
  std::string data_;
};

bool parse(const std::string& text, TriangleMesh& mesh, PlyError& error) { return parse_ply(text, mesh, error); }

const char* kAsciiQuadAndTriangle =
    "ply\n"
    "format ascii 1.0\n"
    "comment two faces\n"
    "element vertex 5\n"
    "property float x\n"
    "property float y\n"
    "property float z\n"
    "property float nx\n"
    "property float ny\n"
    "property float nz\n"
    "property float u\n"
    "property float v\n"
    "element face 2\n"
    "property list uchar int vertex_indices\n"
    "end_header\n"
    "0 0 0  0 0 1  0 0\n"
    "1 0 0  0 0 1  1 0\n"
    "1 1 0  0 0 1  1 1\n"
    "0 1 0  0 0 1  0 1\n"
    "2 2 -1.5e0  0 0 1  0.5 0.5\n"
    "4 0 1 2 3\n"
    "3 1 4 2\n";

TEST(Ply, AsciiWithNormalsUvsAndAPolygon) {
  TriangleMesh m;
  PlyError e;
  ASSERT_TRUE(parse(kAsciiQuadAndTriangle, m, e)) << e.message;
  ASSERT_EQ(m.positions.size(), 5u);
  EXPECT_EQ(m.positions[4], Vec3f(2, 2, -1.5f));
  ASSERT_EQ(m.normals.size(), 5u);
  EXPECT_EQ(m.normals[0], Vec3f(0, 0, 1));
  ASSERT_EQ(m.uvs.size(), 5u);
  EXPECT_EQ(m.uvs[2], Vec2f(1, 1));
  // The quad is fan-triangulated: (0 1 2) (0 2 3), then the triangle.
  const std::vector<uint32_t> expected{0, 1, 2, 0, 2, 3, 1, 4, 2};
  EXPECT_EQ(m.indices, expected);
}

TEST(Ply, CrLfLinesAndExtraWhitespace) {
  const std::string text =
      "ply\r\nformat ascii 1.0\r\nelement vertex 3\r\nproperty float x\r\nproperty float y\r\n"
      "property float z\r\nelement face 1\r\nproperty list uchar uint vertex_index\r\nend_header\r\n"
      "0 0 0\r\n1 0 0\r\n  0   1\t0\r\n3 0 1 2";
  TriangleMesh m;
  PlyError e;
  ASSERT_TRUE(parse(text, m, e)) << e.message;
  EXPECT_EQ(m.indices.size(), 3u);
  EXPECT_EQ(m.positions[2], Vec3f(0, 1, 0));
  EXPECT_TRUE(m.normals.empty());
  EXPECT_TRUE(m.uvs.empty());
}

std::string binary_file(bool big_endian) {
  std::string header = std::string("ply\nformat ") + (big_endian ? "binary_big_endian" : "binary_little_endian") +
                       " 1.0\n"
                       "element vertex 4\n"
                       "property double x\n"
                       "property double y\n"
                       "property double z\n"
                       "property uchar red\n"
                       "property list uchar float junk\n"
                       "property float s\n"
                       "property float t\n"
                       "element face 2\n"
                       "property uchar flags\n"
                       "property list uint int vertex_indices\n"
                       "property list ushort short other\n"
                       "element edge 1\n"
                       "property int vertex1\n"
                       "property int vertex2\n"
                       "end_header\n";
  Bytes b(big_endian);
  const double pos[4][3] = {{0, 0, 0}, {1.5, 0, 0}, {1.5, 2.25, 0}, {0, 2.25, -1e-3}};
  for (int i = 0; i < 4; ++i) {
    b.put(pos[i][0]).put(pos[i][1]).put(pos[i][2]);
    b.put(static_cast<uint8_t>(200));
    b.put(static_cast<uint8_t>(2)).put(1.0f).put(2.0f);  // skipped list
    b.put(static_cast<float>(i) * 0.25f).put(1.0f - static_cast<float>(i) * 0.25f);
  }
  b.put(static_cast<uint8_t>(7)).put(static_cast<uint32_t>(3)).put(0).put(1).put(2);
  b.put(static_cast<uint16_t>(1)).put(static_cast<int16_t>(-5));
  b.put(static_cast<uint8_t>(7)).put(static_cast<uint32_t>(3)).put(0).put(2).put(3);
  b.put(static_cast<uint16_t>(0));
  b.put(0).put(1);  // the edge element, skipped
  return header + b.str();
}

TEST(Ply, BinaryLittleAndBigEndianSkipUnknownProperties) {
  for (bool big : {false, true}) {
    TriangleMesh m;
    PlyError e;
    ASSERT_TRUE(parse(binary_file(big), m, e)) << e.message;
    ASSERT_EQ(m.positions.size(), 4u);
    EXPECT_EQ(m.positions[2], Vec3f(1.5f, 2.25f, 0));
    EXPECT_EQ(m.positions[3], Vec3f(0, 2.25f, -1e-3f));
    ASSERT_EQ(m.uvs.size(), 4u);  // from s, t
    EXPECT_EQ(m.uvs[1], Vec2f(0.25f, 0.75f));
    const std::vector<uint32_t> expected{0, 1, 2, 0, 2, 3};
    EXPECT_EQ(m.indices, expected);
  }
}

TEST(Ply, TextureUvAliases) {
  const std::string text =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float texture_u\nproperty float x\n"
      "property float y\nproperty float z\nproperty float texture_v\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
      "0.1 0 0 0 0.2\n0.3 1 0 0 0.4\n0.5 0 1 0 0.6\n3 0 1 2\n";
  TriangleMesh m;
  PlyError e;
  ASSERT_TRUE(parse(text, m, e)) << e.message;
  ASSERT_EQ(m.uvs.size(), 3u);
  EXPECT_EQ(m.uvs[1], Vec2f(0.3f, 0.4f));
  EXPECT_EQ(m.positions[1], Vec3f(1, 0, 0));
}

// ---------------------------------------------------------------- errors
struct Bad {
  std::string text;
  std::string message_part;
  int line;
};

std::string ascii_header(const std::string& vertex_count, const std::string& face_count) {
  return "ply\nformat ascii 1.0\nelement vertex " + vertex_count +
         "\nproperty float x\nproperty float y\nproperty float z\n"
         "element face " + face_count + "\nproperty list uchar int vertex_indices\nend_header\n";
}

TEST(Ply, ErrorsNameTheProblemAndTheHeaderLine) {
  const Bad cases[] = {
      {"plyx\n", "not a PLY file", 1},
      {"", "not a PLY file", 1},
      {"ply\nformat ascii 2.0\nend_header\n", "unsupported PLY version '2.0'", 2},
      {"ply\nformat binary_middle_endian 1.0\nend_header\n", "unknown format", 2},
      {"ply\nformat ascii 1.0\nproperty float x\nend_header\n", "property before any element", 3},
      {"ply\nformat ascii 1.0\nelement vertex 1\nproperty float128 x\nend_header\n", "unknown type 'float128'", 4},
      {"ply\nformat ascii 1.0\nelement vertex -3\n", "invalid element count '-3'", 3},
      {"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n", "no end_header", 4},
      {"ply\nformat ascii 1.0\nelement vertex 0\nelement vertex 0\nend_header\n", "declared twice", 4},
      {"ply\nformat ascii 1.0\nelement vertex 1\nproperty list float int v\nend_header\n", "integer type", 4},
      {"ply\nformat ascii 1.0\nbogus line\nend_header\n", "unexpected header line 'bogus line'", 3},
      {"ply\nelement vertex 0\nend_header\n", "no format line", 3},
      {ascii_header("1000000000000", "1") + "0 0 0\n3 0 0 0\n", "declares 1000000000000 vertex elements", 3},
      {ascii_header("3", "4294967295") + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "face elements", 7},
      {"ply\nformat ascii 1.0\nelement vertex 1\nproperty float y\nproperty float z\nelement face 0\n"
       "property list uchar int vertex_indices\nend_header\n0 0\n",
       "no 'x' property", 3},
      {"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\n"
       "element face 1\nproperty int foo\nend_header\n0 0 0\n1\n",
       "no 'vertex_indices' list", 7},
      {"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\n"
       "end_header\n0 0 0\n",
       "no face element", 0},
  };
  for (const Bad& c : cases) {
    TriangleMesh m;
    PlyError e;
    EXPECT_FALSE(parse(c.text, m, e)) << c.text;
    EXPECT_NE(e.message.find(c.message_part), std::string::npos) << "got: " << e.message;
    EXPECT_EQ(e.line, c.line) << e.message;
  }
}

TEST(Ply, BodyErrorsAreReported) {
  const Bad cases[] = {
      {ascii_header("3", "1") + "0 0 0\n1 0 0\n0 1 0\n3 0 1 5\n", "face 0 refers to vertex 5 but there are only 3", 0},
      {ascii_header("3", "1") + "0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n", "refers to vertex -1", 0},
      {ascii_header("3", "1") + "0 0 0\n1 zero 0\n0 1 0\n3 0 1 2\n", "vertex 1: 'zero' is not a valid number (line 11)",
       0},
      {ascii_header("3", "1") + "0 0 0\n1 0 0\n0 1 0\n3 0 1.5 2\n", "'1.5' is not a valid number", 0},
      {ascii_header("3", "1") + "0 0 0\n1 0 0\n0 1 nan\n3 0 1 2\n", "vertex 2 has a non-finite position", 0},
      {ascii_header("3", "2") + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "ends inside face 1 of 2", 0},
      {ascii_header("3", "1") + "0 0 0\n1 0 0\n0 1 0\n9 0 1 2\n", "ends inside face 0 of 1", 0},
  };
  for (const Bad& c : cases) {
    TriangleMesh m;
    PlyError e;
    EXPECT_FALSE(parse(c.text, m, e)) << c.text;
    EXPECT_NE(e.message.find(c.message_part), std::string::npos) << "got: " << e.message;
    EXPECT_EQ(e.line, c.line) << e.message;
  }
}

TEST(Ply, TruncatedBinaryFilesAreReportedAtEveryLength) {
  const std::string full = binary_file(false);
  const std::size_t body = full.find("end_header\n") + 11;
  for (std::size_t n = body; n < full.size() - 8; ++n) {  // the trailing edge element is 8 bytes
    TriangleMesh m;
    PlyError e;
    EXPECT_FALSE(parse(full.substr(0, n), m, e)) << n;
    EXPECT_FALSE(e.message.empty());
  }
}

TEST(Ply, HugeListLengthsAreRefusedBeforeAllocation) {
  std::string text = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                     "property float z\nelement face 1\nproperty list uint uint vertex_indices\nend_header\n";
  Bytes b(false);
  for (int i = 0; i < 9; ++i) b.put(static_cast<float>(i % 2));
  b.put(static_cast<uint32_t>(0xFFFFFFFFu)).put(0u).put(1u).put(2u);
  TriangleMesh m;
  PlyError e;
  EXPECT_FALSE(parse(text + b.str(), m, e));
  EXPECT_NE(e.message.find("ends inside face 0"), std::string::npos) << e.message;
}

TEST(Ply, RandomCorruptionNeverCrashesAndNeverYieldsBadIndices) {
  std::mt19937 rng(5);
  const std::string sources[] = {binary_file(false), binary_file(true), kAsciiQuadAndTriangle};
  int accepted = 0;
  for (const std::string& src : sources) {
    for (int trial = 0; trial < 3000; ++trial) {
      std::string s = src;
      const int edits = 1 + static_cast<int>(rng() % 4);
      for (int k = 0; k < edits; ++k) {
        const std::size_t at = rng() % s.size();
        switch (rng() % 3) {
          case 0: s[at] = static_cast<char>(rng()); break;
          case 1: s.erase(at, 1 + rng() % 8); break;
          default: s.insert(at, 1, static_cast<char>(rng())); break;
        }
        if (s.empty()) break;
      }
      TriangleMesh m;
      PlyError e;
      if (parse(s, m, e)) {
        ++accepted;
        for (uint32_t i : m.indices) ASSERT_LT(i, m.positions.size());
        ASSERT_EQ(m.indices.size() % 3, 0u);
      } else {
        ASSERT_FALSE(e.message.empty());
      }
    }
  }
  EXPECT_GT(accepted, 0);  // some edits (e.g. in comments or values) keep the file valid
}

// The layout the reader takes at once (float vertex properties, one uchar/int
// index list, the host's byte order: read_float_vertices and read_int_faces in
// src/scene/ply.cpp) against the same file in the other byte order, which is
// read value by value: the same mesh, and the same message for every
// truncation and every bad value.
std::string float_file(bool big_endian, const std::vector<std::array<float, 5>>& vertices,
                       const std::vector<std::vector<int32_t>>& faces, bool with_uvs) {
  std::string header = std::string("ply\nformat ") + (big_endian ? "binary_big_endian" : "binary_little_endian") +
                       " 1.0\nelement vertex " + std::to_string(vertices.size()) +
                       "\nproperty float x\nproperty float y\nproperty float z\n" +
                       (with_uvs ? "property float u\nproperty float v\n" : "") + "element face " +
                       std::to_string(faces.size()) + "\nproperty list uchar int vertex_indices\nend_header\n";
  Bytes b(big_endian);
  for (const auto& v : vertices) {
    for (int k = 0; k < (with_uvs ? 5 : 3); ++k) b.put(v[static_cast<std::size_t>(k)]);
  }
  for (const auto& f : faces) {
    b.put(static_cast<uint8_t>(f.size()));
    for (int32_t i : f) b.put(i);
  }
  return header + b.str();
}

TEST(Ply, HostOrderFloatLayoutReadsAsTheValueByValueReader) {
  const bool host_big = std::endian::native == std::endian::big;
  const std::vector<std::array<float, 5>> v = {
      {0, 0, 0, 0, 0}, {1, 0, 0, 1, 0}, {1, 1, 0, 1, 1}, {0, 1, 0, 0, 1}, {2, 2, -1.5f, 0.5f, 0.5f}};
  const std::vector<std::vector<int32_t>> good = {{0, 1, 2, 3}, {1, 4, 2}, {0, 1}, {2, 3, 4}};
  const float nan = std::numeric_limits<float>::quiet_NaN();
  struct Case {
    std::vector<std::array<float, 5>> vertices;
    std::vector<std::vector<int32_t>> faces;
  };
  const Case cases[] = {{v, good},
                        {v, {{0, 1, 2}, {1, 5, 2}}},
                        {v, {{0, 1, 2}, {1, -1, 2}}},
                        {v, {{0, 1, 2, 3, 7}}},
                        {{{0, 0, 0}, {1, nan, 0}, {0, 1, 0}}, {{0, 1, 2}}}};
  int accepted = 0;
  for (const Case& c : cases) {
    for (bool uvs : {false, true}) {
      const std::string fast = float_file(host_big, c.vertices, c.faces, uvs);
      const std::string slow = float_file(!host_big, c.vertices, c.faces, uvs);
      // The headers differ in length (the format's name): cut both bodies alike.
      const std::size_t fast_body = fast.find("end_header\n") + 11, slow_body = slow.find("end_header\n") + 11;
      for (std::size_t n = 0; fast_body + n <= fast.size(); ++n) {
        TriangleMesh a, b;
        PlyError ea, eb;
        const bool ok = parse(fast.substr(0, fast_body + n), a, ea);
        ASSERT_EQ(ok, parse(slow.substr(0, slow_body + n), b, eb)) << n;
        ASSERT_EQ(ea.message, eb.message) << n;
        if (!ok) continue;
        ++accepted;
        EXPECT_EQ(a.indices, b.indices);
        ASSERT_EQ(a.positions.size(), b.positions.size());
        EXPECT_EQ(0, std::memcmp(a.positions.data(), b.positions.data(), a.positions.size() * sizeof(Vec3f)));
        ASSERT_EQ(a.uvs.size(), b.uvs.size());
        EXPECT_EQ(0, std::memcmp(a.uvs.data(), b.uvs.data(), a.uvs.size() * sizeof(Vec2f)));
      }
    }
  }
  EXPECT_EQ(accepted, 2);  // the whole good file, with and without uvs; every other case has an error
  TriangleMesh m;
  PlyError e;
  ASSERT_TRUE(parse(float_file(host_big, v, good, false), m, e)) << e.message;
  EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3, 1, 4, 2, 2, 3, 4}));
}

// ---------------------------------------------------------------- files
TEST(Ply, LoadsFromDiskAndReportsMissingFiles) {
  const auto path = std::filesystem::temp_directory_path() / "pt_test_ply_quad.ply";
  {
    std::ofstream out(path, std::ios::binary);
    out << binary_file(true);
  }
  TriangleMesh m;
  PlyError e;
  ASSERT_TRUE(load_ply(path.string(), m, e)) << e.message;
  EXPECT_EQ(m.indices.size(), 6u);
  std::filesystem::remove(path);
  EXPECT_FALSE(load_ply(path.string(), m, e));
  EXPECT_NE(e.message.find("cannot open"), std::string::npos);
}

TEST(Ply, LoadsTheStanfordDragonIfPresent) {
  const std::string path = std::string(PT_SHARED_DIR) + "/assets/meshes/dragon_vrip_res4.ply";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " not present";
  TriangleMesh m;
  PlyError e;
  ASSERT_TRUE(load_ply(path, m, e)) << e.message;
  EXPECT_GT(m.positions.size(), 1000u);
  EXPECT_GT(m.indices.size(), 3000u);
  for (uint32_t i : m.indices) ASSERT_LT(i, m.positions.size());
}

}  // namespace
}  // namespace pt
