// bench_texture_memory MODE DIR [--cache SIZE_MB] [--lookups N] [--seed S]
//
// One process, one way of holding every image in DIR (PNG, JPEG, TGA; a .tx
// beside an image is used by the cache) and N texture lookups spread over
// them as a render's would be, then a line of JSON: the peak resident set
// (getrusage), the time to open, to look up, and to make the same lookups
// again (tiles already read), and what the lookups summed (so that nothing is
// optimised away). MODE:
//   none    nothing opened: the process's own baseline (OpenImageIO loaded);
//   decode  every image decoded into memory (Texture::load: float RGB, what
//           the renderer did before the texture cache), bilinear point lookups;
//   cache   every image through one TextureCache of --cache MiB, filtered
//           lookups over footprints from one texel to the whole image.
// tools/bench/textures/texture_memory.py runs the modes, each in a fresh
// process, interleaved, and writes docs/bench/texture-memory.md.
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "render/textures/texture.h"

namespace {

namespace fs = std::filesystem;

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

long peak_rss_kib() {
  rusage r{};
  getrusage(RUSAGE_SELF, &r);
  return r.ru_maxrss;
}

std::vector<std::string> images_in(const std::string& dir) {
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(dir)) {
    std::string ext = e.path().extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (ext == ".png" || ext == ".jpg" || ext == ".jpeg" || ext == ".tga") out.push_back(e.path().string());
  }
  std::sort(out.begin(), out.end());
  return out;
}

// `lookups` lookups spread over `textures` as a render's would be; their sum.
double look_up(const std::vector<pt::Texture>& textures, long lookups, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  double sum = 0;
  for (long i = 0; i < lookups; ++i) {
    const pt::Texture& t = textures[static_cast<std::size_t>(rng() % textures.size())];
    const pt::Vec2f uv(u(rng), u(rng));
    // Footprints log-uniform from 2^-12 (a texel of a 4K image) to 1 (the whole image).
    const float w = std::exp2(-12.0f * u(rng));
    sum += t.eval(pt::TexCoord(uv, {w, 0.0f}, {0.0f, w})).r;
  }
  return sum;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"bench_texture_memory: peak memory of a folder of textures, decoded or cached"};
  std::string mode, dir;
  double cache_mib = 64;
  long lookups = 2000000;
  unsigned seed = 1;
  app.add_option("mode", mode, "none, decode or cache")->required()->check(CLI::IsMember({"none", "decode", "cache"}));
  app.add_option("dir", dir, "Folder of images")->required()->check(CLI::ExistingDirectory);
  app.add_option("--cache", cache_mib, "Texture cache size, MiB (mode cache)")->check(CLI::Range(1.0, 65536.0));
  app.add_option("--lookups", lookups, "Lookups")->check(CLI::Range(0L, 1000000000L));
  app.add_option("--seed", seed, "Seed of the lookups");
  CLI11_PARSE(app, argc, argv);

  const std::vector<std::string> files = images_in(dir);
  const auto t0 = std::chrono::steady_clock::now();
  std::unique_ptr<pt::TextureCache> cache;
  if (mode == "cache") cache = std::make_unique<pt::TextureCache>(static_cast<uint64_t>(cache_mib * 1048576.0));
  std::vector<pt::Texture> textures;
  if (mode != "none") {
    for (const std::string& f : files) {
      pt::Texture t;
      std::string error;
      bool ok = false;
      if (mode == "decode") {
        ok = pt::Texture::load(f, t, error);
      } else {
        pt::OpenedImage opened;
        ok = cache->open(f, false, pt::TextureFilter::Anisotropic, pt::TextureWrap::Repeat, {}, opened, error);
        t = pt::Texture(opened.image);
      }
      if (!ok) {
        std::cerr << f << ": " << error << '\n';
        return 1;
      }
      textures.push_back(std::move(t));
    }
  }
  const double open_s = seconds_since(t0);
  double sum = 0;
  const auto t1 = std::chrono::steady_clock::now();
  if (!textures.empty()) sum = look_up(textures, lookups, seed);
  const double lookup_s = seconds_since(t1);
  // The same lookups again: what they cost once the tiles they need are read
  // (with a cache that holds them).
  const auto t2 = std::chrono::steady_clock::now();
  if (!textures.empty()) look_up(textures, lookups, seed);
  const double repeat_s = seconds_since(t2);
  std::cout << "{\"mode\": \"" << mode << "\", \"images\": " << files.size() << ", \"cache_mib\": "
            << (mode == "cache" ? cache_mib : 0.0) << ", \"lookups\": " << (textures.empty() ? 0 : lookups)
            << ", \"open_seconds\": " << open_s << ", \"lookup_seconds\": " << lookup_s << ", \"repeat_seconds\": " << repeat_s
            << ", \"peak_rss_kib\": " << peak_rss_kib() << ", \"checksum\": " << sum << "}\n";
  return 0;
}
