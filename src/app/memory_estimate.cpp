#include "app/memory_estimate.h"

#include <malloc.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <memory>
#include <type_traits>
#include <variant>
#include <vector>

#include "accel/embree/compact.h"
#include "core/file_access.h"
#include "imagelib/image_library.h"
#include "render/textures/texture.h"
#include "scene/scene_description.h"

namespace pt {
namespace {

// The acceleration structure's bytes per triangle at the peak of its build
// beyond the mesh arrays counted beside them, measured as peak RSS
// differences with tools/bench/memory (docs/bench/memory.md) and
// tools/bench/scale: on our BVH 40 (980k-triangle grid) to 47 (10M), on
// Embree 59 (980k); Embree's compact build (scenes of
// kEmbreeCompactTriangles or more, accel/embree/compact.h) 17 (10M). Below 4Mi
// triangles part of the build reuses heap the PLY reader freed, hence the
// lower figure there.
constexpr uint64_t kBvhBytesPerTriangle = 44;
constexpr uint64_t kEmbreeBytesPerTriangle = 64;
constexpr uint64_t kEmbreeCompactBytesPerTriangle = 18;
// What any render adds whatever its size: the worker threads (stacks and
// scratch), the task scheduler's and Embree's own state, the image writers'
// buffers. Measured: 5.2 MiB (BVH) and 6.6 MiB (Embree) on the Cornell box.
constexpr uint64_t kRuntimeBytes = uint64_t{7} << 20;
// A shape of the render scene (its Shape variant, material and light entries)
// and its place in the structure.
constexpr uint64_t kBytesPerShape = 512;
// A decoded texel (render/textures/texture.h: float RGB), and what the
// environment map's sampling distribution adds per texel (a Distribution1D per
// row: the function and its CDF, 8 bytes; the luminance table it is built from, 4).
constexpr uint64_t kTextureBytesPerTexel = 3 * sizeof(float);
constexpr uint64_t kDistributionBytesPerTexel = 3 * sizeof(float);

// A file header may claim any size: the sums stop at the largest value.
uint64_t saturating_mul(uint64_t a, uint64_t b) {
  uint64_t r = 0;
  return __builtin_mul_overflow(a, b, &r) ? UINT64_MAX : r;
}
uint64_t saturating_add(uint64_t a, uint64_t b) { return a > UINT64_MAX - b ? UINT64_MAX : a + b; }

}  // namespace

uint64_t MemoryEstimate::added() const {
  return saturating_add(saturating_add(saturating_add(film, images), saturating_add(textures, geometry)), runtime);
}

uint64_t MemoryEstimate::total() const {
  const uint64_t grows = added() > reusable ? added() - reusable : 0;
  return std::max(peak_so_far, saturating_add(baseline, grows));
}

uint64_t resident_bytes() {
  FILE* f = std::fopen("/proc/self/statm", "r");
  if (f == nullptr) return 0;
  unsigned long long size = 0, resident = 0;
  const int n = std::fscanf(f, "%llu %llu", &size, &resident);
  std::fclose(f);
  const long page = ::sysconf(_SC_PAGE_SIZE);
  return n == 2 && page > 0 ? static_cast<uint64_t>(resident) * static_cast<uint64_t>(page) : 0;
}

uint64_t free_heap_bytes() {
#if defined(__GLIBC__) && (__GLIBC__ > 2 || (__GLIBC__ == 2 && __GLIBC_MINOR__ >= 33))
  return static_cast<uint64_t>(mallinfo2().fordblks);
#else
  return 0;
#endif
}

uint64_t peak_resident_bytes() {
  // VmHWM, the peak of this program's own address space. getrusage's
  // ru_maxrss survives exec: a process started by a large parent (fork, then
  // exec) reports the parent's resident size as its own peak.
  if (FILE* f = std::fopen("/proc/self/status", "r")) {
    char line[256];
    unsigned long long kib = 0;
    bool found = false;
    while (!found && std::fgets(line, sizeof line, f) != nullptr)
      found = std::sscanf(line, "VmHWM: %llu kB", &kib) == 1;
    std::fclose(f);
    if (found) return static_cast<uint64_t>(kib) * 1024;
  }
  rusage usage{};
  if (::getrusage(RUSAGE_SELF, &usage) != 0) return 0;
  return static_cast<uint64_t>(usage.ru_maxrss) * 1024;  // KiB on Linux
}

uint64_t texture_bytes(const SceneDescription& scene, const TextureLimits& limits, uint64_t cache_bytes) {
  uint64_t total = 0, cached = 0, largest_decode = 0;
  // `cache`: a material's image, read through the texture cache (its tiles and
  // MIP levels, 4/3 of the finest, at most 4 bytes a channel); else decoded
  // into memory at `bytes_per_texel`.
  const auto add_spec = [&](const ImageHeader& spec, uint64_t bytes_per_texel, bool cache) {
    if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0) return;
    const uint64_t texels = static_cast<uint64_t>(spec.width) * static_cast<uint64_t>(spec.height);
    // An image the loader would refuse (a volume, or beyond the texture
    // limits) is refused by the build, with the scene location that names it;
    // it is never decoded, so it costs nothing.
    if (spec.depth > 1 || !limits.admit(texels, spec.nchannels)) return;
    const uint64_t channel_bytes = saturating_mul(texels, sizeof(float) * static_cast<uint64_t>(spec.nchannels));
    if (cache) {
      cached = saturating_add(cached, saturating_add(channel_bytes, channel_bytes / 3));
    } else {
      total = saturating_add(total, saturating_mul(texels, bytes_per_texel));
    }
    largest_decode = std::max(largest_decode, channel_bytes);
  };
  const auto add = [&](const std::string& path, uint64_t bytes_per_texel, bool cache) {
    if (!why_unreadable(path).empty()) return;  // no FIFO or device is opened; the build reports it
    // The header only, through the image module (loaded here: the render
    // reads these images anyway). If it cannot be loaded, or the file read,
    // the build reports it.
    std::string error;
    const ImageLibrary* lib = image_library(error);
    const std::unique_ptr<ImageReader> in = lib != nullptr ? lib->open(path, false, error) : nullptr;
    if (in) add_spec(in->header(), bytes_per_texel, cache);
  };
  // An image embedded in a model file: the build writes it to a file the
  // cache reads like any other (render/textures/scratch_folder.h).
  const auto add_embedded = [&](const TextureDesc& t) {
    std::string error;
    const ImageLibrary* lib = image_library(error);
    const std::unique_ptr<ImageReader> in =
        lib != nullptr ? lib->open_memory(t.embedded->data(), t.embedded->size(), t.embedded_format, error) : nullptr;
    if (in) add_spec(in->header(), 0, true);
  };
  std::vector<bool> used(scene.textures.size(), false);
  for (const MaterialDesc& m : scene.materials) {
    m.for_each_texture([&](int t) {
      if (t >= 0 && static_cast<std::size_t>(t) < used.size()) used[static_cast<std::size_t>(t)] = true;
    });
  }
  for (std::size_t i = 0; i < scene.textures.size(); ++i)
    if (used[i] && scene.textures[i].type == TextureType::Image) {
      if (scene.textures[i].embedded) add_embedded(scene.textures[i]);
      else add(scene.textures[i].resolved, 0, true);
    }
  if (scene.environment) add(scene.environment->resolved, kTextureBytesPerTexel + kDistributionBytesPerTexel, false);
  if (scene.render.background_image) add(scene.render.background_image->resolved, kTextureBytesPerTexel, false);
  return saturating_add(saturating_add(total, std::min(cached, cache_bytes)), largest_decode);
}

