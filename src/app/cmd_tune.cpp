// tuneray tune SCENE: online BVH tuning along a camera path, with a summary table (speed over
// the default configuration and over native Embree) and optionally a JSON report.
#include <fmt/core.h>

#include <fstream>
#include <iostream>
#include <memory>
#include <stdexcept>

#include "accel/kernel_isa.h"
#include "app/cli_parse.h"
#include "app/commands.h"
#include "app/progress.h"
#include "bench/tune_summary.h"
#include "image/atomic_file.h"
#include "tuning/tune_session.h"

namespace tuneray {

namespace {

struct TuneArgs {
  TuneOptions options;
  std::string objective = "render";
  std::string size = "320x180";
  std::string scheduler = QualityOptions{}.wavefront ? "wavefront" : "tile";
  bool tuned_only = false;
  std::string json;
  bool quiet = false;
};

int run_tune(TuneArgs& a) {
  a.options.objective = parse_objective(a.objective);
  std::tie(a.options.width, a.options.height) = parse_size(a.size);
  a.options.wavefront = a.scheduler == "wavefront";
  a.options.native_in_space = !a.tuned_only;
  fmt::print(
      "tuning {} (objective {}, {} cameras x {} frames, {}x{}, {} spp, {} scheduler; {}{}; tuned "
      "kernels {}) into {}\n",
      a.options.scene, a.objective, a.options.cameras, a.options.iterations, a.options.width,
      a.options.height, a.options.spp, a.scheduler,
      a.options.native_in_space ? "backend tuned|native + BVH" : "tuned BVH only",
      a.options.work_sizes ? " + scheduler, tile_size, batch_size" : "",
      bvh::to_string(bvh::kernel_isa()), a.options.db_path);
  ProgressBar bar("tune", static_cast<uint64_t>(a.options.cameras) * a.options.iterations,
                  !a.quiet && stderr_is_terminal());
  TuneReport report = run_tune_session(
      a.options,
      [&](const std::string& line) {
        bar.finish();
        if (!a.quiet) std::cout << line << std::endl;
      },
      [&](const TuneProgress& p) {
        bar.set_suffix(fmt::format("camera {}/{}, best speedup {:.2f}x", p.camera + 1,
                                   a.options.cameras, p.best_speedup));
        bar.advance();
      });
  bar.finish();
  TuneSummary sum = summarize_tune(report);
  fmt::print("\n{:>6} {:>8} {:>11} {:>11} {:>11} {:>8} {:>15} {:>9} {:>15} {:>6} {:>14}  {}\n",
             "camera", "mode", "default ms", "native ms", "chosen ms", "speedup", "95 % interval",
             "vs native", "95 % interval", "rounds", "search ms", "configuration");
  for (const auto& c : report.cameras)
    fmt::print(
        "{:>6} {:>8} {:>11.2f} {:>11.2f} {:>11.2f} {:>8.3f} {:>15} {:>9.3f} {:>15} {:>6} "
        "{:>14.1f}  {}\n",
        c.camera, c.mode, c.default_ms, c.native_ms, c.chosen_ms, c.speedup(),
        fmt::format("[{:.3f}, {:.3f}]", c.speedup_low, c.speedup_high), c.vs_native(),
        fmt::format("[{:.3f}, {:.3f}]", c.vs_native_low, c.vs_native_high),
        fmt::format("{}{}", c.compare_rounds, c.compare_within_target ? "" : "*"), c.accumulated_ms,
        c.config + (c.race_changed_choice ? " (race)" : "") +
            (c.fallback.empty() ? "" : fmt::format(" (kept {})", c.fallback)));
  fmt::print(
      "\nspeedup over the default configuration: median {:.3f}, geometric mean {:.3f}; "
      "{} of {} cameras searched, {} failed builds\n",
      sum.speedup_median, sum.speedup_geomean, sum.searched, report.cameras.size(),
      report.failed_builds);
  fmt::print(
      "speedup over native Embree (medium): median {:.3f}, geometric mean {:.3f}; "
      "tuned BVH chosen at {} of {} cameras\n",
      sum.vs_native_median, sum.vs_native_geomean, sum.tuned, report.cameras.size());
  if (a.options.finalists > 0)
    fmt::print(
        "race of the finalists: {} frames beside the searches' {}; chose another configuration "
        "than the tuner's best at {} of {} cameras\n",
        sum.race_frames, sum.search_frames, sum.race_changed, report.cameras.size());
  if (sum.fallbacks > 0)
    fmt::print(
        "kept a yardstick at {} of {} cameras: the tuner's choice measured slower than native "
        "by its median or than the default with its whole 95 % interval below 1 (its ratios in "
        "--json, 'rejected')\n",
        sum.fallbacks, report.cameras.size());
  if (sum.capped > 0)
    fmt::print(
        "* {} of {} cameras reached the round cap with an interval wider than ±{:.0f} %: the "
        "machine was too noisy to pin their ratios down\n",
        sum.capped, report.cameras.size(), 100 * a.options.compare_target);
  if (!a.json.empty()) {
    write_text_file(
        a.json,
        tune_report_json(a.options, a.objective, a.scheduler, a.size, report).dump(2) + "\n");
  }
  return 0;
}

}  // namespace

CommandAction add_tune_command(CLI::App& app) {
  auto a = std::make_shared<TuneArgs>();
  TuneOptions& o = a->options;
  CLI::App* cmd = app.add_subcommand("tune", "Tune the BVH online along a camera path");
  cmd->add_option("scene", o.scene, "Scene")->capture_default_str();
  cmd->add_option("--objective", a->objective, "render (render time) or total (build + render)")
      ->check(CLI::IsMember({"render", "total"}))
      ->capture_default_str();
  cmd->add_option("--db", o.db_path, "Tuning database (SQLite)")->capture_default_str();
  cmd->add_option("--epsilon", o.epsilon, "Probability of searching at a new camera")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  cmd->add_option("--predictor", o.predictor, "nn, rbf or both")
      ->check(CLI::IsMember({"nn", "rbf", "both"}))
      ->capture_default_str();
  cmd->add_option("--iterations", o.iterations, "Frames per camera position")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  cmd->add_option("--cameras", o.cameras, "Camera positions along the path")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  cmd->add_option("--camera-path", o.camera_path, "Camera path index")->capture_default_str();
  cmd->add_option("--spp", o.spp, "Samples per pixel per frame")
      ->check(CLI::Range(1, 4096))
      ->capture_default_str();
  cmd->add_option("--size", a->size, "Frame size")->capture_default_str();
  cmd->add_option("--max-bounces", o.max_bounces, "Path length")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  cmd->add_option("--seed", o.seed, "Seed of the tuner and the sampler")->capture_default_str();
  cmd->add_option("--scenes-dir", o.scenes_dir, "Folder to resolve scene files in");
  cmd->add_option("--scheduler", a->scheduler,
                  "Scheduler the frames are measured on (with --work-sizes: where the search "
                  "starts); default: the renderer's")
      ->check(CLI::IsMember({"tile", "wavefront"}))
      ->capture_default_str();
  cmd->add_flag("--tuned-only", a->tuned_only,
                "Search the tuned BVH's parameters only, without native Embree as a choice "
                "(stored under its own tuning key; native is still measured as a yardstick)");
  cmd->add_option("--finalists", o.finalists,
                  "The search's best configurations raced (with native Embree) before choosing; "
                  "0: the tuner's best, unraced")
      ->check(CLI::Range(0, 16))
      ->capture_default_str();
  cmd->add_option("--race-rounds", o.race_rounds, "Interleaved rounds of the finalists' race")
      ->check(CLI::Range(1, 100))
      ->capture_default_str();
  cmd->add_option("--baseline-repeats", o.baseline_repeats,
                  "Interleaved rounds of default, native and chosen per camera, at least")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  cmd->add_option("--compare-max-rounds", o.compare_max_rounds,
                  "Rounds at most, when the intervals are still wider than --compare-target")
      ->check(CLI::Range(2, 1000))
      ->capture_default_str();
  cmd->add_option("--compare-target", o.compare_target,
                  "Half-width of the 95 % intervals of the ratios the rounds go on until")
      ->check(CLI::Range(0.001, 1.0))
      ->capture_default_str();
  cmd->add_option("--json", a->json, "Write the per-camera results and the summary as JSON");
  cmd->add_flag("--work-sizes", o.work_sizes,
                "Also tune the scheduler (tile or wavefront) and its tile or batch size "
                "(stored under its own tuning key)");
  cmd->add_flag("--quiet,-q", a->quiet, "Only the summary");
  return [a] { return run_tune(*a); };
}

}  // namespace tuneray
