// Distributed rendering from the command line (docs/distributed.md): shards
// of samples and tiles merged by `pathtracer merge`, bit for bit equal to the
// render on one machine; what the merge refuses; time-budget shards; the MPI
// launcher (mpirun, when this build has it) and the Slurm script (with a
// stand-in sbatch).
#include <algorithm>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include "app_fixture.h"

namespace pt::test {
namespace {

// Every pixel value, channel, type, window and attribute of an EXR.
struct Exr {
  bool ok = false;
  int x = 0, y = 0, width = 0, height = 0, full_width = 0, full_height = 0;
  std::vector<std::string> channels;
  std::vector<OIIO::TypeDesc> types;
  std::vector<float> pixels;
  std::map<std::string, std::string> attributes;  // name -> value as text
  std::string attr(const std::string& name) const {
    const auto it = attributes.find(name);
    return it == attributes.end() ? std::string() : it->second;
  }
};

Exr read_exr(const std::string& file) {
  Exr e;
  auto in = OIIO::ImageInput::open(file);
  if (!in) return e;
  const OIIO::ImageSpec& s = in->spec();
  e.x = s.x;
  e.y = s.y;
  e.width = s.width;
  e.height = s.height;
  e.full_width = s.full_width;
  e.full_height = s.full_height;
  e.channels = s.channelnames;
  for (int c = 0; c < s.nchannels; ++c) e.types.push_back(s.channelformat(c));
  for (const OIIO::ParamValue& p : s.extra_attribs) e.attributes[p.name().string()] = p.get_string();
  e.pixels.resize(static_cast<std::size_t>(s.width) * s.height * s.nchannels);
  e.ok = in->read_image(0, 0, 0, s.nchannels, OIIO::TypeFloat, e.pixels.data());
  return e;
}

// Empty when the pixels, channels, types and windows are the same bits.
std::string differs(const Exr& a, const Exr& b) {
  if (!a.ok || !b.ok) return "unreadable";
  if (a.channels != b.channels) return "channels";
  if (a.types != b.types) return "channel types";
  if (a.x != b.x || a.y != b.y || a.width != b.width || a.height != b.height) return "data window";
  if (a.full_width != b.full_width || a.full_height != b.full_height) return "display window";
  for (std::size_t i = 0; i < a.pixels.size(); ++i)
    if (std::memcmp(&a.pixels[i], &b.pixels[i], sizeof(float)) != 0)
      return "value " + std::to_string(i) + " (channel " + a.channels[i % a.channels.size()] +
             "): " + std::to_string(a.pixels[i]) + " vs " + std::to_string(b.pixels[i]);
  return {};
}

// AOVs of every accumulation kind, some half, the beauty half.
const std::string kRender = "s.json --seed 3 --quiet --aov albedo,N:float,P:half,Z,IndexOB,emission,diffuse_direct,"
                            "diffuse_indirect,variance,samples,nonfinite,beauty:half";

class Distributed : public AppTest {
 protected:
  void SetUp() override {
    AppTest::SetUp();
    write("s.json", path_scene(24, 16, 10));
  }
  // Runs the shards `shard_args` (one render each, writing NAME.ptshard) and
  // merges them in a shuffled order into `out`; the merge's result.
  RunResult shards_and_merge(const std::vector<std::pair<std::string, std::string>>& shards, const std::string& out,
                             const std::string& merge_args = "") {
    std::vector<std::string> files;
    for (const auto& [name, args] : shards) {
      const RunResult r = run(kRender + " " + args + " --shard-out " + name + ".ptshard");
      EXPECT_EQ(r.status, 0) << args << ": " << r.err;
      files.push_back(name + ".ptshard");
    }
    std::shuffle(files.begin(), files.end(), std::mt19937(static_cast<unsigned>(files.size())));
    std::string list;
    for (const std::string& f : files) list += " " + f;
    return run("merge" + list + " -o " + out + " " + merge_args);
  }
};

TEST_F(Distributed, SampleSharesMergeToTheSingleRenderBitForBit) {
  ASSERT_EQ(run(kRender + " -o single.exr").status, 0);
  const Exr single = read_exr(path("single.exr"));
  for (int n : {1, 2, 3, 5}) {
    std::vector<std::pair<std::string, std::string>> shards;
    for (int k = 0; k < n; ++k) {
      // Appended: GCC 12 warns falsely about "a" + b (-Wrestrict).
      std::string share = "--shard ", name = "n";
      share.append(std::to_string(k)).append("/").append(std::to_string(n));
      name.append(std::to_string(n)).append("_").append(std::to_string(k));
      shards.emplace_back(name, share);
    }
    const std::string out = "merged" + std::to_string(n) + ".exr";
    const RunResult m = shards_and_merge(shards, out);
    ASSERT_EQ(m.status, 0) << m.err;
    EXPECT_NE(m.out.find("merged " + std::to_string(n) + " shard"), std::string::npos) << m.out;
    const Exr merged = read_exr(path(out));
    EXPECT_EQ(differs(single, merged), "") << n << " shards";
    EXPECT_EQ(merged.attr("pathtracer:spp"), "10");
    EXPECT_EQ(merged.attr("pathtracer:partial"), "0");
    EXPECT_EQ(merged.attr("pathtracer:seed"), single.attr("pathtracer:seed"));
    EXPECT_EQ(merged.attr("worldToCamera"), single.attr("worldToCamera"));
  }
  // The band merge on one thread, and the merged film that --shard-out needs,
  // give the same bits.
  for (const std::string args : {"--threads 1", "--threads 3 --shard-out m3.ptshard"}) {
    const RunResult m = run("merge n3_2.ptshard n3_0.ptshard n3_1.ptshard -o t.exr " + args);
    ASSERT_EQ(m.status, 0) << m.err;
    EXPECT_NE(m.out.find(args.find("shard-out") != std::string::npos ? "read and add" : "read, add, resolve and write"),
              std::string::npos) << m.out;
    EXPECT_EQ(differs(single, read_exr(path("t.exr"))), "") << args;
  }
  EXPECT_EQ(run("merge n3_0.ptshard -o t.exr --threads -1").status, 2);
}

TEST_F(Distributed, TilesOfACropKeepItsDataWindowTypesAndMetadata) {
  ASSERT_EQ(run(kRender + " --crop-px 2,3,19,11 -o single.exr").status, 0);
  std::vector<std::pair<std::string, std::string>> shards;
  for (int t = 0; t < 3; ++t)  // three tiles, each in two sample shares
    for (int k = 0; k < 2; ++k)
      shards.emplace_back(std::string("t") + std::to_string(t) + "_" + std::to_string(k),
                          "--crop-px 2,3,19,11 --tile " + std::to_string(t) + "/3 --shard " + std::to_string(k) + "/2");
  const RunResult m = shards_and_merge(shards, "merged.exr");
  ASSERT_EQ(m.status, 0) << m.err;
  const Exr single = read_exr(path("single.exr")), merged = read_exr(path("merged.exr"));
  EXPECT_EQ(differs(single, merged), "");
  EXPECT_EQ(merged.x, 2);
  EXPECT_EQ(merged.y, 3);
  EXPECT_EQ(merged.width, 19);
  EXPECT_EQ(merged.height, 11);
  EXPECT_EQ(merged.full_width, 24);
  ASSERT_FALSE(merged.types.empty());
  EXPECT_EQ(merged.types[0], OIIO::TypeHalf);  // beauty:half kept
  for (const char* key : {"pathtracer:integrator", "pathtracer:sampler", "pathtracer:maxDepth", "worldToNDC"})
    EXPECT_EQ(merged.attr(key), single.attr(key)) << key;
  EXPECT_NE(merged.attr("pathtracer:shards").find("6 shards: 0/3:[0,5) 0/3:[5,10) 1/3:[0,5)"),
            std::string::npos)
      << merged.attr("pathtracer:shards");
}

TEST_F(Distributed, WhatDoesNotBelongTogetherIsRefused) {
  for (const char* s : {"0/3", "1/3", "2/3"})
    ASSERT_EQ(run(kRender + " --shard " + s + " --shard-out " + std::string(1, s[0]) + ".ptshard").status, 0);
  RunResult r = run("merge 0.ptshard 2.ptshard -o m.exr");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("no shard holds samples [3,6) of every pixel"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(path("m.exr")));
  r = run("merge 0.ptshard 2.ptshard -o m.exr --allow-partial");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("warning: partial merge"), std::string::npos) << r.err;
  EXPECT_EQ(read_exr(path("m.exr")).attr("pathtracer:partial"), "1");
  r = run("merge 0.ptshard 1.ptshard 1.ptshard 2.ptshard -o m.exr");
  EXPECT_NE(r.err.find("'1.ptshard' and '1.ptshard' are the same shard (samples [3,6)"), std::string::npos) << r.err;
  ASSERT_EQ(run(kRender + " --sample-range 2,10 --shard-out late.ptshard -o late.exr").status, 0);
  EXPECT_EQ(read_exr(path("late.exr")).attr("pathtracer:spp"), "8");  // the shard's own image: its 8 samples
  r = run("merge 0.ptshard late.ptshard -o m.exr");
  EXPECT_NE(r.err.find("overlap: both hold samples [2,3)"), std::string::npos) << r.err;
  ASSERT_EQ(run(std::string(kRender).replace(kRender.find("--seed 3"), 8, "--seed 4") +
                " --shard 1/3 --shard-out seed.ptshard").status,
            0);
  r = run("merge 0.ptshard seed.ptshard 2.ptshard -o m.exr");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("they differ in seed 3 vs 4"), std::string::npos) << r.err;
  write("t.json", path_scene(24, 16, 10).replace(path_scene(24, 16, 10).find("0.7, 0.7"), 8, "0.6, 0.7"));
  ASSERT_EQ(run(std::string(kRender).replace(0, 6, "t.json") + " --shard 1/3 --shard-out t.ptshard").status, 0);
  r = run("merge 0.ptshard t.ptshard 2.ptshard -o m.exr");
  EXPECT_NE(r.err.find("they differ in the scene: 's.json' (hash"), std::string::npos) << r.err;
  // Another version: the header says so (as an older build would write it).
  std::string other = slurp(path("1.ptshard"));
  const std::string version = "\"version\":\"" PT_VERSION "\"";
  other.replace(other.find(version), version.size(), "\"version\":\"9.9.9\"");
  write("v.ptshard", other);
  r = run("merge 0.ptshard v.ptshard 2.ptshard -o m.exr");
  EXPECT_NE(r.err.find("version " PT_VERSION " vs 9.9.9"), std::string::npos) << r.err;
  // The command line's own checks.
  r = run(kRender + " --shard 3/3 --shard-out x.ptshard");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("K must be in 0..2"), std::string::npos) << r.err;
  r = run(kRender + " --shard 10/11 --shard-out x.ptshard");
  EXPECT_NE(r.err.find("the render has 10 samples per pixel, fewer than 11 shards"), std::string::npos) << r.err;
  r = run(kRender + " --tile 16/17 --shard-out x.ptshard");
  EXPECT_NE(r.err.find("--tile 16/17: the region has 16 rows, fewer than 17 tiles"), std::string::npos) << r.err;
  EXPECT_EQ(run("merge -o m.exr").status, 2);
  r = run("merge nothing.ptshard -o m.exr");
  EXPECT_NE(r.err.find("cannot open shard file 'nothing.ptshard'"), std::string::npos) << r.err;
}

