// The options of `tuneray render` (docs: README.md, docs/quality.md); the run is cmd_render.cpp.
#include <memory>

#include "app/commands.h"
#include "app/render_args.h"

namespace tuneray {

CommandAction add_render_command(CLI::App& app) {
  auto args = std::make_shared<RenderArgs>();
  CLI::App* cmd = app.add_subcommand("render", "Render a scene to an image");
  cmd->add_option("scene", args->scene, "Built-in name, mesh file (.obj/.ply/.gltf) or .json scene")
      ->capture_default_str();
  CLI::Option* spp =
      cmd->add_option("--spp", args->spp, "Samples per pixel (with --truth-dir: 4096 unless given)")
          ->check(CLI::Range(1, 1 << 20))
          ->capture_default_str();
  cmd->add_option("--size", args->size, "Image size WIDTHxHEIGHT")->capture_default_str();
  cmd->add_option("--out", args->outputs, "Output file(s): .png, .exr or .pfm (repeatable)");
  cmd->add_option("--accel", args->accel, "Acceleration structure backend")->capture_default_str();
  cmd->add_option("--bvh", args->bvh, "Backend parameters key=value,... (see docs/bvh.md)");
  cmd->add_option("--threads", args->threads, "Worker threads (0 = all cores)")
      ->check(CLI::Range(0, 1024));
  cmd->add_option("--seed", args->seed, "Random seed")->capture_default_str();
  cmd->add_option("--max-bounces", args->max_bounces,
                  "Scattering events per path (1 = direct light)")
      ->check(CLI::Range(0, 1000))
      ->capture_default_str();
  cmd->add_option("--camera", args->camera, "Camera index")->capture_default_str();
  cmd->add_option("--tile-size", args->tile_size, "Tile side in pixels")
      ->check(CLI::Range(1, 4096))
      ->capture_default_str();
  cmd->add_option("--strategy", args->strategy,
                  "Light transport: mis, light (NEE only), bsdf (no NEE)")
      ->capture_default_str();
  cmd->add_option("--report", args->report, "Write timings as JSON to this file");
  cmd->add_option("--scenes-dir", args->scenes_dir,
                  "Folder to resolve scene files in ($TUNERAY_SCENES)");
  cmd->add_option("--exposure", args->exposure, "Exposure in stops for PNG output")
      ->capture_default_str();
  cmd->add_flag("--quiet,-q", args->quiet, "No progress bar or summary");
  cmd->add_flag("--profile-phases", args->profile_phases,
                "Time intersection, shading and shadow rays apart (summary and report; costs a "
                "little)");
  cmd->add_option("--frame-ms", args->frame_ms,
                  "Frame budget in ms: each frame adds as many spp as fit (replaces --spp)")
      ->check(CLI::Range(0.0, 1e7));
  cmd->add_option("--frames", args->frames, "Frames to accumulate in frame-budget mode")
      ->check(CLI::Range(1, 1 << 20))
      ->capture_default_str();
  cmd->add_option("--until-rmse", args->until_rmse,
                  "Stop before --spp once the image's estimated RMSE (from per-pixel variance) is "
                  "below this")
      ->check(CLI::Range(0.0, 1e30));
  cmd->add_option("--truth-dir", args->truth_dir,
                  "Ground-truth mode: read the cached unbiased reference of this scene, camera, "
                  "size, bounces and --spp/--until-rmse from this folder, or render and cache it "
                  "(tiles, PCG, seed 0; shared with bench quality)");
  add_quality_options(cmd, args->quality);
  return [args, spp] {
    if (!args->truth_dir.empty() && spp->count() == 0) args->spp = kTruthSpp;
    return run_render(*args);
  };
}

}  // namespace tuneray
