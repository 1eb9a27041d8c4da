// The image module (src/imagelib/image_library.h): OpenImageIO is loaded only
// when an image is read or written, through pt_oiio.so, and a module that
// cannot be loaded is a clear error before anything is rendered. The
// dynamic loader itself says what the process loaded (LD_DEBUG=files lists
// every object it maps, with who needed or dlopen'ed it). This test does not
// link OpenImageIO either.
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "scratch_dir_test.h"

namespace pt::test {
namespace {

constexpr const char* kScene = R"({"format": "pathtracer-scene", "version": 1,
  "camera": {"position": [0, 1, 4], "look_at": [0, 0.5, 0], "fov": 40},
  "film": {"width": 8, "height": 6},
  "render": {"integrator": "path", "max_depth": 4, "spp": 1},
  "materials": {"white": {"type": "lambert", "diffuse": [0.7, 0.7, 0.7]},
                "light": {"type": "lambert", "diffuse": [0, 0, 0], "emission": [8, 8, 8]}},
  "shapes": [{"type": "sphere", "center": [0, 0.5, 0], "radius": 0.5, "material": "white"},
             {"type": "sphere", "center": [0, 3, 0], "radius": 0.5, "material": "light"}]
})";

class ImageModule : public ScratchDirTest {
 protected:
  ImageModule() : ScratchDirTest("pt_image_module_") {}
  void SetUp() override {
    ScratchDirTest::SetUp();
    std::ofstream(path("s.json")) << kScene;
  }
  // Runs the executable with LD_DEBUG=files (its report goes to stderr) and `env`.
  CommandResult run(const std::string& args, const std::string& env = "") const {
    return run_command("LD_DEBUG=files " + env + " '" PT_PATHTRACER_EXE "' " + args);
  }
  static bool mapped(const CommandResult& r, const std::string& object) {
    return r.err.find("file=") != std::string::npos && r.err.find(object) != std::string::npos;
  }
  bool exists(const std::string& name) const { return std::filesystem::exists(path(name)); }
  bool has_temporary_files() const {
    for (const auto& e : std::filesystem::directory_iterator(dir_))
      if (e.path().filename().string().find(".tmp") != std::string::npos) return true;
    return false;
  }
};

// The loader's report is there (libc is always mapped), so a missing name means something.
void expect_loader_report(const CommandResult& r) {
  EXPECT_NE(r.err.find("file=libc.so.6"), std::string::npos) << "no LD_DEBUG report:\n" << r.err.substr(0, 2000);
}

TEST_F(ImageModule, VersionHelpAndUsageErrorsLoadNoOpenImageIO) {
  const CommandResult v = run("--version");
  EXPECT_EQ(v.status, 0) << v.err.substr(0, 2000);
  expect_loader_report(v);
  EXPECT_FALSE(mapped(v, "libOpenImageIO")) << "--version loaded OpenImageIO";
  EXPECT_FALSE(mapped(v, "pt_oiio.so"));
  // It still names OpenImageIO's version and where the module is.
  EXPECT_NE(v.out.find("OpenImageIO"), std::string::npos) << v.out;
  EXPECT_NE(v.out.find("pt_oiio.so"), std::string::npos) << v.out;

  for (const char* args : {"--help", "s.json --samples 4 -o a.exr", "missing.json -o a.exr"}) {
    const CommandResult r = run(args);
    EXPECT_EQ(r.status == 0, std::string(args) == "--help") << args;
    expect_loader_report(r);
    EXPECT_FALSE(mapped(r, "libOpenImageIO")) << args << " loaded OpenImageIO";
  }
  EXPECT_FALSE(exists("a.exr"));
}

TEST_F(ImageModule, APpmRenderWithoutImagesLoadsNoOpenImageIO) {
  const CommandResult r = run("s.json -o out.ppm --quiet");
  ASSERT_EQ(r.status, 0) << r.err.substr(0, 2000);
  expect_loader_report(r);
  EXPECT_TRUE(exists("out.ppm"));
  EXPECT_FALSE(mapped(r, "libOpenImageIO"));
  EXPECT_FALSE(mapped(r, "pt_oiio.so"));
}

