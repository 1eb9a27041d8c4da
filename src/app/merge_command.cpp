// `pathtracer merge` (docs/distributed.md): shard files in, one render out.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <future>
#include <iomanip>
#include <iostream>
#include <thread>
#include <tuple>

#include <CLI/CLI.hpp>

#include "app/distributed.h"
#include "app/options.h"
#include "app/output_checks.h"
#include "app/outputs.h"
#include "app/shard_merge.h"
#include "core/mapped_file.h"
#include "core/memory_stream.h"
#include "core/parallel.h"
#include "core/stopwatch.h"
#include "imagelib/image_library.h"
#include "io/exr_uncompressed.h"
#include "io/image_io.h"

namespace pt {
namespace {

struct MergeOptions {
  std::vector<std::string> shards;
  std::vector<std::string> outputs;
  std::string shard_out;
  std::string ocio_config;
  ExrSettings exr;
  bool allow_partial = false;
  bool quiet = false;
  int threads = 0;  // 0: every hardware thread
};

void add_merge_options(CLI::App& app, MergeOptions& m) {
  app.add_option("shards", m.shards, "Shard files (--shard-out of the shards, or of earlier merges), in any order")
      ->required();
  app.add_option("-o,--output", m.outputs, "Output image (.exr, .png, .jpg, .ppm); repeatable")
      ->allow_extra_args(false);
  app.add_option("--shard-out", m.shard_out, "Also write the merged state, to merge again later");
  app.add_flag("--allow-partial", m.allow_partial,
               "Merge an incomplete set (missing tiles or samples): the result is marked partial");
  app.add_option("--ocio-config", m.ocio_config, "OpenColorIO config for display images (default: the shards')");
  app.add_option("--exr-compression", m.exr.compression,
                 "EXR compression: " + join(exr_compression_names(), ", ") + " (dwaa/dwab take a level: dwaa:45)")
      ->check([](const std::string& value) {
        std::string error;
        return check_exr_compression(value, error) ? std::string() : error;
      });
  app.add_flag("--multipart", m.exr.multipart, "EXR: one part per layer");
  app.add_option("--threads", m.threads, "Worker threads of the merge and the EXR write (default: all hardware threads)")
      ->check(CLI::NonNegativeNumber);
  app.add_flag("--quiet", m.quiet, "Print errors only");
}

struct Input {
  std::string path;
  ShardInfo info;
};

// The fixed order: by tile (top row first), then first sample, then path.
void sort_inputs(std::vector<Input>& inputs) {
  const auto key = [](const Input& in) {
    const ShardPiece& p = in.info.pieces.front();
    return std::tie(p.crop.y0, p.crop.x0, p.share.begin, in.path);
  };
  std::sort(inputs.begin(), inputs.end(), [&](const Input& a, const Input& b) { return key(a) < key(b); });
}

bool read_headers(const MergeOptions& m, std::vector<Input>& inputs, std::string& error) {
  for (const std::string& path : m.shards) {
    std::ifstream in(path, std::ios::binary);
    if (!in) {
      error = "cannot open shard file '" + path + "'";
      return false;
    }
    Input input{path, {}};
    if (!read_shard_info(in, path, input.info, error)) return false;
    inputs.push_back(std::move(input));
  }
  sort_inputs(inputs);
  return true;
}

// A shard file mapped (not copied into buffers), its header read again
// (`info`) and its film state (the bytes after the header) in `state`.
bool map_shard(const Input& input, std::optional<MappedFile>& file, ShardInfo& info, std::string_view& state,
               std::string& error) {
  std::string why;
  file = MappedFile::open(input.path, why);
  if (!file) {
    error = "cannot read shard file '" + input.path + "': " + why;
    return false;
  }
  MemoryBuffer buffer(file->bytes());
  std::istream in(&buffer);
  if (!read_shard_info(in, input.path, info, error)) return false;
  state = file->bytes().substr(buffer.consumed());
  return true;
}

// The merged film, for --shard-out: each shard's film state added in
// parallel, one file mapped at a time.
bool add_films(const std::vector<Input>& inputs, ShardMerger& merger, std::string& error) {
  for (const Input& input : inputs) {
    std::optional<MappedFile> file;
    ShardInfo again;
    std::string_view state;
    if (!map_shard(input, file, again, state, error) || !merger.add(input.path, again, state, error)) return false;
  }
  return true;
}

// Images only: the band merge, every shard file mapped at once (only the
// pages of the band being added are read at a time).
bool merge_bands(const std::vector<Input>& inputs, ShardMerger& merger, LayeredImage& layers, std::string& error) {
  std::vector<std::optional<MappedFile>> files(inputs.size());
  std::vector<std::string_view> states(inputs.size());
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    ShardInfo again;
    if (!map_shard(inputs[i], files[i], again, states[i], error)) return false;
  }
  return merger.merge_layers(states, layers, error);
}

// The band merge written as it is made (ShardMerger::merge_streamed): one
// EXR output of one part, no --shard-out. The shards' coverage is checked
// (finish) before anything is written; a refusal leaves no file.
bool streams(const MergeOptions& m) {
  return m.shard_out.empty() && m.outputs.size() == 1 && is_exr_path(m.outputs.front()) && !m.exr.multipart;
}

// The file of the streamed merge, opened on a thread of its own (the image
// module loads there, ~0.2 s, unless the file is uncompressed:
// io/exr_uncompressed.h) while the first bands are merged: `opened`
// gets its writer (nullptr if it cannot be opened, `error` then says why);
// the file is finished once `merged` says the merge wrote every row, and
// discarded if not (`merge_error` then says why, set before `merged`).
bool write_streamed(const MergeOptions& m, const ShardMerger& merger, OutputStamps& stamps,
                    std::promise<ExrBandWriter*>& opened, std::future<bool> merged, const std::string& merge_error,
                    std::string& error) {
  bool handed = false;
  const bool ok = write_guarded(
      m.outputs.front(), stamps,
      [&](const std::string& path, std::string& e) {
        return write_exr_bands(path, merger.layout(), merger.metadata(), m.exr, [&](ExrBandWriter& writer, std::string& why) {
          handed = true;
          opened.set_value(&writer);
          if (merged.get()) return true;
          why = merge_error;
          return false;
        }, e);
      },
      error);
  if (!handed) opened.set_value(nullptr);
  return ok;
}

bool merge_streamed(const MergeOptions& m, const std::vector<Input>& inputs, ShardMerger& merger,
                    OutputStamps& stamps, std::string& error) {
  std::vector<std::optional<MappedFile>> files(inputs.size());
  std::vector<std::string_view> states(inputs.size());
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    ShardInfo again;
    if (!map_shard(inputs[i], files[i], again, states[i], error)) return false;
  }
  if (!merger.view_states(states, error) || !merger.finish(error)) return false;
  // An uncompressed file (the writer write_exr_bands picks for it takes
  // rows as the file stores them): the merge packs them so.
  const bool lines = writes_uncompressed_exr(merger.layout(), merger.metadata(), m.exr);
  std::promise<ExrBandWriter*> opened;
  std::promise<bool> merged;
  std::string merge_error, file_error;
  bool written = false, refused = false;
  std::thread file([&, done = merged.get_future()]() mutable {
    written = write_streamed(m, merger, stamps, opened, std::move(done), merge_error, file_error);
  });
  bool ok = false;
  try {
    ok = merger.merge_streamed(opened.get_future().share(), lines, merge_error, refused);
  } catch (...) {
    merged.set_value(false);
    file.join();
    throw;
  }
  merged.set_value(ok);
  // Every band is merged: the shards are unmapped (~0.05 s of the kernel's
  // time for a shard of 1 GB) while the file thread closes the file and
  // renames it into place (which frees the pages of a file it replaces:
  // 0.3-0.5 s for one of 447 MiB at load 8, docs/bench/merge-s16-write.md).
  states.clear();
  files.clear();
  file.join();
  error = refused ? merge_error : file_error;  // a refusal: the merge's message, as the band merge gives it
  return ok && written;
}

