// The build matrix: every configuration's build time against Embree's own build at the same
// quality, interleaved, with the tree's shape and the process's memory.
#include <unistd.h>

#include <fstream>

#include "accel/build_bench.h"
#include "accel/embree_native.h"
#include "accel/tuned_bvh.h"
#include "bench/accel_bench.h"
#include "bench/accel_json.h"
#include "scene/load.h"

namespace tuneray {

namespace {

size_t resident_kib() {
  std::ifstream statm("/proc/self/statm");
  size_t pages = 0, resident = 0;
  statm >> pages >> resident;
  return resident * static_cast<size_t>(sysconf(_SC_PAGESIZE)) / 1024;
}

}  // namespace

std::vector<std::string> build_configs(const AccelBenchOptions& options) {
  std::vector<std::string> configs = {parse_bvh_config(options.bvh).to_string()};
  if (!options.sweep) return configs;
  for (const char* q : {"low", "medium", "high"})
    for (int width : {2, 4, 8})
      configs.push_back(std::string("quality=") + q + ",branching=" + std::to_string(width));
  configs.push_back("branching=8,static=1");
  configs.push_back("branching=8,compact=1");
  return configs;
}

BuildScene run_build_scene(const AccelBenchOptions& a, const std::string& spec,
                           const BuildHooks& hooks) {
  const int repeats = std::max(1, a.repeats);
  Scene scene = load_scene(spec, LoadOptions{a.scenes_dir});
  GeometryView g{scene.positions.data(), scene.positions.size(), scene.triangles.data(),
                 scene.triangles.size()};
  BuildScene out{spec, g.triangle_count, {}};
  if (hooks.start) hooks.start(out);
  EmbreeNativeAccel native;
  TunedBvhAccel tuned;  // one accelerator rebuilt with every configuration, as the tuner does
  for (const std::string& text : build_configs(a)) {
    tuned.set_config(parse_bvh_config(text));
    BuildRow& row = out.rows.emplace_back();
    row.text = text;
    BuildComparison c;
    try {
      c = compare_build_times(g, tuned, native, repeats);
    } catch (const BuildError& e) {
      row.refused = e.what();
      if (hooks.row) hooks.row(row);
      continue;
    }
    row.stats = c.tuned;
    row.describe = tuned.describe();
    row.native_describe = native.describe();
    row.native_median_ms = c.native_median_ms;
    row.ratio = c.ratio;
    row.tuned_ms = c.tuned_ms;
    row.native_ms = c.native_ms;
    row.rss_kib = resident_kib();
    if (hooks.row) hooks.row(row);
  }
  return out;
}

nlohmann::json build_scene_json(const BuildScene& scene) {
  nlohmann::json out = {
      {"scene", scene.spec}, {"triangles", scene.triangles}, {"configs", nlohmann::json::array()}};
  for (const BuildRow& row : scene.rows) {
    if (!row.refused.empty()) continue;
    nlohmann::json cj = build_stats_json(row.stats);
    cj["config"] = row.describe;
    cj["native"] = row.native_describe;
    cj["native_build_ms"] = row.native_median_ms;
    cj["ratio"] = row.ratio;
    cj["tuned_ms_runs"] = row.tuned_ms;
    cj["native_ms_runs"] = row.native_ms;
    cj["rss_kib"] = row.rss_kib;
    out["configs"].push_back(cj);
  }
  return out;
}

}  // namespace tuneray