// The merge maps each shard file and checks its film state's size before
// adding any of it: a short or long file, or a damaged state, is refused
// naming the file, and nothing is written.
TEST_F(Distributed, DamagedShardFilesAreRefusedAndNothingIsWritten) {
  for (const char* s : {"0/2", "1/2"})
    ASSERT_EQ(run(kRender + " --shard " + s + " --shard-out " + std::string(1, s[0]) + ".ptshard").status, 0);
  const std::string good = slurp(path("1.ptshard"));
  const auto refused = [&](const std::string& bytes, const std::string& message) {
    write("bad.ptshard", bytes);
    // The merged film (--shard-out), the band merge (two images) and the streamed one (one EXR).
    for (const std::string outputs : {"-o m.exr --shard-out m.ptshard", "-o m.exr -o m.png", "-o m.exr"}) {
      const RunResult r = run("merge 0.ptshard bad.ptshard " + outputs);
      EXPECT_EQ(r.status, 1) << message << ", " << outputs;
      EXPECT_NE(r.err.find("'bad.ptshard': " + message), std::string::npos) << outputs << ": " << r.err;
      EXPECT_FALSE(std::filesystem::exists(path("m.exr"))) << outputs;
      EXPECT_FALSE(std::filesystem::exists(path("m.png"))) << outputs;
      EXPECT_FALSE(std::filesystem::exists(path("m.ptshard"))) << outputs;
    }
  };
  refused(good.substr(0, good.size() - 1), "truncated film state");
  refused(good.substr(0, good.size() / 2), "truncated film state");
  refused(good + "x", "film state has trailing data");
  // The pixels' sample count raised above the header's: every pixel holds
  // the same count, so it is among the film state's defaults (a full record
  // after the state's header of 89 bytes and 3 per AOV, their count at byte
  // 36), after the record's five sums (8 bytes each); the count of the
  // exceptions (none here) follows the defaults.
  std::string samples = good;
  const std::size_t body = good.find("PTFILM\r\n");
  ASSERT_NE(body, std::string::npos);
  const auto aovs = static_cast<std::size_t>(static_cast<unsigned char>(good[body + 36]));
  const std::size_t defaults = body + 89 + 3 * aovs, full = 44 + 21 * 8 + 9 * 4;  // the beauty, 21 sums, 9 values
  ASSERT_EQ(good.substr(defaults + full, 8), std::string(8, '\0'));
  ASSERT_NE(good[defaults + 40], 0);
  samples[defaults + 40] = 99;
  refused(samples, "its film state holds 99 samples in pixel (0, 0), more than its pieces' 5");
  // A shard of an older pathtracer (film state version 5) is refused naming the version.
  std::string old = good;
  old[body + 8] = 5;
  refused(old, "film state version 5 is not read by this pathtracer, which reads version 6 (written by an older "
               "one: render it again with this one)");
  // An exception (a wide value) listed but damaged: its count says more than the file holds.
  std::string listed = good;
  listed[defaults + full] = 1;
  refused(listed, "corrupt film state (wide value 0 of 1)");
  const RunResult r = run("merge 0.ptshard 1.ptshard -o m.exr");  // the good ones still merge
  EXPECT_EQ(r.status, 0) << r.err;
}