// Every output checked before any shard is read (as a render's: app/output_checks.h),
// and none of them one of the shards (the merge would replace its input).
bool check_merge_outputs(const MergeOptions& m, std::vector<OutputFile>& files, std::string& error) {
  if (!check_outputs(m.outputs, error)) return false;
  for (const std::string& path : m.outputs) files.push_back({"-o", path});
  if (!m.shard_out.empty()) files.push_back({"--shard-out", m.shard_out});
  if (!check_output_files(files, error)) return false;
  namespace fs = std::filesystem;
  std::error_code ec;
  for (const OutputFile& f : files)
    for (const std::string& shard : m.shards)
      if (fs::exists(f.path, ec) && fs::equivalent(f.path, shard, ec)) {
        error = "cannot write " + f.option + " '" + f.path + "': it is the shard '" + shard + "' being merged";
        return false;
      }
  return true;
}

// An EXR compression that rounds floats destroys Cryptomatte ids (as for a render: app/job.cpp).
bool check_compression(const MergeOptions& m, const ShardInfo& info, std::string& error) {
  std::vector<AovRequest> aovs;
  ChannelType beauty;
  if (!info.film_aovs(aovs, beauty, error)) return false;
  for (const AovRequest& r : aovs)
    if (r.ranks > 0 && exr_compression_rounds_floats(m.exr.compression)) {
      error = "--exr-compression " + m.exr.compression + " rounds 32-bit floats to 24 bits, which destroys " +
              aov_info(r.type).name + "'s ids; choose another compression (zip, piz, dwaa, ...)";
      return false;
    }
  return true;
}

