// Attributes written into an image's header: EXR header attributes (typed) and,
// for PNG/JPEG, text entries where the format has them (PPM has none).
// Names follow OpenEXR's standard attributes where one exists (worldToCamera,
// worldToNDC, chromaticities, ...) and use the "pathtracer:" prefix otherwise.
#pragma once

#include <array>
#include <string>
#include <utility>
#include <vector>

namespace pt {

struct ImageMetadata {
  using Matrix = std::array<float, 16>;  // row-major, as OpenEXR's M44f
  std::vector<std::pair<std::string, std::string>> strings;
  std::vector<std::pair<std::string, int>> ints;
  std::vector<std::pair<std::string, float>> floats;
  std::vector<std::pair<std::string, Matrix>> matrices;

  void set(const std::string& name, const std::string& value) { strings.emplace_back(name, value); }
  void set(const std::string& name, const char* value) { strings.emplace_back(name, value); }
  void set(const std::string& name, int value) { ints.emplace_back(name, value); }
  void set(const std::string& name, float value) { floats.emplace_back(name, value); }
  void set(const std::string& name, const Matrix& value) { matrices.emplace_back(name, value); }
};

}  // namespace pt
