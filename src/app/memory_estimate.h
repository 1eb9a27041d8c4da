// Pre-flight memory estimate (docs/cli.md): before the scene is built and the
// film allocated, the bytes the render will need, compared with the physical
// memory and `--max-memory`.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

namespace pt {

struct SceneDescription;

struct MemoryEstimate {
  uint64_t film = 0;      // film_bytes_per_pixel per pixel (+ a second film when resuming)
  uint64_t images = 0;    // the float RGB image and the largest output buffer
  uint64_t geometry = 0;  // scene geometry and acceleration structure, from primitive counts
  uint64_t total() const { return film + images + geometry; }
};

// `film_bytes_per_pixel`: sizeof(PixelSum) for the beauty film; with AOV layers
// the caller adds theirs. `films`: how many films exist at once.
MemoryEstimate estimate_memory(const SceneDescription& scene, int width, int height,
                               uint64_t film_bytes_per_pixel, int films = 1);

// "4G", "512M", "64k", "1000" (bytes; K/M/G/T are powers of 1024, an optional
// trailing "B"/"iB" is accepted). std::nullopt for anything else.
std::optional<uint64_t> parse_byte_size(const std::string& text);
std::string byte_size_text(uint64_t bytes);  // "1.50 GiB"

// Physical memory (sysconf), 0 if unknown.
uint64_t physical_memory_bytes();

// An error message when `estimate` exceeds `limit` (0: no limit) or the
// physical memory; empty otherwise.
std::string check_memory(const MemoryEstimate& estimate, uint64_t limit, uint64_t physical);

}  // namespace pt