// The shards read and added, and the outputs written: images alone by the
// band merge; with --shard-out through the merged film. `phase` is the
// first phase's name in the report (they differ in what they include).
bool merge_and_write(const MergeOptions& m, const std::vector<Input>& inputs, ShardMerger& merger,
                     OutputStamps& stamps, std::string& phase, double times[4], std::string& error) {
  const auto t0 = Clock::now();
  const double cpu0 = process_cpu_seconds();
  if (streams(m)) {  // the file (and the image module) opened while the first bands are merged
    phase = "read, add, resolve and write";
    const bool ok = merge_streamed(m, inputs, merger, stamps, error);
    times[0] = seconds_since(t0);
    times[1] = process_cpu_seconds() - cpu0;
    return ok;
  }
  // The image module (OpenImageIO: ~260 libraries to bind, ~0.2 s) loads
  // while the shards are added, instead of at the first write. A failure is
  // reported by the write, which asks again (image_library: the same answer).
  std::thread preload([&m] {
    std::string ignored;
    if (!m.outputs.empty()) image_library(ignored);
  });
  LayeredImage layers;
  const bool bands = m.shard_out.empty();
  phase = bands ? "read, add and resolve" : "read and add";
  bool ok = (bands ? merge_bands(inputs, merger, layers, error) : add_films(inputs, merger, error)) &&
            merger.finish(error);
  preload.join();
  times[0] = seconds_since(t0);
  times[1] = process_cpu_seconds() - cpu0;
  const auto t1 = Clock::now();
  const double cpu1 = process_cpu_seconds();
  ok = ok && (bands ? write_merged_images(merger, layers, m.outputs, m.ocio_config, m.exr, stamps, error)
                    : write_merged(merger, m.outputs, m.shard_out, m.ocio_config, m.exr, stamps, error));
  times[2] = seconds_since(t1);
  times[3] = process_cpu_seconds() - cpu1;
  return ok;
}

int merge(const MergeOptions& m) {
  std::string error;
  if (m.outputs.empty() && m.shard_out.empty()) {
    std::cerr << "error: merge: --output (or --shard-out) is required\n";
    return kExitUsage;
  }
  std::vector<OutputFile> files;
  if (!check_merge_outputs(m, files, error)) {
    std::cerr << "error: merge: " << error << '\n';
    return kExitUsage;
  }
  OutputStamps stamps;
  stamps.take(files);
  std::vector<Input> inputs;
  ShardMerger merger(m.allow_partial);
  bool ok = read_headers(m, inputs, error);
  if (ok && !check_compression(m, inputs.front().info, error)) {
    std::cerr << "error: merge: " << error << '\n';
    return kExitUsage;
  }
  for (std::size_t i = 0; ok && i < inputs.size(); ++i) ok = merger.check(inputs[i].path, inputs[i].info, error);
  std::string phase;
  double times[4] = {};
  MergeOptions options = m;
  options.exr.threads = m.threads;
  WorkerPool pool(m.threads);  // --threads bounds the adds, the resolve and the EXR write
  if (ok) pool.run([&] { ok = merge_and_write(options, inputs, merger, stamps, phase, times, error); });
  if (!ok) {
    std::cerr << "error: merge: " << error << '\n';
    return kExitFailure;
  }
  for (const std::string& w : merger.warnings()) std::cerr << "warning: " << w << '\n';
  if (!merger.notes().empty()) std::cerr << "warning: " << merger.notes() << '\n';
  if (!m.quiet) {
    std::vector<std::string> written = m.outputs;
    if (!m.shard_out.empty()) written.push_back(m.shard_out);
    const PixelRect& window = merger.info().window;
    std::cout << std::fixed << std::setprecision(3) << "merged " << merger.shards() << " shard"
              << (merger.shards() == 1 ? "" : "s") << " into " << join(written, ", ") << " (" << window.width()
              << "x" << window.height() << ", " << merger.spp() << " spp"
              << (merger.info().partial ? ", partial" : "") << "): " << phase << " " << times[0] << " s (CPU "
              << times[1] << " s)";
    if (!streams(m)) std::cout << ", write " << times[2] << " s (CPU " << times[3] << " s)";
    std::cout << '\n';
  }
  return 0;
}

}  // namespace

int merge_main(int argc, char** argv) {
  CLI::App app{"pathtracer merge: adds up the shards of a distributed render (docs/distributed.md)",
               "pathtracer merge"};
  MergeOptions m;
  add_merge_options(app, m);
  try {
    app.parse(argc - 1, argv + 1);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : kExitUsage;
  }
  return merge(m);
}

}  // namespace pt
