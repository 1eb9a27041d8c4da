// A temporary folder to run the pathtracer in, for the command-line tests.
#pragma once

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "io/image_io.h"
#include "scratch_dir_test.h"

namespace pt::test {

using RunResult = CommandResult;

// A native scene for the path integrator: a diffuse sphere on a floor under an
// area light; `width` x `height` pixels, `spp` samples.
inline std::string path_scene(int width, int height, int spp) {
  return R"({"format": "pathtracer-scene", "version": 1,
  "camera": {"position": [0, 1, 4], "look_at": [0, 0.5, 0], "fov": 40},
  "film": {"width": )" + std::to_string(width) + R"(, "height": )" + std::to_string(height) + R"(},
  "render": {"integrator": "path", "max_depth": 8, "spp": )" + std::to_string(spp) + R"(},
  "materials": {
    "white": {"type": "lambert", "diffuse": [0.7, 0.7, 0.7]},
    "light": {"type": "lambert", "diffuse": [0, 0, 0], "emission": [8, 8, 8]}
  },
  "shapes": [
    {"type": "sphere", "center": [0, 0.5, 0], "radius": 0.5, "material": "white"},
    {"type": "quad", "vertices": [[-3, 0, -3], [-3, 0, 3], [3, 0, 3], [3, 0, -3]], "material": "white"},
    {"type": "quad", "vertices": [[-0.5, 2.5, -0.5], [0.5, 2.5, -0.5], [0.5, 2.5, 0.5], [-0.5, 2.5, 0.5]], "material": "light"}
  ]
})";
}

// A sphere in front of a backdrop image `backdrop` (write it with
// AppTest::write_image): camera rays that miss the sphere see it. With a
// backdrop of +Inf their samples are +Inf. (The values a scene writes are
// bounded so that paths cannot overflow, docs/scene-format.md "Value limits",
// and environment maps are checked texel by texel; a backdrop image is not,
// and is the way left to make the renderer meet non-finite samples.)
inline std::string backdrop_scene(const std::string& backdrop, int width, int height, int spp) {
  return R"({"format": "pathtracer-scene", "version": 1,
  "camera": {"position": [0, 1, 4], "look_at": [0, 0.5, 0], "fov": 40},
  "film": {"width": )" + std::to_string(width) + R"(, "height": )" + std::to_string(height) + R"(},
  "render": {"integrator": "path", "max_depth": 8, "spp": )" + std::to_string(spp) +
         R"(, "background_image": ")" + backdrop + R"("},
  "materials": {"white": {"type": "lambert", "diffuse": [0.9, 0.9, 0.9]}},
  "shapes": [{"type": "sphere", "center": [0, 0.5, 0], "radius": 0.5, "material": "white"}]
})";
}

class AppTest : public ScratchDirTest {
 protected:
  AppTest() : ScratchDirTest("pt_app_test_") {}

  void write(const std::string& name, const std::string& text) const { std::ofstream(path(name)) << text; }
  // Writes a w x h RGB float EXR of `value` (pt::write_image, through the image module).
  void write_image(const std::string& name, int w, int h, float value) const {
    Image image(w, h);
    for (RGB& p : image.pixels) p = RGB(value);
    std::string error;
    ASSERT_TRUE(pt::write_image(path(name), image, DisplaySettings{}, error)) << error;
  }
  nlohmann::json read_json(const std::string& name) const {
    return nlohmann::json::parse(slurp(path(name)), nullptr, false);
  }

  // Runs the executable in the folder with `args` (a shell word list) and
  // `env` (shell assignments, e.g. "OCIO=config.ocio") in its environment.
  RunResult run(const std::string& args, const std::string& env = "") const {
    return run_command(env + " '" PT_PATHTRACER_EXE "' " + args);
  }

  // Names of the files in the folder.
  std::vector<std::string> files() const {
    std::vector<std::string> names;
    for (const auto& e : std::filesystem::directory_iterator(dir_)) names.push_back(e.path().filename().string());
    return names;
  }
  // True if any file name contains ".tmp" (atomic writes' temporaries).
  bool has_temporary_files() const {
    for (const std::string& n : files())
      if (n.find(".tmp") != std::string::npos) return true;
    return false;
  }
};

}  // namespace pt::test