TEST_F(ImageModule, AnExrRenderOpensTheModuleWhichBringsOpenImageIO) {
  const CommandResult r = run("s.json -o out.exr --quiet");
  ASSERT_EQ(r.status, 0) << r.err.substr(0, 2000);
  EXPECT_TRUE(exists("out.exr"));
  // Opened with dlopen by the executable, not needed by it at start-up.
  const std::size_t at = r.err.find("pt_oiio.so [0];  dynamically loaded by");
  EXPECT_NE(at, std::string::npos) << "pt_oiio.so not dlopen'ed";
  EXPECT_TRUE(mapped(r, "libOpenImageIO"));
  EXPECT_LT(at, r.err.find("file=libOpenImageIO"));
}

// Nothing is rendered and nothing written when an output needs a module that
// cannot be loaded; the message names the module's path.
TEST_F(ImageModule, AMissingModuleIsAClearErrorBeforeRendering) {
  const std::string module = path("nowhere/pt_oiio.so");
  for (const char* out : {"out.exr", "out.png", "out.jpg"}) {
    const CommandResult r = run_command("PT_OIIO_MODULE='" + module + "' '" PT_PATHTRACER_EXE "' s.json -o " +
                                        out + " --report run.json");
    EXPECT_EQ(r.status, 1) << out;
    EXPECT_NE(r.err.find("cannot load the image module '" + module + "' (set by $PT_OIIO_MODULE)"),
              std::string::npos)
        << r.err;
    EXPECT_EQ(r.err.find("render"), std::string::npos) << "it rendered first:\n" << r.err;
    EXPECT_FALSE(exists(out));
    EXPECT_FALSE(exists("run.json"));
    EXPECT_FALSE(has_temporary_files());
  }
  // --version says where it looked; a PPM needs no module.
  const CommandResult v = run_command("PT_OIIO_MODULE='" + module + "' '" PT_PATHTRACER_EXE "' --version");
  EXPECT_NE(v.out.find(module + ", set by $PT_OIIO_MODULE, missing"), std::string::npos) << v.out;
  const CommandResult ppm =
      run_command("PT_OIIO_MODULE='" + module + "' '" PT_PATHTRACER_EXE "' s.json -o out.ppm --quiet");
  EXPECT_EQ(ppm.status, 0) << ppm.err;
  EXPECT_TRUE(exists("out.ppm"));
}

TEST_F(ImageModule, ACorruptOrForeignModuleIsAClearError) {
  std::ofstream(path("pt_oiio.so")) << "not a shared object\n";
  const CommandResult corrupt =
      run_command("PT_OIIO_MODULE=./pt_oiio.so '" PT_PATHTRACER_EXE "' s.json -o out.exr --quiet");
  EXPECT_EQ(corrupt.status, 1);
  EXPECT_NE(corrupt.err.find("cannot load the image module './pt_oiio.so' (set by $PT_OIIO_MODULE): "), std::string::npos) << corrupt.err;
  EXPECT_FALSE(exists("out.exr"));
  // A shared object that is not a pathtracer image module (the C library's libm).
  const CommandResult foreign =
      run_command("PT_OIIO_MODULE=libm.so.6 '" PT_PATHTRACER_EXE "' s.json -o out.exr --quiet");
  EXPECT_EQ(foreign.status, 1);
  EXPECT_NE(foreign.err.find("'libm.so.6' (set by $PT_OIIO_MODULE): it is not a pathtracer image module"),
            std::string::npos)
      << foreign.err;
  EXPECT_FALSE(exists("out.exr"));
  EXPECT_FALSE(has_temporary_files());
}

}  // namespace
}  // namespace pt::test
