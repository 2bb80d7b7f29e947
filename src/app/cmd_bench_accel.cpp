// tuneray bench traversal|build: the matrices of bench/accel_bench.h as tables on stdout, and
// their JSON reports.
#include <tbb/global_control.h>

#include <cstdio>
#include <fstream>
#include <memory>

#include "app/commands.h"
#include "bench/scene_paths.h"
#include "image/atomic_file.h"

namespace tuneray {

namespace {

// The given scenes, else every shared scene; none at all is an error naming the command.
std::vector<std::string> scene_list(const AccelBenchOptions& args, const char* command) {
  auto scenes = !args.scenes.empty() ? args.scenes
                                     : shared_scene_files(find_shared_scenes_dir(args.scenes_dir));
  if (scenes.empty())
    std::fprintf(stderr, "bench %s: no scene given and no shared scenes found\n", command);
  return scenes;
}

std::unique_ptr<tbb::global_control> limit_threads(int threads) {
  if (threads <= 0) return nullptr;
  return std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                               threads);
}

bool write_json(const std::string& path, const nlohmann::json& j) {
  if (path.empty()) return true;
  try {
    write_text_file(path, j.dump(2) + "\n");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench: %s\n", e.what());
    return false;
  }
  return true;
}

TraversalHooks traversal_printer(const AccelBenchOptions& args) {
  TraversalHooks h;
  h.start = [](const TraversalScene& s) {
    std::printf("\n%s: %zu triangles, native build %.1f ms, %zu/%zu/%zu rays\n", s.spec.c_str(),
                s.triangles, s.native_build_ms, s.ray_counts[0], s.ray_counts[1], s.ray_counts[2]);
    std::printf("%-52s %9s %8s %8s %7s %8s | %-26s | %-26s | %-26s\n", "config", "build ms",
                "nodes", "leaves", "SAH", "MiB", "primary nat/tuned/ratio",
                "incoherent nat/tuned/ratio", "shadow nat/tuned/ratio");
  };
  h.row = [](const TraversalRow& r) {
    if (!r.refused.empty()) {
      std::printf("%-52s refused: %s\n", r.text.c_str(), r.refused.c_str());
      return;
    }
    std::string label = r.text == BvhConfig{}.to_string() ? "(defaults)" : r.text;
    std::printf("%-52s %9.1f %8zu %8zu %7.2f %8.1f |", label.c_str(), r.stats.build_ms,
                r.stats.node_count, r.stats.leaf_count, r.stats.sah_cost,
                r.stats.memory_bytes / 1048576.0);
    for (const RaySetRate& s : r.sets)
      std::printf(" %7.2f %7.2f %6.3f     |", s.native_mrays, s.tuned_mrays, s.ratio);
    std::printf("\n");
    std::fflush(stdout);
  };
  h.best = [](const TraversalScene& s) {
    std::printf("best on incoherent rays: %s (ratio %.3f)\n", s.best_config.c_str(), s.best_ratio);
  };
  h.render = [args](const RenderLevelRun& run) {
    const RenderVsNative& r = run.result;
    std::printf(
        "render %dx%d, %u spp, %s scheduler, first camera, %zu interleaved rounds: native %.2f ms, "
        "chosen %.2f ms (medians) -> %.3fx native, 95%% CI %.3f-%.3f%s\n  chosen: %s\n  (%s)\n",
        run.options.width, run.options.height, run.options.spp, run.scheduler.c_str(),
        r.native_ms.size(), r.native_median_ms, r.chosen_median_ms, r.speedup(), r.speedup_low,
        r.speedup_high, r.converged ? "" : " (not within +-3 % at the cap)", r.config.c_str(),
        run.source.c_str());
    std::fflush(stdout);
  };
  return h;
}

BuildHooks build_printer(int repeats) {
  BuildHooks h;
  h.start = [repeats](const BuildScene& s) {
    std::printf(
        "\n%s: %zu triangles; native = Embree's own build at the same quality, "
        "interleaved with the tuned one, medians of %d\n",
        s.spec.c_str(), s.triangles, repeats);
    std::printf("%-52s %9s %9s %6s %8s %8s %6s %8s %8s %10s\n", "config", "build ms", "native",
                "ratio", "nodes", "leaves", "depth", "SAH", "MiB", "RSS KiB");
  };
  h.row = [](const BuildRow& r) {
    if (!r.refused.empty()) {
      std::printf("%-52s refused: %s\n", r.text.c_str(), r.refused.c_str());
      return;
    }
    const BuildStats& s = r.stats;
    std::printf("%-52s %9.1f %9.1f %6.2f %8zu %8zu %6d %8.2f %8.1f %10zu  %s\n", r.text.c_str(),
                s.build_ms, r.native_median_ms, r.ratio, s.node_count, s.leaf_count, s.depth,
                s.sah_cost, s.memory_bytes / 1048576.0, r.rss_kib, s.notes.c_str());
    std::fflush(stdout);
  };
  return h;
}

}  // namespace

int run_bench_traversal(const AccelBenchOptions& args) {
  auto threads = limit_threads(args.threads);
  parse_bvh_config(args.bvh);  // a bad configuration fails before any scene loads
  auto scenes = scene_list(args, "traversal");
  if (scenes.empty()) return 1;
  nlohmann::json report = {
      {"rays_per_set", args.rays}, {"repeats", std::max(1, args.repeats)}, {"scenes", {}}};
  for (const std::string& spec : scenes) {
    report["scenes"].push_back(
        traversal_scene_json(run_traversal_scene(args, spec, traversal_printer(args))));
    // After every scene, so an interrupted run keeps what it measured.
    if (!write_json(args.json, report)) return 1;
  }
  return write_json(args.json, report) ? 0 : 1;
}

int run_bench_build(const AccelBenchOptions& args) {
  auto threads = limit_threads(args.threads);
  parse_bvh_config(args.bvh);
  auto scenes = scene_list(args, "build");
  if (scenes.empty()) return 1;
  const int repeats = std::max(1, args.repeats);
  nlohmann::json report = {{"repeats", repeats}, {"scenes", {}}};
  for (const std::string& spec : scenes)
    report["scenes"].push_back(
        build_scene_json(run_build_scene(args, spec, build_printer(repeats))));
  return write_json(args.json, report) ? 0 : 1;
}

}  // namespace tuneray
