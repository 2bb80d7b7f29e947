// tuneray bench render|peers|traversal|build|quality: the options of the benchmarks (their runs:
// cmd_bench_*.cpp). Bad values fail before any scene loads, in the order the options are checked.
#include <memory>
#include <tuple>

#include "app/cli_parse.h"
#include "app/commands.h"
#include "app/quality_cli.h"

namespace tuneray {

CommandAction add_bench_command(CLI::App& app) {
  CLI::App* bench =
      app.add_subcommand("bench", "Benchmarks: render, peers, traversal, build, quality");
  bench->require_subcommand(1);

  // Sizes are parsed when the command runs, so the library takes them typed.
  auto render = std::make_shared<RenderBenchOptions>();
  auto render_size = std::make_shared<std::string>("640x360");
  CLI::App* r = bench->add_subcommand(
      "render", "Render speed per scene, and Embree's pathtracer side by side");
  r->add_option("scenes", render->scenes, "Scenes (default: cornell + all shared scenes)");
  r->add_option("--size", *render_size, "Image size")->capture_default_str();
  r->add_option("--spp", render->spp, "Samples per pixel per repeat")
      ->check(CLI::Range(1, 4096))
      ->capture_default_str();
  r->add_option("--repeats", render->repeats,
                "Repeats (medians reported; interleaved with the pathtracer's frames)")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  r->add_option("--max-bounces", render->max_bounces, "Path length")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  r->add_option("--accel", render->accel, "Our acceleration structure backend")
      ->capture_default_str();
  r->add_option("--bvh", render->bvh, "Backend parameters key=value,... (see docs/bvh.md)");
  r->add_option("--json", render->json, "Write results as JSON");
  r->add_option("--scenes-dir", render->scenes_dir, "Folder of the shared scenes");
  r->add_flag("!--no-embree", render->embree_reference, "Skip Embree's reference pathtracer");

  auto accel = std::make_shared<AccelBenchOptions>();
  auto accel_size = std::make_shared<std::string>("320x180");
  auto add_accel_options = [&](CLI::App* c) {
    c->add_option("scenes", accel->scenes, "Scenes (default: every shared scene)");
    c->add_option("--rays", accel->rays, "Rays per ray set")
        ->check(CLI::Range(1000, 100000000))
        ->capture_default_str();
    c->add_option("--bvh", accel->bvh, "Tuned BVH configuration key=value,... (default: Embree's)");
    c->add_option("--json", accel->json, "Write results as JSON");
    c->add_option("--repeats", accel->repeats, "Timed repeats (median)")
        ->check(CLI::Range(1, 1000))
        ->capture_default_str();
    c->add_option("--threads", accel->threads, "Threads (0 = all cores)")
        ->check(CLI::Range(0, 1024));
    c->add_flag("!--no-sweep", accel->sweep, "Skip the small configuration sweep");
    c->add_option("--scenes-dir", accel->scenes_dir, "Folder of the shared scenes");
  };
  CLI::App* t = bench->add_subcommand(
      "traversal", "Tuned BVH vs Embree native: Mrays/s on primary, incoherent and shadow rays");
  add_accel_options(t);
  t->add_flag("--cpu-time", accel->cpu_time,
              "Time the ray sets by the process's CPU time instead of wall time (steadier on a "
              "shared machine; rates are then per CPU-second)");
  t->add_flag("!--no-render", accel->render,
              "Skip the render-level run (native vs the best configuration, whole frames)");
  t->add_option("--size", *accel_size, "Frame size of the render-level run")->capture_default_str();
  t->add_option("--spp", accel->spp, "Samples per pixel of a render-level frame")
      ->check(CLI::Range(1, 4096))
      ->capture_default_str();
  t->add_option("--scheduler", accel->scheduler, "Scheduler of the render-level run")
      ->check(CLI::IsMember({"tile", "wavefront"}))
      ->capture_default_str();
  t->add_option("--db", accel->db,
                "Render the best configuration of this `tune` database (same --size, --spp, "
                "--scheduler) instead of the table's best");
  CLI::App* b = bench->add_subcommand(
      "build", "Build time vs Embree native at the same quality (interleaved), tree shape, memory");
  add_accel_options(b);

  auto quality = std::make_shared<QualityBenchOptions>();
  auto quality_size = std::make_shared<std::string>("640x360");
  CLI::App* q = bench->add_subcommand(
      "quality", "RMSE vs ground truth at a frame budget: ablation of the quality techniques");
  q->add_option("scenes", quality->scenes, "Scenes (default: every scenes/*.json)");
  q->add_option("--size", *quality_size, "Image size")->capture_default_str();
  q->add_option("--frame-ms", quality->frame_ms, "Frame budget (ms)")
      ->check(CLI::Range(1.0, 1e7))
      ->capture_default_str();
  q->add_option("--target-spp", quality->target_spp,
                "Set the frame budget per scene to this many baseline spp (overrides --frame-ms)")
      ->check(CLI::Range(0.0, 1e6));
  q->add_option("--frames", quality->frames, "Frames accumulated")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  q->add_option("--repeats", quality->repeats,
                "Runs per configuration, interleaved, each with its own seed (medians reported)")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  q->add_option("--max-bounces", quality->max_bounces, "Path length")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  q->add_option("--truth-dir", quality->truth_dir, "Ground-truth cache folder")
      ->capture_default_str();
  q->add_option("--truth-spp", quality->truth_spp, "Ground-truth samples per pixel")
      ->check(CLI::Range(1, 1 << 20))
      ->capture_default_str();
  q->add_option("--bias-spp", quality->bias_spp, "Samples per pixel of the bias estimate")
      ->check(CLI::Range(1, 1 << 20))
      ->capture_default_str();
  q->add_option("--truth-until-rmse", quality->truth_until_rmse,
                "Stop the ground truth early once its estimated RMSE is below this (0 = off)")
      ->check(CLI::Range(0.0, 1e30));
  q->add_option("--clamp", quality->clamp,
                "Absolute firefly clamp m for the clamp rows (0 = use --clamp-rel)")
      ->check(CLI::Range(0.0f, 1e30f))
      ->capture_default_str();
  q->add_option("--clamp-rel", quality->clamp_relative,
                "Relative firefly clamp for the clamp rows: m = this x the image's mean pixel "
                "length")
      ->check(CLI::Range(0.0f, 1e30f))
      ->capture_default_str();
  std::string names;
  for (const std::string& n : quality_configurations()) names += (names.empty() ? "" : ", ") + n;
  q->add_option("--only", quality->only, "Run only these configurations: " + names);
  q->add_flag("--sweep", quality->sweep, "Also sweep tile size and wavefront batch size");
  q->add_option("--json", quality->json, "Write results as JSON");
  q->add_option("--plot", quality->plot, "Write PREFIX.dat and PREFIX.gp (gnuplot, RMSE vs time)");
  q->add_option("--scenes-dir", quality->scenes_dir, "Folder of the shared scenes");

  auto peers = std::make_shared<PeersBenchOptions>();
  auto peers_size = std::make_shared<std::string>("320x240");
  auto peers_json = std::make_shared<std::string>();
  CLI::App* p = bench->add_subcommand(
      "peers", "Error at equal time against Embree's pathtracer on its Cornell box");
  p->add_option("--size", *peers_size, "Image size")->capture_default_str();
  p->add_option("--max-bounces", peers->peer.max_path_length,
                "Path length (the pathtracer's --max-path-length)")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  p->add_option("--times", peers->times_s, "Render times in seconds to compare at")
      ->check(CLI::Range(1e-3, 1e4))
      ->capture_default_str();
  p->add_option("--reference-spp", peers->reference_spp,
                "Samples per pixel of both references (cached)")
      ->check(CLI::Range(2, 1 << 20))
      ->capture_default_str();
  p->add_option("--repeats", peers->repeats, "Interleaved timing repeats (medians reported)")
      ->check(CLI::Range(1, 100))
      ->capture_default_str();
  p->add_option("--frame-ms", peers->frame_ms, "Our frame budget")
      ->check(CLI::Range(0.1, 1e6))
      ->capture_default_str();
  p->add_option("--accel", peers->accel, "Our acceleration structure backend")
      ->capture_default_str();
  p->add_option("--bvh", peers->bvh, "Backend parameters key=value,... (see docs/bvh.md)");
  p->add_option("--truth-dir", peers->truth_dir, "Cache of both references")->capture_default_str();
  p->add_option("--pathtracer", peers->peer.binary, "Embree's pathtracer")->capture_default_str();
  p->add_option("--ecs", peers->peer.scene, "Embree's scene (.ecs, its .obj beside it)")
      ->capture_default_str();
  p->add_flag("!--no-denoise", peers->denoise, "Skip the runs with the denoiser");
  add_radiance_cache_options(p, peers->cache);  // vertex 0: no cached columns
  auto peers_reuse = std::make_shared<std::string>(std::to_string(peers->path_reuse));
  p->add_option("--path-reuse", *peers_reuse,
                "Also runs with path reuse: in pools of N = 2..64 pixels, auto (pools of 16 where "
                "the runs' own passes show they pay), or off (0: no reused columns)")
      ->capture_default_str();
  p->add_option("--json", *peers_json, "Write results as JSON");

  return [=] {
    if (q->parsed()) {
      check_quality_configurations(quality->only);  // before the size, as it always was
      std::tie(quality->width, quality->height) = parse_size(*quality_size);
      return run_bench_quality(*quality);
    }
    if (p->parsed()) {
      std::tie(peers->peer.width, peers->peer.height) = parse_size(*peers_size);
      QualityOptions reuse;
      parse_path_reuse(*peers_reuse, reuse);
      peers->path_reuse = reuse.path_reuse;
      peers->path_reuse_auto = reuse.path_reuse_auto;
      return run_bench_peers(*peers, *peers_json);
    }
    if (r->parsed()) {
      std::tie(render->width, render->height) = parse_size(*render_size);
      return run_bench_render(*render);
    }
    // A bad size fails now, not after the tables; without the render-level run it is unused.
    if (t->parsed() && accel->render)
      std::tie(accel->width, accel->height) = parse_size(*accel_size);
    if (t->parsed()) return run_bench_traversal(*accel);
    if (b->parsed()) return run_bench_build(*accel);
    return 2;
  };
}

}  // namespace tuneray
