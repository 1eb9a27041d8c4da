// pathtracer: renders a scene file to one or more images.
//
//   pathtracer SCENE -o OUT [-o OUT2 ...] [--accel embree|bvh] [--threads N] [--spp N]
//              [--seed N] [--integrator NAME] [--max-depth N] [--filter box|gaussian|mitchell]
//              [--sampler random|jittered|sobol]
//              [--clamp X] [--width W] [--height H] [--strict] [--quiet] [--report FILE]
//              [--aov LIST] [--crop X0,Y0,X1,Y1 | --crop-px X,Y,W,H] [--replay X,Y,N]
//
// Outputs, AOVs, crops and replays: docs/output.md.
// Exit status: 0 success; 1 the scene, the render or an output failed (nothing
// is written for a bad scene); 2 a bad command line (CLI11's message).
#include <chrono>
#include <cmath>
#include <cstdint>
#include <iomanip>
#include <iostream>
#include <limits>
#include <memory>
#include <cstdlib>
#include <optional>
#include <set>
#include <stdexcept>
#include <sstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <OpenImageIO/imageio.h>
#include <embree3/rtcore_config.h>
#include <oneapi/tbb/version.h>

#include "accel/accelerator.h"
#include "core/diagnostics.h"
#include "core/parallel.h"
#include "io/image_io.h"
#include "io/run_record.h"
#include "render/film/aov.h"
#include "render/film/film.h"
#include "render/film/filter.h"
#include "render/integrators/integrator.h"
#include "render/render_scene.h"
#include "scene/loader.h"

