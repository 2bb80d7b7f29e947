// `tuneray bench traversal` and `tuneray bench build`: the tuned BVH against Embree's native BVH
// on the same rays (primary, incoherent bounce, shadow), all cores, median of repeats; then
// (traversal) a rendered frame, native against the best configuration found
// (tuning/render_vs_native.h). One scene per call; the caller loops and reports.
#pragma once

#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "accel/accel.h"
#include "accel/bvh_config.h"
#include "render/render_settings.h"
#include "tuning/render_vs_native.h"

namespace tuneray {

struct AccelBenchOptions {
  std::vector<std::string> scenes;  // scene specs; empty: every shared scene found
  std::string scenes_dir;           // where the shared scenes live (empty: search)
  size_t rays = 200000;             // per ray set
  std::string bvh;                  // tuned configuration (`--bvh`); empty: defaults
  bool sweep = true;                // also run the small sweep of configurations
  std::string json;                 // write results here when not empty
  int repeats = 5;                  // median of this many timings (>= 1)
  int threads = 0;                  // 0: all cores
  bool cpu_time = false;            // process CPU time instead of wall time
  // The render-level run of `bench traversal` (defaults: tune's, so a --db it wrote matches).
  bool render = true;
  int width = 320, height = 180;
  uint32_t spp = 1;
  std::string scheduler = QualityOptions{}.wavefront ? "wavefront" : "tile";
  std::string db;  // the configuration to render: the database's best; empty: the table's best
};

// The configurations a matrix runs: `bvh` first, then (with `sweep`) the sweep's.
std::vector<std::string> traversal_configs(const AccelBenchOptions& options);
std::vector<std::string> build_configs(const AccelBenchOptions& options);

// One ray set's rates from the seconds of each timed pass: rays / median seconds, in Mrays/s.
struct RaySetRate {
  std::string name;
  double native_mrays = 0, tuned_mrays = 0;
  double ratio = 0;  // tuned / native
};
RaySetRate ray_set_rate(const std::string& name, size_t rays, const std::vector<double>& native_s,
                        const std::vector<double>& tuned_s);

struct TraversalRow {
  std::string text;      // the configuration as listed
  std::string refused;   // non-empty: the build refused it, with this reason
  std::string describe;  // the accelerator's own description of what it built
  BvhConfig config;
  BuildStats stats;
  std::vector<RaySetRate> sets;  // primary, incoherent, shadow
};

// The row with the highest incoherent ratio (the first on ties); none with a positive ratio:
// nullopt.
std::optional<size_t> best_incoherent(const std::vector<TraversalRow>& rows);

struct RenderLevelRun {
  RenderVsNativeOptions options;
  std::string scheduler, source;  // source: where the chosen configuration came from
  RenderVsNative result;
};

struct TraversalScene {
  std::string spec;
  size_t triangles = 0;
  double native_build_ms = 0;
  std::vector<size_t> ray_counts;  // per ray set
  std::vector<TraversalRow> rows;
  std::string best_config;  // empty when no row beat ratio 0
  double best_ratio = 0;
  std::optional<RenderLevelRun> render;
};

// Called as the scene runs (all optional): start once the rays exist, row after each
// configuration, best once the table is complete, render after the render-level run.
struct TraversalHooks {
  std::function<void(const TraversalScene&)> start, best;
  std::function<void(const TraversalRow&)> row;
  std::function<void(const RenderLevelRun&)> render;
};

TraversalScene run_traversal_scene(const AccelBenchOptions& options, const std::string& spec,
                                   const TraversalHooks& hooks = {});
nlohmann::json traversal_scene_json(const TraversalScene& scene);

struct BuildRow {
  std::string text, refused, describe, native_describe;
  BuildStats stats;  // of the tuned build (the median run's)
  double native_median_ms = 0, ratio = 0;
  std::vector<double> tuned_ms, native_ms;  // every run
  size_t rss_kib = 0;                       // resident memory after the builds
};

struct BuildScene {
  std::string spec;
  size_t triangles = 0;
  std::vector<BuildRow> rows;
};

struct BuildHooks {
  std::function<void(const BuildScene&)> start;
  std::function<void(const BuildRow&)> row;
};

BuildScene run_build_scene(const AccelBenchOptions& options, const std::string& spec,
                           const BuildHooks& hooks = {});
nlohmann::json build_scene_json(const BuildScene& scene);

}  // namespace tuneray
