// The command line's outputs and the values it accepts (issue 20; docs/cli.md,
// "Outputs"): every output checked before rendering, no output that is an
// input or another output, failed writes that leave the old file, "did you
// mean" for unknown options, non-finite and out-of-range numbers refused.
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <tuple>
#include <vector>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include "app_fixture.h"

namespace pt::test {
namespace {

namespace fs = std::filesystem;

class CliOutputs : public AppTest {
 protected:
  void SetUp() override {
    AppTest::SetUp();
    write("s.json", path_scene(16, 12, 1));
  }
  // Runs with the file size limited to `kib` KiB (RLIMIT_FSIZE, as a full disk
  // would: writes beyond it fail with EFBIG; SIGXFSZ is ignored so that the
  // process sees the error instead of dying). /bin/sh's ulimit counts 512-byte
  // blocks.
  RunResult run_with_file_limit(const std::string& args, int kib) const {
    return run_command("trap '' XFSZ; ulimit -f " + std::to_string(kib * 2) + "; exec '" PT_PATHTRACER_EXE "' " + args);
  }
  // Writes `name` with `text` and returns it (the "old file" a failed write must keep).
  std::string old_file(const std::string& name, const std::string& text = "the old file") const {
    write(name, text);
    return text;
  }
};

// ---------------------------------------------------------------- before rendering

TEST_F(CliOutputs, MissingFolderIsFoundBeforeRenderingUnderTheUsersName) {
  for (const std::string args : {"-o nowhere/a.exr", "-o a.exr --report nowhere/run.json",
                                  "-o a.exr --checkpoint nowhere/c.ckpt"}) {
    const RunResult r = run("s.json --spp 100000 " + args);  // a render that would take minutes
    EXPECT_EQ(r.status, 2) << args << "\n" << r.err;
    EXPECT_NE(r.err.find("nowhere/"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("the folder 'nowhere' does not exist"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find(".tmp-"), std::string::npos) << "an internal name is shown: " << r.err;
    EXPECT_EQ(r.out, "") << r.out;
    EXPECT_FALSE(fs::exists(path("a.exr")));
  }
  write("file", "x");
  const RunResult r = run("s.json -o file/a.exr");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("cannot write -o 'file/a.exr': 'file' is not a folder"), std::string::npos) << r.err;
}

TEST_F(CliOutputs, UnwritableFolderIsFoundBeforeRendering) {
  if (::geteuid() == 0) GTEST_SKIP() << "root writes into a read-only folder anyway";
  fs::create_directories(path("ro"));
  ::chmod(path("ro").c_str(), 0555);
  const RunResult r = run("s.json -o ro/a.exr");
  ::chmod(path("ro").c_str(), 0755);
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("cannot write -o 'ro/a.exr': cannot create a file in the folder 'ro': Permission denied"),
            std::string::npos)
      << r.err;
}

TEST_F(CliOutputs, AnOutputThatIsNoRegularFileIsRefused) {
  fs::create_directories(path("dir.exr"));
  RunResult r = run("s.json -o dir.exr");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("cannot write -o 'dir.exr': it is a directory"), std::string::npos) << r.err;
  ASSERT_EQ(::mkfifo(path("fifo.json").c_str(), 0644), 0);
  r = run("s.json -o a.exr --report fifo.json");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("cannot write --report 'fifo.json': it is a FIFO (named pipe), not a regular file"),
            std::string::npos)
      << r.err;
  r = run("s.json -o a.exr --report /dev/null");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("--report '/dev/null': it is a character device"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(path("a.exr")));
}

TEST_F(CliOutputs, AnOutputThatIsAnInputIsRefused) {
  const std::string scene = slurp(path("s.json"));
  fs::create_directories(path("sub"));
  fs::create_symlink("s.json", path("link.json"));
  const std::vector<std::string> spellings = {"--checkpoint s.json", "--report ./s.json", "--report sub/../s.json",
                                              "--report link.json", "--checkpoint " + path("s.json")};
  for (const std::string& args : spellings) {
    const RunResult r = run("s.json -o a.exr " + args);
    EXPECT_EQ(r.status, 2) << args;
    EXPECT_NE(r.err.find("it is the scene file 's.json', which this run reads"), std::string::npos) << r.err;
    EXPECT_EQ(slurp(path("s.json")), scene);
    EXPECT_FALSE(fs::exists(path("a.exr")));
  }
  // A texture, a mesh and an environment map the scene names.
  OIIO::ImageSpec spec(4, 2, 3, OIIO::TypeDesc::UINT8);
  auto out = OIIO::ImageOutput::create("tex.png");
  ASSERT_TRUE(out && out->open(path("tex.png"), spec));
  const std::vector<unsigned char> px(4 * 2 * 3, 128);
  ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, px.data()) && out->close());
  write("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  write("t.json", R"({"format": "pathtracer-scene", "version": 1, "camera": {"position": [0, 1, 4], "look_at": [0, 0, 0]},
    "film": {"width": 8, "height": 6},
    "materials": {"wood": {"texture": "tex.png"}},
    "environment": {"file": "tex.png"},
    "shapes": [{"type": "mesh", "file": "tri.obj", "material": "wood"}]})");
  RunResult r = run("t.json -o tex.png");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("refusing to write -o 'tex.png': it is the texture 'tex.png' of the scene"), std::string::npos)
      << r.err;
  r = run("t.json -o a.exr --report tri.obj");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("it is the mesh 'tri.obj' of the scene"), std::string::npos) << r.err;
  EXPECT_EQ(slurp(path("tri.obj")), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
}