// An EXR's bytes with its capDate's value (the time of writing) blanked.
std::string without_cap_date(std::string bytes) {
  const std::string key("capDate\0string\0", 15);
  const std::size_t at = bytes.find(key);
  if (at != std::string::npos) bytes.replace(at + key.size() + 4, 19, 19, '-');  // after its 4-byte size
  return bytes;
}

// One EXR output is written as the bands are merged (ShardMerger::merge_streamed):
// the same bytes as the band merge's image written whole (an EXR with a PNG
// beside it), for every compression, on one thread and on several, over a
// frame of many chunks of rows, a crop and a partial merge; --multipart and
// --shard-out take the other paths and give the same pixels.
TEST_F(Distributed, StreamedMergeWritesTheSameBytesAsTheWholeImage) {
  write("tall.json", path_scene(20, 150, 3));
  const std::string render = "tall.json --seed 7 --quiet --aov albedo,N:float,P:half,Z,IndexOB,variance,samples,"
                             "CryptoObject,beauty:half";
  for (const char* k : {"0", "1", "2"}) {
    const RunResult r = run(render + " --shard " + std::string(k) + "/3 --shard-out s" + k + ".ptshard");
    ASSERT_EQ(r.status, 0) << r.err;
  }
  ASSERT_EQ(run(render + " -o single.exr").status, 0);
  const Exr single = read_exr(path("single.exr"));
  for (const std::string c : {"none", "rle", "zips", "zip", "piz", "b44", "b44a", "dwaa", "dwab"}) {
    for (const char* threads : {"1", "3"}) {
      if (threads[0] == '1' && c != "none" && c != "zip") continue;  // one thread: two compressions suffice
      const std::string args = " --exr-compression " + c + " --threads " + threads;
      RunResult r = run("merge s0.ptshard s1.ptshard s2.ptshard -o streamed.exr" + args);
      ASSERT_EQ(r.status, 0) << c << ": " << r.err;
      EXPECT_NE(r.out.find("read, add, resolve and write"), std::string::npos) << r.out;
      r = run("merge s0.ptshard s1.ptshard s2.ptshard -o whole.exr -o whole.png" + args);
      ASSERT_EQ(r.status, 0) << c << ": " << r.err;
      EXPECT_NE(r.out.find("read, add and resolve"), std::string::npos) << r.out;
      const std::string streamed = slurp(path("streamed.exr"));
      EXPECT_GT(streamed.size(), 20u * 150u) << c;
      EXPECT_TRUE(without_cap_date(streamed) == without_cap_date(slurp(path("whole.exr")))) << c << ", --threads " << threads;
      if (c == "none" || c == "zip") {
        EXPECT_EQ(differs(single, read_exr(path("streamed.exr"))), "") << c;
      }
    }
  }
  // Uncompressed, the streamed merge writes the file itself (io/exr_uncompressed.h): the same bytes,
  // with no image module to load; a compressed file needs the module.
  const std::string nowhere = "PT_OIIO_MODULE='" + path("nowhere/pt_oiio.so") + "'";
  RunResult alone = run("merge s0.ptshard s1.ptshard s2.ptshard -o alone.exr --exr-compression none", nowhere);
  ASSERT_EQ(alone.status, 0) << alone.err;
  ASSERT_EQ(run("merge s0.ptshard s1.ptshard s2.ptshard -o whole.exr -o whole.png --exr-compression none").status, 0);
  EXPECT_TRUE(without_cap_date(slurp(path("alone.exr"))) == without_cap_date(slurp(path("whole.exr"))));
  alone = run("merge s0.ptshard s1.ptshard s2.ptshard -o zip.exr --exr-compression zip", nowhere);
  EXPECT_EQ(alone.status, 1);
  EXPECT_NE(alone.err.find("cannot load the image module"), std::string::npos) << alone.err;
  EXPECT_FALSE(std::filesystem::exists(path("zip.exr")));
  for (const std::string args : {"--multipart", "--shard-out m.ptshard"}) {
    const RunResult r = run("merge s0.ptshard s1.ptshard s2.ptshard -o other.exr " + args);
    ASSERT_EQ(r.status, 0) << args << ": " << r.err;
    EXPECT_EQ(r.out.find("resolve and write"), std::string::npos) << r.out;
    if (args != "--multipart") {
      EXPECT_EQ(differs(single, read_exr(path("other.exr"))), "") << args;
    }
  }
  // A crop of shares, and a partial merge (a share missing): the same bytes too.
  for (const char* k : {"0", "1"})
    ASSERT_EQ(run(render + " --crop-px 3,40,14,90 --shard " + std::string(k) + "/2 --shard-out c" + k + ".ptshard").status, 0);
  for (const std::string shards : {"c0.ptshard c1.ptshard", "s0.ptshard s2.ptshard --allow-partial"}) {
    ASSERT_EQ(run("merge " + shards + " -o streamed.exr").status, 0) << shards;
    ASSERT_EQ(run("merge " + shards + " -o whole.exr -o whole.png").status, 0) << shards;
    EXPECT_TRUE(without_cap_date(slurp(path("streamed.exr"))) == without_cap_date(slurp(path("whole.exr")))) << shards;
  }
  EXPECT_EQ(read_exr(path("streamed.exr")).attr("pathtracer:partial"), "1");
}

