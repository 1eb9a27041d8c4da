#include "app/distributed.h"

#include <iomanip>
#include <iostream>
#include <sstream>

#include "app/job.h"
#include "app/mpi_launch.h"
#include "app/options.h"
#include "app/outputs.h"
#include "app/shard_file.h"
#include "app/signals.h"
#include "io/run_record.h"
#include "render/film/film.h"

namespace pt {
namespace {

// "wrote s.ptshard (samples [0,16) of 64, tile 1/4, 64x12 pixels): render 1.234 s".
std::string shard_line(const Options& o, const ShardInfo& info, const RunFigures& f) {
  const ShardPiece& p = info.pieces.front();
  std::vector<std::string> files = o.outputs;
  if (!o.shard_out.empty()) files.push_back(o.shard_out);
  std::ostringstream out;
  out << std::fixed << std::setprecision(3) << "wrote " << join(files, ", ") << " (samples " << p.done.text()
      << " of " << info.target_spp;
  if (p.done != p.share) out << ", share " << p.share.text() << " cut short by --time-budget";
  if (p.tile) out << ", tile " << p.tile->k << "/" << p.tile->n;
  out << ", " << p.crop.width() << "x" << p.crop.height() << " pixels): parse " << f.parse_s << " s, build "
      << f.build_s << " s, render " << f.render_s << " s, write " << f.write_s << " s\n";
  return out.str();
}

}  // namespace

int finish_shard(const Options& o, Job& job, const RenderScene& scene, const Film& film,
                 const RenderOutcome& outcome, RunFigures& figures, int signal) {
  if (outcome.cancelled) {
    std::cerr << "interrupted (signal " << signal << "): the shard's last pass is incomplete, so no state was "
              << "written; render it again (it reproduces exactly)"
              << (o.checkpoint.empty() ? "" : ", or resume it from its checkpoint " + o.checkpoint) << '\n';
    return exit_status_for_signal(signal);
  }
  const auto t0 = Clock::now();
  ImageMetadata metadata = render_metadata(job, scene, outcome, figures.render_s);
  for (auto& [name, value] : metadata.ints)  // the shard's samples, not the index it reached
    if (name == "pathtracer:spp") value = outcome.spp_done - job.shard.share.begin;
  const ShardInfo info = shard_info(job, film, outcome, metadata, figures.render_s);
  if (o.mpi) return mpi_gather(o, info, film, job.exr, job.stamps);
  std::string error;
  if (!write_outputs(o.outputs, film.layers(job.beauty_type), job.display, job.exr, metadata, job.stamps, error) ||
      (!o.shard_out.empty() && !write_shard(o.shard_out, info, film, error))) {
    std::cerr << "error: " << error << '\n';
    return kExitFailure;
  }
  figures.write_s = seconds_since(t0);
  if (!o.report.empty() && !write_run_record(o.report, run_record(o, job, scene, film, outcome, figures), error)) {
    std::cerr << "error: " << error << '\n';
    return kExitFailure;
  }
  if (!o.quiet) std::cout << shard_line(o, info, figures);
  return 0;
}

}  // namespace pt