namespace {

struct Options {
  std::string scene;
  std::vector<std::string> outputs;
  std::string accel = "embree";
  int threads = 0;     // 0: all hardware threads
  int spp = 0;         // 0: the scene's value
  uint64_t seed = 0;
  std::string integrator;  // empty: the scene's value
  int max_depth = -1;      // < 0: the scene's value
  std::string filter;      // empty: the scene's value
  std::string sampler = "random";  // the path integrator's sampler (docs/samplers.md)
  float clamp = -1.0f;     // < 0: the scene's value; 0 = off
  int width = 0, height = 0;
  bool strict = false;
  bool quiet = false;
  std::string report;  // run record (JSON); empty: none
  // Display images (PNG, JPEG, PPM); see src/io/display.h.
  std::optional<float> exposure;  // stops; unset: the scene's
  std::string view, display, look;
  std::string ocio_config;  // unset: $OCIO
  // docs/output.md
  std::string aov;                 // --aov list; empty: beauty only
  std::vector<double> crop;        // fractions x0, y0, x1, y1; empty: the full frame
  std::vector<int> crop_px;        // pixels x, y, w, h; empty: the full frame
  std::vector<int> replay;         // x, y, sample; empty: a normal render
};

constexpr int kExitFailure = 1;
constexpr int kExitUsage = 2;
constexpr int kMaxThreads = 4096;
constexpr int kMaxSpp = 1 << 20;
constexpr int kMaxDepth = 1 << 16;
constexpr int kMaxResolution = 32768;  // as pt::LoadOptions::max_resolution

std::string version_text() {
  const int oiio = OIIO::openimageio_version();
  std::ostringstream os;
  os << "pathtracer " << PT_VERSION << '\n'
     << "  Embree " << RTC_VERSION_STRING << '\n'
     << "  OpenImageIO " << oiio / 10000 << '.' << oiio / 100 % 100 << '.' << oiio % 100 << '\n'
     << "  oneTBB " << TBB_runtime_version();
  return os.str();
}

std::string join(const std::vector<std::string>& items, const char* sep) {
  std::string s;
  for (const std::string& item : items) s += (s.empty() ? "" : sep) + item;
  return s;
}

void add_options(CLI::App& app, Options& o) {
  app.add_option("scene", o.scene, "Scene file (native, Path of Light or CGR JSON)")->required();
  app.add_option("-o,--output", o.outputs,
                 "Output image (.exr, .png, .ppm); repeat to write several formats from one render")
      ->allow_extra_args(false);
  app.add_option("--accel", o.accel, "Acceleration structure")
      ->check(CLI::IsMember(pt::accel_kind_names()))
      ->capture_default_str();
  app.add_option("--threads", o.threads, "Worker threads (default: all hardware threads)")
      ->check(CLI::Range(1, kMaxThreads));
  app.add_option("--spp", o.spp, "Samples per pixel (default: the scene's)")->check(CLI::Range(1, kMaxSpp));
  app.add_option("--seed", o.seed, "Random seed")->capture_default_str();
  app.add_option("--integrator", o.integrator,
                 "Integrator (default: the scene's)")
      ->check(CLI::IsMember(pt::integrator_names()));
  app.add_option("--max-depth", o.max_depth, "Bounces (path) or recursion depth (whitted) (default: the scene's)")
      ->check(CLI::Range(0, kMaxDepth));
  app.add_option("--filter", o.filter, "Pixel filter of the path integrator (default: the scene's, box)")
      ->check(CLI::IsMember({"box", "gaussian", "mitchell"}));
  app.add_option("--sampler", o.sampler, "Sampler of the path integrator (docs/samplers.md)")
      ->check(CLI::IsMember(pt::sampler_type_names()))
      ->capture_default_str();
  app.add_option("--clamp", o.clamp,
                 "Path integrator: clamp each sample's radiance to this largest channel value (0: off, the default)")
      ->check(CLI::Range(0.0f, std::numeric_limits<float>::max()));
  app.add_option("--width", o.width, "Image width (alone: keeps the scene's aspect ratio)")
      ->check(CLI::Range(1, kMaxResolution));
  app.add_option("--height", o.height, "Image height (alone: keeps the scene's aspect ratio)")
      ->check(CLI::Range(1, kMaxResolution));
  app.add_flag("--strict", o.strict, "Treat warnings (e.g. unknown keys in legacy files) as errors");
  app.add_flag("--quiet", o.quiet, "Print errors only");
  app.add_option("--report", o.report, "Write a run record (JSON: settings, backend, time per phase)");
  app.add_option("--exposure", o.exposure, "Display images: exposure in stops (default: the scene's)");
  app.add_option("--view", o.view,
                 "Display images: 'standard' (sRGB) or 'aces' (ACES 1.0 SDR video), or a view of the OCIO config");
  app.add_option("--display", o.display, "Display images: a display of the OCIO config (default: its default)");
  app.add_option("--look", o.look, "Display images: look(s) of the OCIO config, e.g. '+grade'");
  app.add_option("--ocio-config", o.ocio_config, "OpenColorIO config file (default: $OCIO, if set)");
  app.add_option("--aov", o.aov,
                 "Extra EXR layers, comma-separated, each optionally ':half' or ':float' (docs/output.md): " +
                     join(pt::aov_names(), ", "));
  auto* crop = app.add_option("--crop", o.crop, "Render only this region: X0,Y0,X1,Y1 as fractions of the frame")
                   ->delimiter(',')
                   ->expected(4);
  app.add_option("--crop-px", o.crop_px, "Render only this region: X,Y,W,H in pixels")
      ->delimiter(',')
      ->expected(4)
      ->excludes(crop);
  app.add_option("--replay", o.replay,
                 "Render only sample N of pixel (X, Y) (as a full render draws it) and print its radiance: X,Y,N")
      ->delimiter(',')
      ->expected(3);
  app.set_version_flag("--version", version_text());
}

// The display pipeline for PNG/JPEG/PPM outputs: the scene's transform and
// exposure, overridden from the command line; $OCIO names a config when
// --ocio-config does not. The course transforms ignore the OCIO settings.
pt::DisplaySettings display_settings(const Options& o, const pt::FilmDesc& film) {
  pt::DisplaySettings d;
  d.transform = film.display;
  d.exposure = o.exposure.value_or(film.exposure.value);
  d.view = o.view;
  d.display = o.display;
  d.look = o.look;
  d.ocio_config = o.ocio_config;
  if (d.ocio_config.empty()) {
    if (const char* env = std::getenv("OCIO"); env != nullptr) d.ocio_config = env;
  }
  return d;
}

// Checks every output path before any work is done. Returns false after printing why.
bool check_outputs(const std::vector<std::string>& outputs) {
  std::set<std::string> seen;
  for (const std::string& path : outputs) {
    if (!pt::is_supported_image_path(path)) {
      std::cerr << "error: cannot write '" << path << "': unsupported image extension (supported: "
                << join(pt::supported_image_extensions(), ", ") << ")\n";
      return false;
    }
    if (!seen.insert(path).second) {
      std::cerr << "error: output '" << path << "' is given more than once\n";
      return false;
    }
  }
  return true;
}

void print_diagnostics(const pt::Diagnostics& diag, bool quiet) {
  if (diag.all().empty() || (quiet && !diag.has_errors())) return;
  std::cerr << diag.format();
}

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// The region to render, in pixels of a width x height frame; false after printing why.
bool crop_window(const Options& o, int width, int height, pt::PixelRect& out) {
  out = {0, 0, width, height};
  if (!o.replay.empty()) {
    out = {o.replay[0], o.replay[1], o.replay[0] + 1, o.replay[1] + 1};
  } else if (!o.crop.empty()) {
    const std::vector<double>& c = o.crop;
    if (!(0.0 <= c[0] && c[0] < c[2] && c[2] <= 1.0 && 0.0 <= c[1] && c[1] < c[3] && c[3] <= 1.0)) {
      std::cerr << "error: --crop: need 0 <= X0 < X1 <= 1 and 0 <= Y0 < Y1 <= 1\n";
      return false;
    }
    out = {static_cast<int>(std::floor(c[0] * width)), static_cast<int>(std::floor(c[1] * height)),
           static_cast<int>(std::ceil(c[2] * width)), static_cast<int>(std::ceil(c[3] * height))};
  } else if (!o.crop_px.empty()) {
    const std::vector<int>& c = o.crop_px;
    if (c[0] > width || c[1] > height || c[2] > width || c[3] > height) {  // also keeps X + W from overflowing
      std::cerr << "error: --crop-px: " << c[2] << "x" << c[3] << " at (" << c[0] << ", " << c[1]
                << ") is not inside the " << width << "x" << height << " frame\n";
      return false;
    }
    out = {c[0], c[1], c[0] + c[2], c[1] + c[3]};
  }
  if (out.x0 < 0 || out.y0 < 0 || out.empty() || out.x1 > width || out.y1 > height) {
    std::cerr << "error: " << (o.replay.empty() ? "the crop" : "the replayed pixel") << " [" << out.x0 << ", "
              << out.x1 << ") x [" << out.y0 << ", " << out.y1 << ") is not inside the " << width << "x" << height
              << " frame\n";
    return false;
  }
  return true;
}

// The replayed sample's AOVs, one per line: its first hit and, for the path
// integrator, its lighting split (docs/output.md).
void print_replay_aovs(const pt::Film& film, int x, int y) {
  for (const pt::AovRequest& r : film.aovs()) {
    if (r.type == pt::AovType::Samples || r.type == pt::AovType::Variance) continue;
    std::cout << "  " << pt::aov_info(r.type).name << ":";
    for (float v : film.aov_value(r.type, x, y)) std::cout << ' ' << v;
    std::cout << '\n';
  }
}

int run(const Options& o) {
  if (o.outputs.empty() && o.replay.empty()) {
    std::cerr << "error: --output is required (except with --replay)\n";
    return kExitUsage;
  }
  if (!check_outputs(o.outputs)) return kExitUsage;
  std::vector<pt::AovRequest> aovs;
  if (std::string why; !o.aov.empty() && !pt::parse_aov_list(o.aov, aovs, why)) {
    std::cerr << "error: --aov: " << why << '\n';
    return kExitUsage;
  }
  if (!o.replay.empty()) {  // a replay reports every AOV of its one sample (they draw no random numbers)
    aovs.clear();
    for (const pt::AovInfo& info : pt::aov_catalogue()) aovs.push_back({info.type, info.default_type});
  }
  pt::AccelKind accel = pt::AccelKind::Embree;
  pt::parse_accel_kind(o.accel, accel);  // already validated by CLI11

  // Parse.
  auto t0 = Clock::now();
  pt::Diagnostics diag;
  diag.set_warnings_as_errors(o.strict);
  pt::LoadOptions load_options;
  load_options.strict = o.strict;
  const std::optional<pt::SceneDescription> desc = pt::load_scene(o.scene, load_options, diag);
  print_diagnostics(diag, o.quiet);
  if (!desc || diag.has_errors()) return kExitFailure;
  const double parse_s = seconds_since(t0);

  // Integrator (checked before the expensive build).
  pt::IntegratorSettings settings;
  settings.max_depth = o.max_depth >= 0 ? o.max_depth : desc->render.max_depth.value;
  settings.spp = o.spp > 0 ? o.spp : desc->render.spp.value;
  settings.seed = o.seed;
  settings.filter = desc->render.filter;
  if (o.filter == "gaussian") settings.filter = pt::PixelFilterType::Gaussian;
  if (o.filter == "mitchell") settings.filter = pt::PixelFilterType::Mitchell;
  if (o.filter == "box") settings.filter = pt::PixelFilterType::Box;
  settings.sampler = pt::parse_sampler_type(o.sampler).value_or(pt::SamplerType::Random);
  settings.clamp = o.clamp >= 0.0f ? o.clamp : desc->render.clamp.value;
  if (!o.replay.empty()) {
    if (o.replay[2] < 0 || o.replay[2] >= settings.spp) {
      std::cerr << "error: --replay: sample " << o.replay[2] << " is not one of the render's " << settings.spp
                << " samples per pixel\n";
      return kExitUsage;
    }
    settings.only_sample = o.replay[2];
  }
  const std::string integrator_name = o.integrator.empty() ? desc->render.integrator.value : o.integrator;
  std::string error;
  const std::unique_ptr<pt::Integrator> integrator = pt::make_integrator(integrator_name, settings, error);
  if (!integrator) {
    pt::Diagnostics d;
    d.error(o.integrator.empty() ? desc->render.integrator.where : pt::SourceLocation{}, error);
    std::cerr << d.format();
    return kExitFailure;
  }

  // The display pipeline (checked before the expensive build, like the outputs).
  const pt::DisplaySettings display = display_settings(o, desc->film);
  if (display.transform != pt::DisplayTransform::Srgb && !(o.view.empty() && o.display.empty() && o.look.empty()))
    std::cerr << "warning: --view, --display and --look apply to native scenes; this scene's display images "
                 "use its course's documented curve (docs/rendering.md)\n";
  if (!pt::DisplayEncoder::create(display, error)) {
    std::cerr << "error: display images: " << error << '\n';
    return kExitUsage;
  }

  // Build.
  t0 = Clock::now();
  pt::WorkerPool pool(o.threads);
  pt::Diagnostics build_diag;
  build_diag.set_warnings_as_errors(o.strict);
  pt::BuildOptions build_options;
  build_options.accel = accel;
  build_options.width_override = o.width;
  build_options.height_override = o.height;
  const std::unique_ptr<pt::RenderScene> scene = pt::build_render_scene(*desc, build_options, pool, build_diag);
  print_diagnostics(build_diag, o.quiet);
  if (!scene) return kExitFailure;
  if (std::string why; !integrator->can_render(*scene, why)) {  // e.g. bvh-cost with --accel=embree
    std::cerr << "error: " << why << '\n';
    return kExitFailure;
  }
  const double build_s = seconds_since(t0);

  pt::PixelRect crop;
  if (!crop_window(o, scene->width, scene->height, crop)) return kExitUsage;

  // Render.
  t0 = Clock::now();
  pt::Film film(scene->width, scene->height, crop, aovs);
  integrator->render(*scene, film, pool);
  const double render_s = seconds_since(t0);
  const pt::NonFiniteReport& non_finite = film.non_finite();
  if (non_finite.total() > 0 && !o.quiet)
    std::cerr << "warning: " << non_finite.describe() << "; they were added as black (replay one with --replay X,Y,N)\n";
  if (!o.replay.empty()) {
    const pt::PixelSum& s = film.sum(crop.x0, crop.y0);
    const pt::RGB v = non_finite.total() > 0 ? non_finite.value : s.value();
    std::cout << std::setprecision(9) << "replay pixel (" << crop.x0 << ", " << crop.y0 << ") sample "
              << settings.only_sample << ": radiance " << v.r << " " << v.g << " " << v.b << '\n';
    print_replay_aovs(film, crop.x0, crop.y0);
  }

  // Write.
  t0 = Clock::now();
  const pt::LayeredImage image = film.layers();
  pt::RenderStamp stamp;
  stamp.render_seconds = render_s;
  stamp.spp = settings.spp;
  stamp.seed = settings.seed;
  stamp.backend = scene->accel->stats().backend;
  stamp.integrator = integrator_name;
  stamp.software_version = PT_VERSION;
  stamp.has_camera = true;
  stamp.world_to_camera = scene->camera.world_to_camera();
  stamp.world_to_ndc = scene->camera.world_to_ndc();
  pt::ImageMetadata metadata;
  pt::add_render_stamp(metadata, stamp);
  for (const std::string& path : o.outputs) {
    if (!pt::write_layered_image(path, image, display, error, metadata)) {
      std::cerr << "error: " << error << '\n';
      return kExitFailure;
    }
  }
  const double write_s = seconds_since(t0);

  if (!o.report.empty()) {
    pt::RunRecord record;
    record.scene = o.scene;
    record.integrator = integrator_name;
    record.width = scene->width;
    record.height = scene->height;
    record.spp = settings.spp;
    record.max_depth = settings.max_depth;
    record.seed = settings.seed;
    record.filter = pt::pixel_filter_name(settings.filter);
    record.clamp = settings.clamp;
    record.threads = pool.threads();
    const pt::AccelStats stats = scene->accel->stats();
    record.accel_backend = stats.backend;
    record.accel_memory_bytes = stats.memory_bytes;
    record.primitive_count = stats.primitive_count;
    record.timings = {parse_s, build_s - stats.build_seconds, stats.build_seconds, render_s, write_s,
                      parse_s + build_s + render_s + write_s};
    record.software_version = PT_VERSION;
    if (!pt::write_run_record(o.report, record, error)) {
      std::cerr << "error: " << error << '\n';
      return kExitFailure;
    }
  }

  if (!o.quiet && !o.outputs.empty()) {
    std::cout << std::fixed << std::setprecision(3) << "wrote " << join(o.outputs, ", ") << " ("
              << scene->width << "x" << scene->height << ", " << integrator_name << ", " << settings.spp
              << " spp, " << pool.threads() << " threads"
              << (settings.clamp > 0.0f ? ", clamp " + std::to_string(settings.clamp) : std::string())
              << "): parse " << parse_s << " s, build " << build_s
              << " s, render " << render_s << " s, write " << write_s << " s\n";
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"pathtracer: renders a scene file (native, Path of Light or CGR JSON) to EXR/PNG/PPM"};
  Options options;
  add_options(app, options);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);  // prints help, version or the error
    return code == 0 ? 0 : kExitUsage;
  }
  try {
    return run(options);
  } catch (const std::exception& e) {  // e.g. std::bad_alloc for an absurdly large scene
    std::cerr << "error: " << e.what() << '\n';
    return kExitFailure;
  }
}
