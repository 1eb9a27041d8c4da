#include "app/options.h"

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <iterator>
#include <limits>
#include <sstream>
#include <utility>

#include <CLI/CLI.hpp>

#include "accel/accelerator.h"
#include "app/memory_estimate.h"
#include "app/outputs.h"
#include "app/versions.h"
#include "io/image_io.h"
#include "render/film/aov.h"
#include "render/integrators/integrator.h"
#include "render/textures/texture_cache.h"
#include "scene/resolution_limits.h"
#include "scene/scene_description.h"
#include "scene/suggest.h"

namespace pt {
namespace {

constexpr int kMaxThreads = 4096;
constexpr int kMaxSpp = 1 << 20;
constexpr int kMaxDepth = 1 << 16;
constexpr int kMaxResolution = ResolutionLimits{}.max_resolution;
constexpr double kMaxSeconds = 1e7;
constexpr uint64_t kMinTextureCacheBytes = uint64_t{1} << 20;

// Numbers CLI11 would accept but the renderer cannot use (issue 20): CLI11's
// Range lets NaN through (every comparison with it is false), and its integer
// conversion wraps "-1" and 2^64 to 18446744073709551615.
CLI::Validator finite_number() {
  return CLI::Validator(
    [](std::string& text) -> std::string {
      char* end = nullptr;
      const double v = std::strtod(text.c_str(), &end);
      if (end == text.c_str()) return {};  // not a number: CLI11's own conversion says so
      return std::isfinite(v) ? std::string() : "must be a finite number, got '" + text + "'";
    },
    "FINITE");
}
CLI::Validator seed_value() {
  return CLI::Validator(
    [](std::string& text) -> std::string {
      uint64_t v = 0;
      const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
      if (!text.empty() && ec == std::errc() && end == text.data() + text.size()) return {};
      return "must be an integer in [0, " + std::to_string(std::numeric_limits<uint64_t>::max()) + "], got '" +
             text + "'";
    },
    "UINT64");
}

}  // namespace

std::string version_text() {
  const SoftwareVersions v = software_versions();
  std::ostringstream os;
  os << "pathtracer " << v.pathtracer << '\n'
     << "  Embree " << v.embree << " (tasking: " << v.embree_tasking << ", native packets: "
     << v.embree_native_packets << ")\n"
     << "  OpenImageIO " << v.openimageio << " (image module " << v.image_module << ", " << v.image_module_origin
     << "; loaded on the first image read or written)\n"
     << "  OpenEXR " << v.openexr << '\n'
     << "  OpenColorIO " << v.opencolorio << '\n'
     << "  oneTBB " << v.tbb << '\n'
     << "  " << v.compiler << " (" << v.build_type << ")";
  return os.str();
}

namespace {

// `pathtracer --help` lists the options by task, in this order (CLI11 prints a
// group where its first option was added, so each add_*_options below adds one
// group, and add_options calls them in this order), then kHelpExamples.
constexpr const char* kGroupSceneOutput = "Scene and output";
constexpr const char* kGroupQuality = "Quality";
constexpr const char* kGroupLongRenders = "Long renders";
constexpr const char* kGroupCompositing = "Compositing";
constexpr const char* kGroupDebugging = "Debugging";

constexpr const char* kHelpExamples =
    "Examples:\n"
    "  # the showcase, as an EXR with albedo, normal and depth layers and a PNG (docs/output.md)\n"
    "  pathtracer scenes/showcase.json -o out/showcase.exr -o out/showcase.png --aov albedo,N,Z\n"
    "  # a long render: 10 minutes at most, a checkpoint every 60 s; continue it later with --resume\n"
    "  pathtracer scene.json -o frame.exr --time-budget 600 --checkpoint frame.ckpt\n"
    "  # a non-finite sample reported at pixel 120,80, sample 37: render only that sample and print it\n"
    "  pathtracer scene.json -o frame.exr --replay 120,80,37\n"
    "\n"
    "Which backend and sampler is fastest on a scene: pathtracer-compare SCENE --out DIR (README).\n"
    "Details: docs/cli.md (long renders), docs/output.md (compositing), docs/samplers.md (quality).";

// The scene, the images written, the backend and the display transform.
void add_scene_output_options(CLI::App& app, Options& o) {
  app.get_help_ptr()->group(kGroupSceneOutput);
  app.add_option("scene", o.scene, "Scene file (native, Path of Light or CGR JSON)")->required();
  app.add_option("-o,--output", o.outputs,
                 "Output image (.exr, .png, .jpg, .ppm); repeat to write several formats from one render "
                 "(required except for a replay, --pixel or --replay)")
      ->allow_extra_args(false)
      ->group(kGroupSceneOutput);
  app.add_option("--width", o.width, "Image width (alone: keeps the scene's aspect ratio)")
      ->check(CLI::Range(1, kMaxResolution))
      ->group(kGroupSceneOutput);
  app.add_option("--height", o.height, "Image height (alone: keeps the scene's aspect ratio)")
      ->check(CLI::Range(1, kMaxResolution))
      ->group(kGroupSceneOutput);
  app.add_option("--set", o.overrides,
                 "Override a scene value before validation: KEY=VALUE, KEY a JSON path in the scene file "
                 "(render.spp=256, camera.fov=30, shapes[3].radius=2), VALUE JSON or a bare word; repeatable")
      ->allow_extra_args(false)
      ->group(kGroupSceneOutput);
  app.add_option("--accel", o.accel, "Acceleration structure")
      ->check(CLI::IsMember(accel_kind_names()))
      ->capture_default_str()
      ->group(kGroupSceneOutput);
  app.add_option("--threads", o.threads, "Worker threads (default: all hardware threads)")
      ->check(CLI::Range(1, kMaxThreads))
      ->group(kGroupSceneOutput);
  app.add_option("--exposure", o.exposure, "Display images: exposure in stops (default: the scene's)")
      ->check(finite_number())
      ->group(kGroupSceneOutput);
  app.add_option("--view", o.view,
                 "Display images: 'standard' (sRGB) or 'aces' (ACES 1.0 SDR video), or a view of the OCIO config")
      ->group(kGroupSceneOutput);
  app.add_option("--display", o.display, "Display images: a display of the OCIO config (default: its default)")
      ->group(kGroupSceneOutput);
  app.add_option("--look", o.look, "Display images: look(s) of the OCIO config, e.g. '+grade'")
      ->group(kGroupSceneOutput);
  app.add_option("--ocio-config", o.ocio_config, "OpenColorIO config file (default: $OCIO, if set)")
      ->group(kGroupSceneOutput);
  app.add_flag("--quiet", o.quiet, "Print errors only (no progress)")->group(kGroupSceneOutput);
}

// Noise, bias and the estimator: samples, integrator, sampler, filter.
void add_quality_options(CLI::App& app, Options& o) {
  app.add_option("--spp", o.spp, "Samples per pixel (default: the scene's; with --time-budget: no limit)")
      ->check(CLI::Range(1, kMaxSpp))
      ->group(kGroupQuality);
  app.add_option("--integrator", o.integrator,
                 "Integrator (default: the scene's); normal, depth, signature, bvh-cost: debug views")
      ->check(CLI::IsMember(integrator_names()))
      ->group(kGroupQuality);
  app.add_option("--max-depth", o.max_depth, "Bounces (path) or recursion depth (whitted) (default: the scene's)")
      ->check(CLI::Range(0, kMaxDepth))
      ->group(kGroupQuality);
  app.add_option("--sampler", o.sampler, "Sampler of the path integrator (docs/samplers.md)")
      ->check(CLI::IsMember(sampler_type_names()))
      ->capture_default_str()
      ->group(kGroupQuality);
  app.add_option("--filter", o.filter, "Pixel filter of the path integrator (default: the scene's, box)")
      ->check(CLI::IsMember(std::vector<std::string>(std::begin(kPixelFilterNames), std::end(kPixelFilterNames))))
      ->group(kGroupQuality);
  app.add_option("--clamp", o.clamp,
                 "Path integrator: clamp each sample's radiance to this largest channel value (0: off, the default)")
      ->check(finite_number() & CLI::Range(0.0f, std::numeric_limits<float>::max()))
      ->group(kGroupQuality);
  app.add_option("--seed", o.seed, "Random seed")->check(seed_value())->capture_default_str()->group(kGroupQuality);
}

// Time budgets, checkpoints, progress, memory and the run record (docs/cli.md).
void add_long_render_options(CLI::App& app, Options& o) {
  app.add_option("--time-budget", o.time_budget,
                 "Render in progressive passes for at most this many seconds (with --spp: whichever comes first)")
      ->check(finite_number() & CLI::Range(0.001, kMaxSeconds))
      ->group(kGroupLongRenders);
  app.add_option("--pass-spp", o.pass_spp,
                 "Samples per progressive pass (default: all at once; adapted to the time under --time-budget)")
      ->check(CLI::Range(1, kMaxSpp))
      ->group(kGroupLongRenders);
  app.add_option("--checkpoint", o.checkpoint, "Write a checkpoint to this file at pass boundaries")
      ->group(kGroupLongRenders);
  app.add_option("--checkpoint-every", o.checkpoint_every, "Seconds between checkpoints")
      ->check(finite_number() & CLI::Range(0.0, kMaxSeconds))
      ->capture_default_str()
      ->group(kGroupLongRenders);
  app.add_option("--resume", o.resume, "Continue the render saved in this checkpoint (same scene and settings)")
      ->group(kGroupLongRenders);
  app.add_option("--progress-interval", o.progress_interval,
                 "Seconds between progress lines when stderr is not a terminal")
      ->check(finite_number() & CLI::Range(0.05, kMaxSeconds))
      ->capture_default_str()
      ->group(kGroupLongRenders);
  app.add_option("--max-memory", o.max_memory, "Refuse renders estimated to need more memory than this (e.g. 4G, 512M)")
      ->group(kGroupLongRenders);
  app.add_option("--report", o.report,
                 "Write a run record (JSON: settings, versions, time per phase, speed, memory, spp reached)")
      ->group(kGroupLongRenders);
  app.add_option("--texture-cache", o.texture_cache,
                 "Memory for image texture tiles (e.g. 64M, 1G; default " +
                     byte_size_text(TextureCache::kDefaultBytes) + "): least recently used tiles are dropped "
                     "beyond it, and read again when needed")
      ->check(CLI::Validator(
          [](std::string& text) -> std::string {
            const std::optional<uint64_t> bytes = parse_byte_size(text);
            if (!bytes) return "'" + text + "' is not a size (e.g. 256M, 1G, 65536)";
            if (*bytes < kMinTextureCacheBytes) return "at least 1M, got '" + text + "'";
            return {};
          },
          "SIZE"))
      ->group(kGroupLongRenders);
}

// AOVs, alpha, EXR layout and crops (docs/output.md).
void add_compositing_options(CLI::App& app, Options& o) {
  app.add_option("--aov", o.aov,
                 "Extra EXR layers, comma-separated, each optionally ':half' or ':float' (docs/output.md): " +
                     join(aov_names(), ", ") + "; 'beauty:half' writes the beauty (R, G, B, A; float by default) as half")
      ->group(kGroupCompositing);
  app.add_option("--cryptomatte-levels", o.cryptomatte_levels,
                 "Ids kept per pixel by the CryptoObject and CryptoMaterial AOVs (two per EXR layer)")
      ->check(CLI::Range(1, kCryptomatteMaxRanks))
      ->capture_default_str()
      ->group(kGroupCompositing);
  app.add_flag("--film-transparent", o.film_transparent,
               "Leave what camera rays see when they hit nothing out of the image (alpha 0; PNG gets alpha); "
               "it still lights the scene (default: the scene's render.film_transparent)")
      ->group(kGroupCompositing);
  app.add_option("--exr-compression", o.exr_compression,
                 "EXR compression: " + join(exr_compression_names(), ", ") + " (dwaa/dwab take a level: dwaa:45)")
      ->check([](const std::string& value) {
        std::string error;
        return check_exr_compression(value, error) ? std::string() : error;
      })
      ->capture_default_str()
      ->group(kGroupCompositing);
  app.add_flag("--multipart", o.multipart, "EXR: one part per layer (readers load only the parts they need)")
      ->group(kGroupCompositing);
  auto* crop = app.add_option("--crop", o.crop, "Render only this region: X0,Y0,X1,Y1 as fractions of the frame")
                   ->delimiter(',')
                   ->expected(4)
                   ->check(finite_number())
                   ->group(kGroupCompositing);
  app.add_option("--crop-px", o.crop_px, "Render only this region: X,Y,W,H in pixels")
      ->delimiter(',')
      ->expected(4)
      ->excludes(crop)
      ->group(kGroupCompositing);
}

// The replay of one sample (docs/output.md), strict parsing and the version.
void add_debugging_options(CLI::App& app, Options& o) {
  auto* pixel = app.add_option("--pixel", o.pixel,
                               "Replay: render only one sample of pixel X,Y, as the render with these options "
                               "draws it, and print its radiance and AOVs (writes no files)")
                    ->delimiter(',')
                    ->expected(2)
                    ->group(kGroupDebugging);
  auto* sample = app.add_option("--sample", o.sample, "Replay: the sample index N for --pixel (default 0)")
                     ->needs(pixel)
                     ->group(kGroupDebugging);
  app.add_option("--replay", o.replay, "Replay: X,Y,N, shorthand for --pixel X,Y --sample N")
      ->delimiter(',')
      ->expected(3)
      ->excludes(pixel)
      ->excludes(sample)
      ->group(kGroupDebugging);
  app.add_flag("--strict", o.strict, "Treat warnings (e.g. unknown keys in legacy files) as errors")
      ->group(kGroupDebugging);
  app.set_version_flag("--version", [] { return version_text(); })->group(kGroupDebugging);
  // One code path for both spellings.
  app.final_callback([&o] {
    if (!o.pixel.empty()) {
      o.replay = {o.pixel[0], o.pixel[1], o.sample};
      o.replay_option = "--pixel";
    } else if (!o.replay.empty()) {
      o.replay_option = "--replay";
    }
  });
}

}  // namespace

namespace {

// Options users reach for under other tools' names, and ours. Checked before
// the edit distance: "--samples" is one edit from "--sample" (the replay's
// index) but means --spp.
constexpr std::pair<const char*, const char*> kOptionAliases[] = {
    {"--samples", "--spp"},          {"--sample-count", "--spp"},      {"--samples-per-pixel", "--spp"},
    {"--time", "--time-budget"},     {"--budget", "--time-budget"},    {"--time-limit", "--time-budget"},
    {"--depth", "--max-depth"},      {"--bounces", "--max-depth"},     {"--max-bounces", "--max-depth"},
    {"--out", "--output"},           {"--output-file", "--output"},    {"--override", "--set"},
    {"--resolution", "--width"},     {"--res", "--width"},             {"--memory", "--max-memory"},
    {"--threads-count", "--threads"}, {"--nthreads", "--threads"},     {"--aovs", "--aov"},
    {"--restart", "--resume"},       {"--continue", "--resume"},       {"--run-report", "--report"},
};

}  // namespace

std::string unknown_option_message(const CLI::App& app, const std::vector<std::string>& extras) {
  std::vector<std::string> names;
  for (const CLI::Option* opt : app.get_options())
    for (const std::string& n : opt->get_lnames()) names.push_back("--" + n);
  std::string message;
  for (const std::string& arg : extras) {
    if (arg.size() < 2 || arg[0] != '-') continue;
    const std::string word = arg.substr(0, arg.find('='));
    std::string suggestion;
    for (const auto& [alias, name] : kOptionAliases)
      if (word == alias) suggestion = name;
    if (suggestion.empty()) suggestion = closest_match(word, names);
    message += (message.empty() ? "" : "\nerror: ") + std::string("unknown option ") + pt::quoted(word) +
               (suggestion.empty() ? "; see --help" : "; did you mean " + pt::quoted(suggestion) + "?");
  }
  return message;
}

void add_options(CLI::App& app, Options& o) {
  add_scene_output_options(app, o);
  add_quality_options(app, o);
  add_long_render_options(app, o);
  add_distributed_options(app, o);
  add_compositing_options(app, o);
  add_debugging_options(app, o);
  app.footer(kHelpExamples);
}

}  // namespace pt