uint64_t geometry_bytes(const SceneDescription& scene, AccelKind accel) {
  uint64_t bytes = 0, triangles = 0;
  const auto add = [&](const ShapeDesc& shape) {
    bytes += kBytesPerShape;
    if (const auto* mesh = std::get_if<TriangleMesh>(&shape.geometry)) {
      bytes += mesh->positions.size() * sizeof(Vec3f) + mesh->indices.size() * sizeof(uint32_t) +
               mesh->normals.size() * sizeof(Vec3f) + mesh->uvs.size() * sizeof(Vec2f);  // the arrays
      triangles += mesh->triangle_count();
    }
  };
  for (const ShapeDesc& shape : scene.shapes) add(shape);
  for (const ObjectDesc& object : scene.objects)
    for (const ShapeDesc& shape : object.shapes) add(shape);
  uint64_t per_triangle = kBvhBytesPerTriangle;
  if (accel == AccelKind::Embree)
    per_triangle = triangles >= kEmbreeCompactTriangles ? kEmbreeCompactBytesPerTriangle : kEmbreeBytesPerTriangle;
  return bytes + triangles * per_triangle + scene.instances.size() * kBytesPerShape;
}

MemoryEstimate estimate_memory(const SceneDescription& scene, uint64_t pixels, const PixelBytes& per_pixel,
                               int films, AccelKind accel, uint64_t texture_cache_bytes) {
  MemoryEstimate e;
  e.film = pixels * per_pixel.film * static_cast<uint64_t>(films);
  e.images = saturating_add(saturating_mul(pixels, per_pixel.images), per_pixel.writer);
  e.textures = texture_bytes(scene, TextureLimits{}, texture_cache_bytes);
  e.geometry = geometry_bytes(scene, accel);
  e.runtime = kRuntimeBytes;
  return e;
}