// The files an imported model reads are inputs too: an OBJ's MTL file and
// the textures it names, a glTF file's buffer and images.
TEST_F(CliOutputs, AnOutputThatAnImportReadsIsRefused) {
  const fs::path assets = fs::path(PT_TEST_DATA_DIR) / "data" / "assets";
  for (const char* f : {"obj/features.obj", "obj/features.mtl", "obj/mask.png", "obj/stripes.png", "gltf/pbr.gltf",
                        "gltf/pbr.bin", "gltf/base.png"}) {
    fs::create_directories(path(fs::path(f).parent_path().string()));
    fs::copy_file(assets / f, path(f), fs::copy_options::overwrite_existing);
  }
  const std::string mtl = slurp(path("obj/features.mtl"));
  for (const auto& [scene, output, what] :
       {std::tuple<std::string, std::string, std::string>{"obj/features.obj", "obj/features.mtl", "'features.mtl', which the import of"},
        {"obj/features.obj", "obj/stripes.png", "the texture 'stripes.png' of the scene"},
        {"gltf/pbr.gltf", "gltf/pbr.bin", "'pbr.bin', which the import of"},
        {"gltf/pbr.gltf", "gltf/base.png", "the texture 'base.png' of the scene"}}) {
    const RunResult r = run(scene + " --spp 1 --width 8 -o a.exr --report " + output);
    EXPECT_EQ(r.status, 2) << scene << " " << output;
    EXPECT_NE(r.err.find("refusing to write --report '" + output + "': it is " + what), std::string::npos) << r.err;
  }
  EXPECT_EQ(slurp(path("obj/features.mtl")), mtl);
  EXPECT_FALSE(fs::exists(path("a.exr")));
}

TEST_F(CliOutputs, AnOutputThatIsAnotherOutputIsRefused) {
  RunResult r = run("s.json -o a.exr --report a.exr");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("--report 'a.exr' is the same file as -o 'a.exr'"), std::string::npos) << r.err;
  r = run("s.json -o a.exr -o ./a.exr");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("-o './a.exr' is the same file as -o 'a.exr'"), std::string::npos) << r.err;
  r = run("s.json -o a.exr --checkpoint run.json --report run.json");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("--report 'run.json' is the same file as --checkpoint 'run.json'"), std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(path("a.exr")));
}