TEST_F(Distributed, CompositingLayersMergeExactly) {
  // A transparent film (alpha is the coverage) and Cryptomatte with 2 levels,
  // fewer than the ids some pixels see, so that slots overflow in the shards.
  const std::string render = "s.json --seed 5 --quiet --film-transparent --cryptomatte-levels 2 "
                             "--aov CryptoObject,CryptoMaterial,Z,beauty:half";
  ASSERT_EQ(run(render + " -o single.exr").status, 0);
  std::string list;
  for (const char* s : {"0/3", "1/3", "2/3"}) {
    const std::string name = std::string("c").append(1, s[0]).append(".ptshard");
    const RunResult r = run(render + " --shard " + s + " --shard-out " + name);
    ASSERT_EQ(r.status, 0) << r.err;
    list.insert(0, " " + name);  // the last first
  }
  RunResult r = run("merge" + list + " -o merged.exr -o merged.png");
  ASSERT_EQ(r.status, 0) << r.err;
  const Exr single = read_exr(path("single.exr")), merged = read_exr(path("merged.exr"));
  EXPECT_EQ(differs(single, merged), "");
  EXPECT_NE(std::find(merged.channels.begin(), merged.channels.end(), "CryptoObject00.r"), merged.channels.end());
  int manifests = 0;
  for (const auto& [name, value] : single.attributes)
    if (name.rfind("cryptomatte/", 0) == 0) {
      ++manifests;
      EXPECT_EQ(merged.attr(name), value) << name;
    }
  EXPECT_EQ(manifests, 8);  // name, hash, conversion, manifest of two types
  auto png = OIIO::ImageInput::open(path("merged.png"));
  ASSERT_TRUE(png);
  EXPECT_EQ(png->spec().nchannels, 4);  // a transparent film's PNG has alpha, merged or not
  // Shards of another level count do not merge; a compression that rounds
  // floats is refused for Cryptomatte ids; no output may replace a shard.
  ASSERT_EQ(run(std::string(render).replace(render.find("levels 2"), 8, "levels 3") +
                " --shard 1/3 --shard-out l.ptshard").status,
            0);
  r = run("merge c0.ptshard l.ptshard c2.ptshard -o m.exr");
  EXPECT_NE(r.err.find("they differ in Cryptomatte levels 2 vs 3"), std::string::npos) << r.err;
  r = run("merge" + list + " -o m.exr --exr-compression pxr24");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("destroys CryptoObject's ids"), std::string::npos) << r.err;
  r = run("merge" + list + " --shard-out c0.ptshard");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("cannot write --shard-out 'c0.ptshard': it is the shard 'c0.ptshard' being merged"), std::string::npos) << r.err;
  // A shard's --shard-out is checked before the scene is read, as -o is.
  r = run(render + " --shard 0/3 --shard-out no/such/folder/x.ptshard");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("cannot write --shard-out 'no/such/folder/x.ptshard': the folder"), std::string::npos) << r.err;
}