std::optional<uint64_t> parse_byte_size(const std::string& text) {
  std::size_t i = 0;
  uint64_t value = 0;
  while (i < text.size() && std::isdigit(static_cast<unsigned char>(text[i]))) {
    if (value > (UINT64_MAX - 9) / 10) return std::nullopt;
    value = value * 10 + static_cast<uint64_t>(text[i++] - '0');
  }
  if (i == 0) return std::nullopt;
  std::string unit = text.substr(i);
  for (char& c : unit) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  if (unit == "B" || unit.empty()) return value;
  int shift = 0;
  switch (unit[0]) {
    case 'K': shift = 10; break;
    case 'M': shift = 20; break;
    case 'G': shift = 30; break;
    case 'T': shift = 40; break;
    default: return std::nullopt;
  }
  const std::string rest = unit.substr(1);
  if (!(rest.empty() || rest == "B" || rest == "IB")) return std::nullopt;
  if (value > (UINT64_MAX >> shift)) return std::nullopt;
  return value << shift;
}

std::string byte_size_text(uint64_t bytes) {
  const char* units[] = {"bytes", "KiB", "MiB", "GiB", "TiB"};
  double v = static_cast<double>(bytes);
  int u = 0;
  while (v >= 1024.0 && u < 4) {
    v /= 1024.0;
    ++u;
  }
  char buf[48];
  if (u == 0)
    std::snprintf(buf, sizeof buf, "%llu bytes", static_cast<unsigned long long>(bytes));
  else
    std::snprintf(buf, sizeof buf, "%.2f %s", v, units[u]);
  return buf;
}

uint64_t physical_memory_bytes() {
  const long pages = ::sysconf(_SC_PHYS_PAGES);
  const long page = ::sysconf(_SC_PAGE_SIZE);
  if (pages <= 0 || page <= 0) return 0;
  return static_cast<uint64_t>(pages) * static_cast<uint64_t>(page);
}

std::string check_memory(const MemoryEstimate& e, uint64_t limit, uint64_t physical) {
  std::string detail = " (the process so far " + byte_size_text(e.baseline) + ", film " + byte_size_text(e.film) +
                       ", images " + byte_size_text(e.images) + ", textures " + byte_size_text(e.textures) +
                       ", geometry and acceleration structure " + byte_size_text(e.geometry) + ", threads and " +
                       "writers " + byte_size_text(e.runtime) + ")";
  if (e.peak_so_far > saturating_add(e.baseline, e.added()))
    detail = " (the peak while the scene was read " + byte_size_text(e.peak_so_far) + ")";
  if (limit > 0 && e.total() > limit)
    return "the render needs an estimated " + byte_size_text(e.total()) + detail + ", more than --max-memory " +
           byte_size_text(limit) + "; lower the resolution, crop, request fewer AOVs or raise the limit";
  if (physical > 0 && e.total() > physical)
    return "the render needs an estimated " + byte_size_text(e.total()) + detail +
           ", more than this machine's physical memory " + byte_size_text(physical) +
           "; lower the resolution, crop or request fewer AOVs";
  return {};
}

}  // namespace pt
