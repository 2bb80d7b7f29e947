// The options of `tuneray view` (docs/viewer.md); the viewer itself is src/view/.
#include <memory>

#include "app/cli_parse.h"
#include "app/commands.h"
#include "app/quality_cli.h"
#include "tuning/frame_bench.h"
#include "view/viewer.h"

namespace tuneray {

namespace {

struct ViewArgs {
  ViewerOptions options;
  std::string size = "640x360";
  QualityCli quality;
  std::string objective = "render";
};

}  // namespace

CommandAction add_view_command(CLI::App& app) {
  auto a = std::make_shared<ViewArgs>();
  ViewerOptions& o = a->options;
  CLI::App* cmd = app.add_subcommand(
      "view", "Interactive viewer: progressive path tracing in a window (needs a display)");
  cmd->add_option("scene", o.scene, "Built-in name, mesh file or .json scene")
      ->capture_default_str();
  cmd->add_option("--size", a->size, "Window and image size WIDTHxHEIGHT")->capture_default_str();
  cmd->add_option(
         "--frame-ms", o.frame_ms,
         "Rendering budget per frame in ms (display adds ~5 ms at 640x360: 25 gives ~30 fps)")
      ->check(CLI::Range(0.1, 1e6))
      ->capture_default_str();
  cmd->add_option("--accel", o.accel, "Acceleration structure backend")->capture_default_str();
  cmd->add_option("--bvh", o.bvh, "Backend parameters key=value,... (see docs/bvh.md)");
  cmd->add_option("--threads", o.threads, "Worker threads (0 = all cores)")
      ->check(CLI::Range(0, 1024));
  cmd->add_option("--seed", o.seed, "Random seed")->capture_default_str();
  cmd->add_option("--max-bounces", o.max_bounces, "Scattering events per path")
      ->check(CLI::Range(0, 1000))
      ->capture_default_str();
  cmd->add_option("--camera", o.camera, "Camera index to start from")->capture_default_str();
  cmd->add_option("--path", o.path, "Play back this camera path of the scene")
      ->check(CLI::Range(0, 1 << 20));
  cmd->add_option("--path-frames", o.path_frames,
                  "Frames the playback takes (then it holds the path's last camera)")
      ->check(CLI::Range(1, 1 << 20))
      ->capture_default_str();
  cmd->add_option("--frames", o.frames, "Scripted: stop after this many frames")
      ->check(CLI::Range(1, 1 << 24));
  cmd->add_option("--screenshot", o.screenshot,
                  "Scripted: write what the window shows after the last frame (.png/.exr/.pfm)");
  cmd->add_option("--record", o.record, "Write the cameras flown through as a camera path (JSON)");
  cmd->add_option("--save-prefix", o.save_prefix, "File name start of the images P and X save")
      ->capture_default_str();
  cmd->add_option("--exposure", o.exposure, "Exposure in stops")->capture_default_str();
  cmd->add_flag("--chart", o.chart, "Show the strip chart of frame times from the start (key G)");
  cmd->add_option("--scenes-dir", o.scenes_dir,
                  "Folder to resolve scene files in ($TUNERAY_SCENES)");
  cmd->add_flag("--quiet,-q", o.quiet, "No help or summary lines");
  cmd->add_flag("--tune", o.tune,
                "Tune the accelerator online while viewing, as `tune` does (same database and "
                "keys: size, 1 spp, bounces, scheduler)");
  cmd->add_option("--db", o.tuning.db_path, "Tuning database (SQLite) of --tune")
      ->capture_default_str();
  cmd->add_option("--objective", a->objective, "render or total (build + render), for --tune")
      ->check(CLI::IsMember({"render", "total"}))
      ->capture_default_str();
  cmd->add_option("--epsilon", o.tuning.epsilon, "Probability of searching at a new camera")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  add_quality_options(cmd, a->quality);
  return [a] {
    std::tie(a->options.width, a->options.height) = parse_size(a->size);
    a->options.quality = resolve_quality(a->quality);
    // Uniform sampling unless asked for: adaptive passes' bookkeeping over the whole film
    // overran a 25 ms budget to ~45 ms per frame at 640x360 (docs/viewer.md), and a viewer
    // restarts its film at every camera move, before adaptive sampling would pay off.
    if (!a->quality.adaptive_on) a->options.quality.adaptive = false;
    a->options.tuning.objective = parse_objective(a->objective);
    return run_viewer(a->options);
  };
}

}  // namespace tuneray