TEST_F(CliOutputs, ResumeCheckpointIsAnOutputOnlyAsTheCheckpoint) {
  ASSERT_EQ(run("s.json -o a.exr --spp 2 --checkpoint c.ckpt --quiet").status, 0);
  const std::string ckpt = slurp(path("c.ckpt"));
  RunResult r = run("s.json -o a.exr --spp 4 --resume c.ckpt --report c.ckpt");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("refusing to write --report 'c.ckpt': it is --resume's checkpoint 'c.ckpt'"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(slurp(path("c.ckpt")), ckpt);
  r = run("s.json -o a.exr --spp 4 --resume c.ckpt --checkpoint c.ckpt --quiet");
  EXPECT_EQ(r.status, 0) << r.err;  // goes on from it and updates it
  EXPECT_NE(slurp(path("c.ckpt")), ckpt);
}

TEST_F(CliOutputs, AovWithOnlyDisplayOutputsIsRefused) {
  const RunResult r = run("s.json -o a.png -o a.jpg --aov albedo");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("--aov: AOV layers are written to EXR outputs only, and no -o is an EXR (a.png, a.jpg)"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(path("a.png")));
  EXPECT_EQ(run("s.json -o a.png -o a.exr --aov albedo --quiet").status, 0);
}

// ---------------------------------------------------------------- a full disk

TEST_F(CliOutputs, EveryImageWriterReportsAFullDiskAndKeepsTheOldFile) {
  write("big.json", path_scene(256, 192, 1));  // every format's file is larger than 8 KiB
  for (const std::string name : {"a.exr", "a.png", "a.jpg", "a.ppm"}) {
    const std::string old = old_file(name);
    const RunResult r = run_with_file_limit("big.json --quiet -o " + name, 4);
    EXPECT_EQ(r.status, 1) << name << "\n" << r.err;
    EXPECT_NE(r.err.find("cannot write '" + name + "': "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("File too large"), std::string::npos) << r.err;
    EXPECT_EQ(slurp(path(name)), old) << name;
    EXPECT_FALSE(has_temporary_files()) << name;
  }
  // The same renders without the limit: the files are written.
  ASSERT_EQ(run("big.json --quiet -o a.exr -o a.png -o a.jpg -o a.ppm").status, 0);
  for (const std::string name : {"a.exr", "a.png", "a.jpg", "a.ppm"}) EXPECT_GT(fs::file_size(path(name)), 8192u);
}

TEST_F(CliOutputs, CheckpointAndReportWritersReportAFullDiskAndKeepTheOldFile) {
  // The checkpoint (16x12 pixels of 40 bytes) and the record exceed 2 KiB; the tiny PPM does not.
  write("tiny.json", path_scene(4, 3, 1));
  const std::string old_record = old_file("run.json");
  RunResult r = run_with_file_limit("tiny.json --quiet -o a.ppm --report run.json", 2);
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_NE(r.err.find("cannot write 'run.json': File too large"), std::string::npos) << r.err;
  EXPECT_EQ(slurp(path("run.json")), old_record);
  const std::string old_ckpt = old_file("c.ckpt");
  r = run_with_file_limit("s.json --quiet -o b.ppm --spp 2 --checkpoint c.ckpt", 2);
  EXPECT_NE(r.err.find("warning: checkpoint: cannot write 'c.ckpt': write failed: File too large"), std::string::npos)
      << r.err;
  EXPECT_EQ(slurp(path("c.ckpt")), old_ckpt);
  EXPECT_FALSE(has_temporary_files());
}

// ---------------------------------------------------------------- partial display images

TEST_F(CliOutputs, DisplayImagesCarryTheRenderMetadata) {
  ASSERT_EQ(run("s.json --quiet --spp 3 -o a.png -o a.jpg").status, 0);
  auto png = OIIO::ImageInput::open(path("a.png"));
  ASSERT_TRUE(png);
  EXPECT_EQ(png->spec().get_string_attribute("pathtracer:partial"), "0");
  EXPECT_EQ(png->spec().get_string_attribute("pathtracer:spp"), "3");
  EXPECT_EQ(png->spec().get_string_attribute("pathtracer:integrator"), "path");
  auto jpg = OIIO::ImageInput::open(path("a.jpg"));
  ASSERT_TRUE(jpg);
  const std::string comment = jpg->spec().get_string_attribute("ImageDescription");
  EXPECT_NE(comment.find("display: "), std::string::npos) << comment;
  EXPECT_NE(comment.find("\npathtracer:partial: 0"), std::string::npos) << comment;
  EXPECT_NE(comment.find("\npathtracer:spp: 3"), std::string::npos) << comment;
  EXPECT_NE(comment.find("\npathtracer:seed: 0"), std::string::npos) << comment;
}

// ---------------------------------------------------------------- options and values

TEST_F(CliOutputs, UnknownOptionsGetADidYouMean) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"--samples 4", "unknown option '--samples'; did you mean '--spp'?"},
      {"--spq 4", "unknown option '--spq'; did you mean '--spp'?"},
      {"--samples=4", "unknown option '--samples'; did you mean '--spp'?"},
      {"--time-bugdet 3", "unknown option '--time-bugdet'; did you mean '--time-budget'?"},
      {"--bounces 3", "unknown option '--bounces'; did you mean '--max-depth'?"},
      {"--xyzzy", "unknown option '--xyzzy'; see --help"},
  };
  for (const auto& [args, said] : cases) {
    const RunResult r = run("s.json -o a.exr " + args);
    EXPECT_EQ(r.status, 2) << args;
    EXPECT_NE(r.err.find("error: " + said), std::string::npos) << args << "\n" << r.err;
  }
  EXPECT_FALSE(fs::exists(path("a.exr")));
}

TEST_F(CliOutputs, NonFiniteNumbersAreRefused) {
  for (const std::string args : {"--time-budget nan", "--clamp nan", "--exposure nan", "--checkpoint-every nan",
                                  "--exposure inf", "--time-budget 1e999", "--progress-interval nan",
                                  "--crop 0,0,nan,1"}) {
    const RunResult r = run("s.json -o a.exr " + args);
    EXPECT_EQ(r.status, 2) << args << "\n" << r.err;
    EXPECT_NE(r.err.find("must be a finite number"), std::string::npos) << args << "\n" << r.err;
  }
  EXPECT_FALSE(fs::exists(path("a.exr")));
}

TEST_F(CliOutputs, SeedsOutsideTheirRangeAreRefused) {
  for (const std::string seed : {"-1", "18446744073709551616", "1e3", "0x10", ""}) {
    const RunResult r = run("s.json -o a.exr --seed '" + seed + "'");
    EXPECT_EQ(r.status, 2) << seed;
    EXPECT_NE(r.err.find("must be an integer in [0, 18446744073709551615]"), std::string::npos) << r.err;
  }
  const RunResult r = run("s.json -o a.exr --quiet --seed 18446744073709551615 --report run.json");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(read_json("run.json")["image"]["seed"].get<uint64_t>(), 18446744073709551615ull);
}

TEST_F(CliOutputs, ResumeFromAFifoDoesNotWait) {
  ASSERT_EQ(::mkfifo(path("c.ckpt").c_str(), 0644), 0);
  const RunResult r = run("s.json -o a.exr --resume c.ckpt");  // open() on a FIFO would wait for a writer
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("'c.ckpt': it is a FIFO (named pipe), not a regular file"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(path("a.exr")));
}

}  // namespace
}  // namespace pt::test
