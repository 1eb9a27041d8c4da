// gen_grid_ply: writes a displaced grid as a binary little-endian PLY, the
// large mesh of the load-and-build benchmark (bench_scale.py, docs/bench/scale.md).
//
//   gen_grid_ply OUT.ply [--triangles 10000000]
//
// An n x n grid of quads over [-1, 1]^2 in the xz plane (n = ceil(sqrt(T / 2)),
// so at least T triangles, two per quad), each vertex raised along +y by a sum
// of sines (a terrain: no two neighbouring triangles coplanar). Vertices are
// float x y z; faces are a uchar count of 3 and three int indices, as most
// exporters write them. Deterministic: the same T gives the same bytes.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace {

float height(float x, float z) {
  return 0.08f * std::sin(7.0f * x) * std::cos(5.0f * z) + 0.03f * std::sin(23.0f * x + 17.0f * z) +
         0.01f * std::cos(61.0f * x - 43.0f * z);
}

template <class T>
void put(std::vector<char>& out, T v) {
  const char* p = reinterpret_cast<const char*>(&v);
  out.insert(out.end(), p, p + sizeof(T));
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"gen_grid_ply: a displaced grid as a binary PLY"};
  std::string path;
  uint64_t triangles = 10'000'000;
  app.add_option("output", path, "PLY file to write")->required();
  app.add_option("--triangles", triangles, "Least number of triangles")->check(CLI::Range(uint64_t{2}, uint64_t{1} << 31));
  CLI11_PARSE(app, argc, argv);
  const auto n = static_cast<uint32_t>(std::ceil(std::sqrt(static_cast<double>(triangles) / 2.0)));
  const uint64_t vertices = static_cast<uint64_t>(n + 1) * (n + 1);
  const uint64_t faces = 2ull * n * n;
  std::ofstream f(path, std::ios::binary);
  if (!f) {
    std::cerr << "error: cannot write " << path << "\n";
    return 1;
  }
  f << "ply\nformat binary_little_endian 1.0\ncomment gen_grid_ply " << n << "x" << n << "\nelement vertex "
    << vertices << "\nproperty float x\nproperty float y\nproperty float z\nelement face " << faces
    << "\nproperty list uchar int vertex_indices\nend_header\n";
  std::vector<char> row;
  for (uint32_t j = 0; j <= n; ++j) {
    row.clear();
    for (uint32_t i = 0; i <= n; ++i) {
      const float x = -1.0f + 2.0f * static_cast<float>(i) / static_cast<float>(n);
      const float z = -1.0f + 2.0f * static_cast<float>(j) / static_cast<float>(n);
      put(row, x);
      put(row, height(x, z));
      put(row, z);
    }
    f.write(row.data(), static_cast<std::streamsize>(row.size()));
  }
  for (uint32_t j = 0; j < n; ++j) {
    row.clear();
    for (uint32_t i = 0; i < n; ++i) {
      const int32_t a = static_cast<int32_t>(j * (n + 1) + i), b = a + 1, c = a + static_cast<int32_t>(n + 1), d = c + 1;
      const int32_t tris[2][3] = {{a, c, b}, {b, c, d}};
      for (const auto& t : tris) {
        put(row, static_cast<uint8_t>(3));
        for (int32_t v : t) put(row, v);
      }
    }
    f.write(row.data(), static_cast<std::streamsize>(row.size()));
  }
  if (!f.flush()) {
    std::cerr << "error: writing " << path << " failed\n";
    return 1;
  }
  std::cout << path << ": " << n << "x" << n << " grid, " << vertices << " vertices, " << faces << " triangles\n";
  return 0;
}
