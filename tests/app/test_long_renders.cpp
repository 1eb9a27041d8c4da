// Long renders from the command line (docs/cli.md): progress, time budget,
// signals, checkpoints and resume, atomic outputs, the run record.
#include <signal.h>

#include <chrono>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include "app_fixture.h"
#include "child_process.h"
#include "io/image_io.h"

namespace pt::test {
namespace {

using Clock = std::chrono::steady_clock;

// How long a test waits for a child before giving up on it: a guard against a
// hung suite, never a bound on speed (no test may bound process wall-clock
// time; the assertions are on what the program reports).
constexpr double kHangGuard = 300.0;

// The "pathtracer:*" header attributes of an EXR; false if it cannot be read.
bool read_render_metadata(const std::string& file, int& spp, int& partial) {
  auto in = OIIO::ImageInput::open(file);
  if (!in) return false;
  const OIIO::ImageSpec& spec = in->spec();
  spp = spec.get_int_attribute("pathtracer:spp", -1);
  partial = spec.get_int_attribute("pathtracer:partial", -1);
  return true;
}

bool same_pixels(const std::string& a, const std::string& b) {
  Image ia, ib;
  std::string error;
  if (!read_image(a, ia, error) || !read_image(b, ib, error)) return false;
  if (ia.width != ib.width || ia.height != ib.height) return false;
  for (std::size_t i = 0; i < ia.pixels.size(); ++i)
    if (ia.pixels[i].r != ib.pixels[i].r || ia.pixels[i].g != ib.pixels[i].g || ia.pixels[i].b != ib.pixels[i].b)
      return false;
  return true;
}

// The film state of a checkpoint: everything after its two header lines.
std::string film_state(const std::string& checkpoint) {
  std::size_t first = checkpoint.find('\n');
  std::size_t second = first == std::string::npos ? first : checkpoint.find('\n', first + 1);
  return second == std::string::npos ? std::string() : checkpoint.substr(second + 1);
}

class LongRender : public AppTest {
 protected:
  ChildProcess spawn(const std::vector<std::string>& args) const {
    return ChildProcess(PT_PATHTRACER_EXE, args, dir_.string());
  }
};

TEST_F(LongRender, ProgressLinesWhenStderrIsNotATerminal) {
  write("s.json", path_scene(64, 48, 1));
  const RunResult r = run("s.json -o a.exr --time-budget 1 --progress-interval 0.1");
  ASSERT_EQ(r.status, 0) << r.err;
  // Plain lines (no carriage-return redraws), each with a percentage, ETA and speed.
  EXPECT_NE(r.err.find("progress: "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("%, elapsed "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("ETA "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("samples/s"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find('\r'), std::string::npos);
  const RunResult quiet = run("s.json -o b.exr --time-budget 0.5 --progress-interval 0.1 --quiet");
  ASSERT_EQ(quiet.status, 0) << quiet.err;
  EXPECT_TRUE(quiet.err.empty()) << quiet.err;
}

TEST_F(LongRender, TimeBudgetIsHonoured) {
  write("s.json", path_scene(64, 48, 1));
  const RunResult r = run("s.json -o a.exr --time-budget 2 --report run.json --quiet");
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json rec = read_json("run.json");
  ASSERT_TRUE(rec.is_object());
  // Bounds on what the driver controls, on the render's own clock (not on the
  // process's wall-clock time, which a loaded machine stretches: start-up,
  // parsing and writing are not the budget's business): no pass starts once
  // the budget is spent (a started pass completes, and on a loaded machine
  // may take longer than planned, so the render's end is not bounded).
  const double render = rec["timings"]["render"].get<double>();
  const double last_pass = rec["progress"]["last_pass_seconds"].get<double>();
  EXPECT_GT(last_pass, 0.0) << rec.dump();
  EXPECT_LE(render - last_pass, 2.0 + 0.5) << rec.dump();  // + stopping the progress thread, setting up a pass
  EXPECT_GE(render, 1.0) << rec.dump();  // the budget is used (the scene's 1 spp is not the limit)
  EXPECT_GT(rec["progress"]["spp_reached"].get<int>(), 1);
  EXPECT_EQ(rec["progress"]["time_budget"].get<double>(), 2.0);
  EXPECT_FALSE(rec["progress"]["partial"].get<bool>());
  int spp = 0, partial = -1;
  ASSERT_TRUE(read_render_metadata(path("a.exr"), spp, partial));
  EXPECT_EQ(spp, rec["progress"]["spp_reached"].get<int>());
  EXPECT_EQ(partial, 0);
}

TEST_F(LongRender, SppAndTimeBudgetStopAtWhicheverComesFirst) {
  write("s.json", path_scene(32, 24, 1));
  const RunResult r = run("s.json -o a.exr --time-budget 600 --spp 5 --report run.json --quiet");
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json rec = read_json("run.json");
  EXPECT_EQ(rec["progress"]["spp_reached"], 5);
  EXPECT_LT(rec["timings"]["render"].get<double>(), 60.0);
  // Jittered samples come in equal passes (each stratified on its own) that divide the target.
  ASSERT_EQ(run("s.json -o j.exr --time-budget 600 --spp 12 --sampler jittered --pass-spp 5 --report j.json").status, 0);
  const nlohmann::json jit = read_json("j.json");
  EXPECT_EQ(jit["progress"]["spp_reached"], 12);
  EXPECT_EQ(jit["progress"]["passes"], 3);  // passes of 4, the largest divisor of 12 not above 5
}

// Sends `signal_number` once the child has printed progress; expects exit status 128 + it.
void interrupt_after_progress(ChildProcess& child, int signal_number) {
  ASSERT_TRUE(child.wait_for_output("progress: ", kHangGuard)) << child.err();
  child.send(signal_number);
  EXPECT_EQ(child.wait(kHangGuard), 128 + signal_number) << child.err();
  EXPECT_NE(child.err().find("wrote partial"), std::string::npos) << child.err();
}

TEST_F(LongRender, SigintWritesPartialOutputsAndExitsWith130) {
  write("s.json", path_scene(64, 48, 1));
  ChildProcess child = spawn({"s.json", "-o", "p.exr", "-o", "p.png", "--time-budget", "120", "--progress-interval",
                              "0.1", "--report", "run.json"});
  ASSERT_TRUE(child.started());
  interrupt_after_progress(child, SIGINT);
  int spp = 0, partial = 0;
  ASSERT_TRUE(read_render_metadata(path("p.exr"), spp, partial));
  EXPECT_EQ(partial, 1);
  EXPECT_GE(spp, 0);
  Image img;
  std::string error;
  ASSERT_TRUE(read_image(path("p.exr"), img, error)) << error;  // complete and readable
  EXPECT_EQ(img.width, 64);
  EXPECT_TRUE(read_image(path("p.png"), img, error)) << error;
  const nlohmann::json rec = read_json("run.json");
  EXPECT_TRUE(rec["progress"]["partial"].get<bool>());
  EXPECT_EQ(rec["progress"]["signal"], SIGINT);
  EXPECT_EQ(rec["progress"]["spp_reached"], spp);
  EXPECT_FALSE(has_temporary_files());
}

// One pass of 2^20 samples in each pixel of one 16x16 tile, on one thread:
// minutes of work. Before issue 20 the signal was seen only between tiles, so
// the render went on to the tile's end; now it stops inside the pixel. The
// test asserts what the program reports, not how long it took: the samples it
// rendered are fewer than the tile's, the outputs are marked partial, and the
// record agrees with the image's sample counts.
TEST_F(LongRender, SigintStopsInsideALongPass) {
  write("s.json", path_scene(16, 16, 1));
  ChildProcess child = spawn({"s.json", "-o", "p.exr", "-o", "p.png", "--spp", "1048576", "--threads", "1",
                              "--aov", "samples", "--progress-interval", "0.05", "--report", "run.json"});
  ASSERT_TRUE(child.started());
  interrupt_after_progress(child, SIGINT);
  const nlohmann::json rec = read_json("run.json");
  ASSERT_TRUE(rec.is_object());
  EXPECT_TRUE(rec["progress"]["partial"].get<bool>());
  EXPECT_EQ(rec["progress"]["spp_reached"], 0);  // the one pass did not complete
  EXPECT_EQ(rec["progress"]["passes"], 0);
  const int64_t rendered = rec["performance"]["pixel_samples"].get<int64_t>();
  EXPECT_GT(rendered, 0);
  EXPECT_LT(rendered, int64_t{16} * 16 * 1048576) << "the whole tile was rendered after the signal";
  // The samples layer holds each pixel's own count: they add up to the record's.
  auto in = OIIO::ImageInput::open(path("p.exr"));
  ASSERT_TRUE(in);
  EXPECT_EQ(in->spec().get_int_attribute("pathtracer:partial", -1), 1);
  int c = -1;  // "samples", or a name with a component suffix ("samples.X")
  std::string names;
  for (int i = 0; i < in->spec().nchannels; ++i) {
    const std::string name(in->spec().channel_name(i));
    names += name + " ";
    if (name.rfind("samples", 0) == 0) c = i;
  }
  ASSERT_GE(c, 0) << names;
  std::vector<float> counts(16 * 16);
  ASSERT_TRUE(in->read_image(0, 0, c, c + 1, OIIO::TypeFloat, counts.data())) << in->geterror();
  double sum = 0;
  for (float n : counts) sum += n;
  EXPECT_EQ(sum, static_cast<double>(rendered));
  auto png = OIIO::ImageInput::open(path("p.png"));
  ASSERT_TRUE(png);
  EXPECT_EQ(png->spec().get_string_attribute("pathtracer:partial"), "1");
}

// Two runs writing one name: another program writes out.exr (and the record)
// while this render runs; neither is replaced, and this run's files are kept
// beside them under names of their own.
TEST_F(LongRender, AnOutputChangedDuringTheRenderIsNotReplaced) {
  write("s.json", path_scene(16, 16, 1));
  ChildProcess child = spawn({"s.json", "-o", "out.exr", "--spp", "1048576", "--threads", "1", "--progress-interval",
                              "0.05", "--report", "run.json"});
  ASSERT_TRUE(child.started());
  const std::string pid = std::to_string(child.pid());  // wait() forgets it
  ASSERT_TRUE(child.wait_for_output("progress: ", kHangGuard)) << child.err();
  write("out.exr", "written by another render");
  write("run.json", "{}");
  child.send(SIGINT);
  EXPECT_EQ(child.wait(kHangGuard), 1) << child.err();
  EXPECT_NE(child.err().find("'out.exr' was changed by another program while this run went on"), std::string::npos)
      << child.err();
  EXPECT_NE(child.err().find("this run's file is 'out.conflict-" + pid + ".exr'"), std::string::npos) << child.err();
  EXPECT_EQ(slurp(path("out.exr")), "written by another render");
  EXPECT_EQ(slurp(path("run.json")), "{}");
  int spp = 0, partial = 0;
  ASSERT_TRUE(read_render_metadata(path("out.conflict-" + pid + ".exr"), spp, partial));
  EXPECT_EQ(partial, 1);
  EXPECT_TRUE(read_json("run.conflict-" + pid + ".json").is_object());
  EXPECT_FALSE(has_temporary_files());
}

TEST_F(LongRender, SigtermExitsWith143) {
  write("s.json", path_scene(64, 48, 1));
  ChildProcess child = spawn({"s.json", "-o", "t.exr", "--time-budget", "120", "--progress-interval", "0.1"});
  ASSERT_TRUE(child.started());
  interrupt_after_progress(child, SIGTERM);
  int spp = 0, partial = 0;
  ASSERT_TRUE(read_render_metadata(path("t.exr"), spp, partial));
  EXPECT_EQ(partial, 1);
  EXPECT_FALSE(has_temporary_files());
}

TEST_F(LongRender, ResumedRenderIsBitIdenticalToAnUninterruptedOne) {
  write("s.json", path_scene(48, 32, 1));
  // Uninterrupted: 8 spp in passes of 2 (its final checkpoint holds the exact film sums).
  ASSERT_EQ(run("s.json -o full.exr --spp 8 --pass-spp 2 --seed 7 --checkpoint full.ckpt --quiet").status, 0);
  // Stopped after 4 spp, then resumed to 8.
  ASSERT_EQ(run("s.json -o half.exr --spp 4 --pass-spp 2 --seed 7 --checkpoint half.ckpt --quiet").status, 0);
  const RunResult r = run("s.json -o resumed.exr --spp 8 --pass-spp 2 --seed 7 --resume half.ckpt "
                          "--checkpoint resumed.ckpt --report run.json --quiet");
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string full = film_state(slurp(path("full.ckpt")));
  ASSERT_FALSE(full.empty());
  EXPECT_TRUE(full == film_state(slurp(path("resumed.ckpt"))));  // every double of every pixel
  EXPECT_NE(full, film_state(slurp(path("half.ckpt"))));
  EXPECT_TRUE(same_pixels(path("full.exr"), path("resumed.exr")));
  EXPECT_EQ(read_json("run.json")["progress"]["resumed_spp"], 4);
}

TEST_F(LongRender, RenderInterruptedBySigintResumesFromItsLastCheckpoint) {
  write("s.json", path_scene(96, 64, 1));
  ChildProcess child = spawn({"s.json", "-o", "cut.exr", "--spp", "256", "--pass-spp", "1", "--checkpoint", "cut.ckpt",
                              "--checkpoint-every", "0", "--progress-interval", "0.1"});
  ASSERT_TRUE(child.started());
  ASSERT_TRUE(child.wait_for_output("progress: ", kHangGuard)) << child.err();
  for (int i = 0; i < 200 && !std::filesystem::exists(path("cut.ckpt")); ++i) child.wait_for_output("\x01", 0.05);
  child.send(SIGINT);
  ASSERT_EQ(child.wait(kHangGuard), 130) << child.err();
  ASSERT_TRUE(std::filesystem::exists(path("cut.ckpt")));
  const std::string header = slurp(path("cut.ckpt")).substr(0, 400);
  const std::size_t at = header.find("\"spp_done\":");
  ASSERT_NE(at, std::string::npos);
  const int done = std::stoi(header.substr(at + 11));
  ASSERT_GT(done, 0);
  ASSERT_LT(done, 256) << "the render finished before the signal; nothing to resume";
  const int target = done + 2;  // resume a little further, and render the same without interruption
  const std::string common = " --spp " + std::to_string(target) + " --pass-spp 1 --quiet";
  ASSERT_EQ(run("s.json -o resumed.exr --resume cut.ckpt --checkpoint resumed.ckpt" + common).status, 0);
  ASSERT_EQ(run("s.json -o full.exr --checkpoint full.ckpt" + common).status, 0);
  EXPECT_TRUE(film_state(slurp(path("full.ckpt"))) == film_state(slurp(path("resumed.ckpt"))));
  EXPECT_TRUE(same_pixels(path("full.exr"), path("resumed.exr")));
}

TEST_F(LongRender, ResumeRefusesADifferentSceneOrSettings) {
  write("s.json", path_scene(32, 24, 1));
  ASSERT_EQ(run("s.json -o a.exr --spp 2 --checkpoint a.ckpt --quiet").status, 0);
  RunResult r = run("s.json -o b.exr --spp 4 --seed 5 --resume a.ckpt");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("seed 0 -> 5"), std::string::npos) << r.err;
  r = run("s.json -o b.exr --spp 4 --width 16 --resume a.ckpt");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("width 32 -> 16"), std::string::npos) << r.err;
  r = run("s.json -o b.exr --spp 4 --set camera.fov=30 --resume a.ckpt");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("the scene differs"), std::string::npos) << r.err;
  write("s.json", path_scene(32, 24, 3));  // the file changed
  r = run("s.json -o b.exr --spp 4 --resume a.ckpt");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("the scene differs"), std::string::npos) << r.err;
  write("junk.ckpt", "not a checkpoint\n");
  r = run("s.json -o b.exr --resume junk.ckpt");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("not a pathtracer checkpoint"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(path("b.exr")));
}

TEST_F(LongRender, FailedWriteLeavesTheOldFileAndNoTemporary) {
  write("s.json", path_scene(32, 24, 1));
  write("old.exr", "the old content");
  // The first output's folder does not exist: the run is refused before it renders.
  const RunResult r = run("s.json -o missing/a.exr -o old.exr --spp 1");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("missing/a.exr"), std::string::npos) << r.err;
  EXPECT_EQ(slurp(path("old.exr")), "the old content");
  EXPECT_FALSE(has_temporary_files());
}

TEST_F(LongRender, KillDuringAWriteLeavesTheOldImageWhole) {
  // A large, fast image (writing it takes ~0.2 s). The test waits until the
  // atomic writer's temporary file appears (atomic_file.cpp names it
  // "<path>.tmp-<pid>"), i.e. the write is under way, then kills the process
  // with SIGKILL: out.exr must still be the previous image, byte for byte.
  write("s.json", path_scene(1600, 1200, 1));
  ASSERT_EQ(run("s.json -o out.exr --spp 1 --max-depth 0 --seed 1 --quiet").status, 0);
  const std::string old = slurp(path("out.exr"));
  int caught = 0;
  for (int attempt = 0; attempt < 3; ++attempt) {
    ChildProcess child = spawn({"s.json", "-o", "out.exr", "--spp", "1", "--max-depth", "0", "--seed", "2", "--quiet"});
    ASSERT_TRUE(child.started());
    const std::string tmp = path("out.exr.tmp-" + std::to_string(child.pid()));
    const auto end = Clock::now() + std::chrono::duration<double>(kHangGuard);
    while (!std::filesystem::exists(tmp) && Clock::now() < end && child.wait(0.001) < 0) {
    }
    if (std::filesystem::exists(tmp)) {
      child.send(SIGKILL);
      ++caught;
    }
    child.wait(10.0);
    if (std::filesystem::exists(tmp)) {
      EXPECT_EQ(slurp(path("out.exr")), old) << "attempt " << attempt;  // the old image, whole
      std::filesystem::remove(tmp);  // SIGKILL leaves no chance to clean up
    } else {
      Image img;  // the write finished first: the new image, whole
      std::string error;
      EXPECT_TRUE(read_image(path("out.exr"), img, error)) << error;
      EXPECT_EQ(img.width, 1600);
    }
  }
  EXPECT_GT(caught, 0) << "no kill landed during a write";
}

TEST_F(LongRender, RunRecordHasVersionsSpeedAndMemory) {
  write("s.json", path_scene(32, 24, 3));
  ASSERT_EQ(run("s.json -o a.exr --report run.json --quiet").status, 0);
  const nlohmann::json rec = read_json("run.json");
  ASSERT_TRUE(rec.is_object());
  const nlohmann::json& sw = rec["software"];
  EXPECT_FALSE(sw["embree"]["version"].get<std::string>().empty());
  EXPECT_EQ(sw["embree"]["version"].get<std::string>().substr(0, 2), "3.");
  EXPECT_NE(sw["embree"]["tasking_system"], "unknown");
  EXPECT_FALSE(sw["openimageio"].get<std::string>().empty());
  EXPECT_FALSE(sw["openexr"].get<std::string>().empty());
  EXPECT_FALSE(sw["opencolorio"].get<std::string>().empty());
  EXPECT_FALSE(sw["tbb"].get<std::string>().empty());
  EXPECT_FALSE(sw["compiler"]["name"].get<std::string>().empty());
  EXPECT_EQ(rec["image"]["spp"], 3);
  EXPECT_EQ(rec["progress"]["spp_reached"], 3);
  EXPECT_EQ(rec["progress"]["partial"], false);
  EXPECT_EQ(rec["performance"]["pixel_samples"], 32 * 24 * 3);
  EXPECT_GT(rec["performance"]["samples_per_second"].get<double>(), 0.0);
  EXPECT_GE(rec["performance"]["rays"].get<int64_t>(), 32 * 24 * 3);  // at least every camera ray
  EXPECT_GT(rec["performance"]["rays_per_second"].get<double>(), 0.0);
  EXPECT_GT(rec["performance"]["render_cpu_seconds"].get<double>(), 0.0);  // the render phase did work
  EXPECT_GT(rec["memory"]["peak_rss_bytes"].get<double>(), 1e6);  // at least the executable's own pages
  EXPECT_GE(rec["memory"]["estimate_bytes"].get<double>(), 32.0 * 24 * 40);  // at least the film
  for (const char* phase :
       {"parse", "mesh_load", "texture_load", "scene_build", "accel_build", "render", "write", "total"})
    EXPECT_GE(rec["timings"][phase].get<double>(), 0.0) << phase;
}

}  // namespace
}  // namespace pt::test
