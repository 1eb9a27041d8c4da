// Student-style course files of our own (tests/scene/student-files/README.md),
// each mixing several of the spellings the courses left to their students:
// every file loads without an error, warns exactly where its reading is an
// assumption, and renders lit (not black, not background only) with the
// integrator the file picks.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/parallel.h"
#include "render/film/film.h"
#include "render/integrators/integrator.h"
#include "render/render_scene.h"
#include "scene/loader.h"

namespace pt {
namespace {

struct StudentFile {
  const char* name;
  std::vector<const char*> warnings;  // one entry per expected warning (a part of its text)
};

void PrintTo(const StudentFile& f, std::ostream* os) { *os << f.name; }

class CourseStudentFiles : public ::testing::TestWithParam<StudentFile> {};

// Share of the pixels brighter than the background by more than 0.02 in some channel.
double lit_share(const Image& img, const RGB& background) {
  std::size_t lit = 0;
  for (const RGB& p : img.pixels)
    lit += p.r > background.r + 0.02f || p.g > background.g + 0.02f || p.b > background.b + 0.02f;
  return static_cast<double>(lit) / static_cast<double>(img.pixels.size());
}

TEST_P(CourseStudentFiles, LoadWithTheirWarningsAndRenderLit) {
  const StudentFile& file = GetParam();
  const std::string path = std::string(PT_TEST_DATA_DIR) + "/scene/student-files/" + file.name;
  Diagnostics diag;
  const auto desc = load_scene(path, LoadOptions{}, diag);
  ASSERT_TRUE(desc) << diag.format();
  EXPECT_EQ(diag.error_count(), 0) << diag.format();
  EXPECT_EQ(diag.warning_count(), static_cast<int>(file.warnings.size())) << diag.format();
  for (const char* text : file.warnings)
    EXPECT_NE(diag.format().find(text), std::string::npos) << text << "\n" << diag.format();

  WorkerPool pool(2);
  const auto scene = build_render_scene(*desc, BuildOptions{}, pool, diag);
  ASSERT_TRUE(scene) << diag.format();
  IntegratorSettings settings;
  settings.spp = desc->render.spp.value;
  settings.max_depth = desc->render.max_depth.value;
  std::string error;
  const auto integrator = make_integrator(desc->render.integrator.value, settings, error);
  ASSERT_TRUE(integrator) << error;
  Film film(scene->width, scene->height);
  integrator->render(*scene, film, pool);
  // Each file's lit subject covers a quarter to a half of its frame (0.22 to 0.56
  // measured on the 8-bit images); a dropped light leaves none of it.
  EXPECT_GT(lit_share(film.image(), desc->render.background.value), 0.1);
}

INSTANTIATE_TEST_SUITE_P(
    Files, CourseStudentFiles,
    ::testing::Values(
        StudentFile{"soft_shadows.json", {"area light 'position' taken as the centre"}},
        StudentFile{"lamp_on_a_ball.json",
                    {"choose the sampler with --sampler", "unknown camera type 'perspective'; rendered with a pinhole",
                     "zig-zag order: taken as v0, v1, v3, v2"}},
        StudentFile{"ply_and_glass.json",
                    {"'aperture' taken as the lens diameter", "'focal_length' taken as the distance",
                     "kt 0.9 taken as a fully transparent dielectric", "taken as a parallelogram"}},
        StudentFile{"cgr_dof.json", {"'aperture' taken as the lens diameter"}}),
    [](const ::testing::TestParamInfo<StudentFile>& p) {
      std::string name = p.param.name;
      return name.substr(0, name.find('.'));
    });

}  // namespace
}  // namespace pt