// The header (second line) of a shard file, and its film state (the rest).
std::pair<nlohmann::json, std::string> split_shard(const std::string& bytes) {
  const std::size_t a = bytes.find('\n'), b = bytes.find('\n', a + 1);
  return {nlohmann::json::parse(bytes.substr(a + 1, b - a - 1), nullptr, false), bytes.substr(b + 1)};
}

TEST_F(Distributed, TimeBudgetSharesReproduceExactlyAndMergeWhatTheyTook) {
  // Shares far larger than the budget allows: each shard stops where its time runs out.
  const std::string args = kRender + " --spp 1000000 --time-budget 0.3";
  for (const char* k : {"0", "1"})
    ASSERT_EQ(run(args + " --shard " + std::string(k) + "/2 --shard-out b" + k + ".ptshard").status, 0);
  const auto [header, film] = split_shard(slurp(path("b1.ptshard")));
  ASSERT_TRUE(header.is_object());
  const auto done = header["pieces"][0]["done"];
  EXPECT_EQ(done[0], 500000);
  EXPECT_GT(done[1].get<int>(), 500000);  // it rendered something ...
  EXPECT_LT(done[1].get<int>(), 1000000);  // ... and stopped on time
  // Re-run alone with the range it took (no budget): the same film state, bit for bit.
  const std::string range = "--sample-range 500000," + std::to_string(done[1].get<int>());
  ASSERT_EQ(run(kRender + " --spp 1000000 " + range + " --shard-out again.ptshard").status, 0);
  EXPECT_EQ(split_shard(slurp(path("again.ptshard"))).second, film);
  const RunResult m = run("merge b1.ptshard b0.ptshard -o m.exr");
  ASSERT_EQ(m.status, 0) << m.err;
  const auto done0 = split_shard(slurp(path("b0.ptshard"))).first["pieces"][0]["done"];
  const Exr merged = read_exr(path("m.exr"));
  EXPECT_EQ(merged.attr("pathtracer:partial"), "0");
  EXPECT_EQ(merged.attr("pathtracer:spp"),
            std::to_string(done0[1].get<int>() + done[1].get<int>() - 500000));
}

