// The traversal matrix: every configuration against native Embree on the same ray sets, then
// a rendered frame, native against the best configuration (the table's or a database's).
#include <stdexcept>

#include "accel/embree_native.h"
#include "accel/tuned_bvh.h"
#include "bench/accel_bench.h"
#include "bench/accel_json.h"
#include "bench/ray_sets.h"
#include "scene/load.h"
#include "tuning/stats.h"

namespace tuneray {

namespace {

std::string size_text(int width, int height) {
  return std::to_string(width) + "x" + std::to_string(height);
}

RenderLevelRun render_run(const AccelBenchOptions& a, const Scene& scene, const BvhConfig& best) {
  RenderLevelRun run;
  RenderVsNativeOptions& o = run.options;
  o.width = a.width;
  o.height = a.height;
  o.spp = a.spp;
  o.repeats = std::max(2, a.repeats);
  o.max_repeats = std::max(o.repeats, 30);
  o.wavefront = a.scheduler == "wavefront";
  run.scheduler = a.scheduler;
  const CameraDesc& camera = scene.cameras.front();
  AccelChoice chosen = AccelChoice::tuned(best);
  run.source = "best of the table on incoherent rays";
  if (!a.db.empty()) {
    auto found = best_in_database(a.db, scene, camera, o);
    if (!found)
      throw std::runtime_error("bench traversal: " + a.db + " holds no `tune --objective " +
                               "render` data for " + size_text(a.width, a.height) + ", " +
                               std::to_string(o.spp) + " spp, " + a.scheduler + " on this machine");
    chosen = found->choice;
    run.source = "best in " + a.db + " (" + found->tuning_key + ")";
  }
  run.result = render_vs_native(scene, camera, chosen, o);
  return run;
}

}  // namespace

// Branching 4 and 8, leaf sizes 1-8, high quality. sah_block_size=4 makes the SAH count leaf
// cost in packs of 4, which is how our leaves store triangles.
std::vector<std::string> traversal_configs(const AccelBenchOptions& options) {
  std::vector<std::string> out = {parse_bvh_config(options.bvh).to_string()};
  if (!options.sweep) return out;
  for (int width : {4, 8}) {
    const std::string w = "branching=" + std::to_string(width);
    out.push_back(w + ",max_leaf=1");
    out.push_back(w + ",max_leaf=4");
    for (int leaf : {4, 8}) out.push_back(w + ",sah_block_size=4,max_leaf=" + std::to_string(leaf));
  }
  const std::string best_guess = "branching=8,sah_block_size=4,max_leaf=8";
  out.push_back(best_guess + ",quality=high");
  out.push_back(best_guess + ",static=1");
  out.push_back(best_guess + ",compact=1");
  return out;
}

RaySetRate ray_set_rate(const std::string& name, size_t rays, const std::vector<double>& native_s,
                        const std::vector<double>& tuned_s) {
  RaySetRate r{name, rays / median(native_s) / 1e6, rays / median(tuned_s) / 1e6, 0};
  r.ratio = r.tuned_mrays / r.native_mrays;
  return r;
}

std::optional<size_t> best_incoherent(const std::vector<TraversalRow>& rows) {
  std::optional<size_t> best;
  double best_ratio = 0;
  for (size_t i = 0; i < rows.size(); ++i)
    for (const RaySetRate& set : rows[i].sets)
      if (set.name == "incoherent" && set.ratio > best_ratio) {
        best_ratio = set.ratio;
        best = i;
      }
  return best;
}

TraversalScene run_traversal_scene(const AccelBenchOptions& a, const std::string& spec,
                                   const TraversalHooks& hooks) {
  const int repeats = std::max(1, a.repeats);
  Scene scene = load_scene(spec, LoadOptions{a.scenes_dir});
  GeometryView g{scene.positions.data(), scene.positions.size(), scene.triangles.data(),
                 scene.triangles.size()};
  EmbreeNativeAccel native;
  TraversalScene out;
  out.spec = spec;
  out.triangles = g.triangle_count;
  out.native_build_ms = native.build(g).build_ms;
  std::vector<RaySet> sets = make_ray_sets(scene, native, a.rays);
  for (const RaySet& set : sets) out.ray_counts.push_back(set.rays.size());
  if (hooks.start) hooks.start(out);

  for (const std::string& text : traversal_configs(a)) {
    TunedBvhAccel tuned(parse_bvh_config(text));
    TraversalRow& row = out.rows.emplace_back();
    row.text = text;
    try {
      row.stats = tuned.build(g);
    } catch (const BuildError& e) {
      row.refused = e.what();
      if (hooks.row) hooks.row(row);
      continue;
    }
    row.describe = tuned.describe();
    row.config = tuned.config();
    for (const RaySet& set : sets) {
      std::vector<double> nat, tun;
      trace_seconds(native, set);  // warm caches
      trace_seconds(tuned, set);
      for (int r = 0; r < repeats; ++r) {
        nat.push_back(trace_seconds(native, set, a.cpu_time));
        tun.push_back(trace_seconds(tuned, set, a.cpu_time));
      }
      row.sets.push_back(ray_set_rate(set.name, set.rays.size(), nat, tun));
    }
    if (hooks.row) hooks.row(row);
  }

  BvhConfig best_bvh = parse_bvh_config(a.bvh);
  if (std::optional<size_t> best = best_incoherent(out.rows)) {
    const TraversalRow& row = out.rows[*best];
    out.best_config = row.describe;
    best_bvh = row.config;
    for (const RaySetRate& set : row.sets)
      if (set.name == "incoherent") out.best_ratio = set.ratio;
  }
  if (hooks.best) hooks.best(out);
  if (a.render) {
    out.render = render_run(a, scene, best_bvh);
    if (hooks.render) hooks.render(*out.render);
  }
  return out;
}

nlohmann::json traversal_scene_json(const TraversalScene& scene) {
  nlohmann::json out = {{"scene", scene.spec},
                        {"triangles", scene.triangles},
                        {"native_build_ms", scene.native_build_ms},
                        {"configs", nlohmann::json::array()}};
  for (const TraversalRow& row : scene.rows) {
    if (!row.refused.empty()) continue;
    nlohmann::json cj = build_stats_json(row.stats);
    cj["config"] = row.describe;
    for (const RaySetRate& set : row.sets)
      cj["ray_sets"][set.name] = {{"native_mrays", set.native_mrays},
                                  {"tuned_mrays", set.tuned_mrays},
                                  {"ratio", set.ratio}};
    out["configs"].push_back(cj);
  }
  out["best_incoherent"] = {{"config", scene.best_config}, {"ratio", scene.best_ratio}};
  if (scene.render) {
    const RenderLevelRun& run = *scene.render;
    const RenderVsNative& r = run.result;
    out["render"] = {{"size", size_text(run.options.width, run.options.height)},
                     {"spp", run.options.spp},
                     {"scheduler", run.scheduler},
                     {"min_repeats", run.options.repeats},
                     {"max_repeats", run.options.max_repeats},
                     {"rounds", r.native_ms.size()},
                     {"config", r.config},
                     {"source", run.source},
                     {"native_ms", r.native_ms},
                     {"chosen_ms", r.chosen_ms},
                     {"native_median_ms", r.native_median_ms},
                     {"chosen_median_ms", r.chosen_median_ms},
                     {"native_build_ms", r.native_build_ms},
                     {"chosen_build_ms", r.chosen_build_ms},
                     {"speedup_over_native", r.speedup()},
                     {"speedup_ci95", {r.speedup_low, r.speedup_high}},
                     {"ci_within_target", r.converged}};
  }
  return out;
}

}  // namespace tuneray