TEST_F(Distributed, StratifiedSamplersShareWholePasses) {
  const std::string args = kRender + " --sampler jittered --spp 16 --pass-spp 4";
  ASSERT_EQ(run(args + " -o single.exr").status, 0);
  std::vector<std::string> files;
  for (int k = 0; k < 3; ++k) {
    const std::string f = std::string("j") + std::to_string(k) + ".ptshard";
    ASSERT_EQ(run(args + " --shard " + std::to_string(k) + "/3 --shard-out " + f).status, 0);
    files.push_back(f);
  }
  ASSERT_EQ(run("merge " + files[2] + " " + files[0] + " " + files[1] + " -o merged.exr").status, 0);
  EXPECT_EQ(differs(read_exr(path("single.exr")), read_exr(path("merged.exr"))), "");
  RunResult r = run(args + " --shard 4/5 --shard-out x.ptshard");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("the render has 4 passes, fewer than 5 shards (this sampler stratifies each pass of 4 "
                       "samples"),
            std::string::npos)
      << r.err;
  r = run(args + " --sample-range 2,8 --shard-out x.ptshard");
  EXPECT_NE(r.err.find("A and B must be multiples of 4"), std::string::npos) << r.err;
}

TEST_F(Distributed, MpiRanksRenderSharesAndRankZeroMerges) {
#if !defined(PT_MPIRUN)
  // Without MPI, --mpi says so before reading the scene, exits 2 and writes nothing.
  const RunResult r = run(kRender + " --mpi -o mpi.exr");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("this pathtracer was built without MPI"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(path("mpi.exr")));
  GTEST_SKIP() << "this build has no MPI launcher (CMake found no MPI, or -DPT_WITH_MPI=OFF): checked that --mpi "
                  "says so; mpirun -np 3 not run";
#else
  ASSERT_EQ(run(kRender + " -o single.exr").status, 0);
  // As root, Open MPI's mpirun needs these; oversubscribe: 3 ranks on fewer cores.
  const std::string mpirun = "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 '" +
                             std::string(PT_MPIRUN) + "' --oversubscribe -np 3 '" PT_PATHTRACER_EXE "' ";
  RunResult r = run_command(mpirun + kRender + " --threads 1 --mpi -o mpi.exr --shard-out mpi.ptshard");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(differs(read_exr(path("single.exr")), read_exr(path("mpi.exr"))), "");
  EXPECT_NE(read_exr(path("mpi.exr")).attr("pathtracer:shards").find("3 shards: [0,3) [3,6) [6,10)"),
            std::string::npos);
  // The merged state merges again (alone: a complete set).
  ASSERT_EQ(run("merge mpi.ptshard -o again.exr").status, 0);
  EXPECT_EQ(differs(read_exr(path("single.exr")), read_exr(path("again.exr"))), "");
  // A scene every rank refuses: all answer, mpirun fails, nothing hangs or is written.
  write("bad.json", "{");
  r = run_command(mpirun + "bad.json --mpi --threads 1 -o bad.exr");
  EXPECT_NE(r.status, 0);
  EXPECT_FALSE(std::filesystem::exists(path("bad.exr")));
#endif
}

TEST_F(Distributed, SlurmScriptSubmitsAnArrayAndAMergeThatWaitsForIt) {
  // A stand-in sbatch: logs its arguments and runs the job at once, the tasks of an array one after another.
  write("sbatch", R"(#!/bin/bash
echo "sbatch $*" >> sbatch.log
array="" script="${@: -1}" out=""
for a in "$@"; do case "$a" in --array=*) array="${a#--array=}" ;; --output=*) out="${a#--output=}" ;; esac; done
id=$(( $(wc -l < sbatch.log) + 4000 ))
if [ -n "$array" ]; then
  IFS=- read -r first last <<< "$array"
  for ((k = first; k <= ${last:-$first}; k++)); do
    SLURM_ARRAY_TASK_ID=$k sh "$script" > "${out//%a/$k}" 2>&1 || exit 1
  done
else
  sh "$script" > "$out" 2>&1 || exit 1
fi
echo "$id;cluster"
)");
  ASSERT_EQ(run(kRender + " -o single.exr").status, 0);
  const RunResult r = run_command("chmod +x sbatch && SBATCH=./sbatch PT_SHARD_DIR=sh PT_EXE='" PT_PATHTRACER_EXE
                                  "' bash '" PT_SLURM_SCRIPT "' s.json 3 --partition=debug --time=10 -- " +
                                  kRender.substr(7) + " -o out.exr");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("submitted render array 4001 (3 shards) and merge 4002"), std::string::npos) << r.out;
  const std::string log = slurp(path("sbatch.log"));
  EXPECT_NE(log.find("--array=0-2 --job-name=pt-s"), std::string::npos) << log;
  EXPECT_NE(log.find("--dependency=afterok:4001 --job-name=pt-s-merge"), std::string::npos) << log;
  EXPECT_NE(log.find("--partition=debug --time=10"), std::string::npos) << log;
  EXPECT_EQ(differs(read_exr(path("single.exr")), read_exr(path("out.exr"))), "");
  EXPECT_NE(slurp(path("sh/jobs.txt")).find("--array=K"), std::string::npos);
}

}  // namespace
}  // namespace pt::test
