// The traversal and build matrices on the built-in Cornell box with few rays, through the
// library: the rows the sweep lists, the rates' arithmetic, the best row, the render-level run
// and the JSON, never the timings themselves.
#include <gtest/gtest.h>

#include <algorithm>

#include "bench/accel_bench.h"
#include "tuning/stats.h"

namespace tuneray {
namespace {

TEST(AccelMatrix, RateIsRaysOverTheMedianSeconds) {
  RaySetRate r = ray_set_rate("primary", 3000000, {3.0, 1.0, 2.0}, {0.5, 1.5, 1.0, 0.75});
  EXPECT_EQ(r.name, "primary");
  EXPECT_DOUBLE_EQ(r.native_mrays, 1.5);         // 3e6 rays / 2 s
  EXPECT_DOUBLE_EQ(r.tuned_mrays, 3.0 / 0.875);  // median of four: (0.75 + 1.0) / 2
  EXPECT_DOUBLE_EQ(r.ratio, r.tuned_mrays / r.native_mrays);
}

TraversalRow row_with(double incoherent_ratio) {
  TraversalRow r;
  r.sets = {{"primary", 1, 1, 9.0}, {"incoherent", 1, 1, incoherent_ratio}, {"shadow", 1, 1, 9.0}};
  return r;
}

TEST(AccelMatrix, BestRowIsTheFirstWithTheHighestIncoherentRatio) {
  EXPECT_EQ(best_incoherent({row_with(0.8), row_with(1.2), row_with(1.2), row_with(0.9)}), 1u);
  TraversalRow refused;
  refused.refused = "too deep";
  EXPECT_EQ(best_incoherent({refused, row_with(0.5)}), 1u);
  EXPECT_FALSE(best_incoherent({refused}).has_value());
  EXPECT_FALSE(best_incoherent({row_with(0.0)}).has_value());
}

TEST(AccelMatrix, SweepsListTheirConfigurationsAfterTheGivenOne) {
  AccelBenchOptions o;
  o.bvh = "branching=4";
  std::vector<std::string> t = traversal_configs(o);
  ASSERT_EQ(t.size(), 12u);
  EXPECT_EQ(t[0], parse_bvh_config("branching=4").to_string());
  EXPECT_EQ(t[1], "branching=4,max_leaf=1");
  EXPECT_EQ(t.back(), "branching=8,sah_block_size=4,max_leaf=8,compact=1");
  std::vector<std::string> b = build_configs(o);
  ASSERT_EQ(b.size(), 12u);
  EXPECT_EQ(b[1], "quality=low,branching=2");
  o.sweep = false;
  EXPECT_EQ(traversal_configs(o).size(), 1u);
  EXPECT_EQ(build_configs(o).size(), 1u);
}

AccelBenchOptions tiny() {
  AccelBenchOptions o;
  o.rays = 2000;
  o.repeats = 3;
  o.width = 16;
  o.height = 12;
  return o;
}

TEST(AccelMatrix, TraversalOnCornell) {
  AccelBenchOptions o = tiny();
  o.render = false;
  std::vector<std::string> order;
  TraversalHooks hooks;
  hooks.start = [&](const TraversalScene& s) {
    order.push_back("start");
    EXPECT_EQ(s.ray_counts.size(), 3u);
  };
  hooks.row = [&](const TraversalRow&) { order.push_back("row"); };
  hooks.best = [&](const TraversalScene&) { order.push_back("best"); };
  hooks.render = [&](const RenderLevelRun&) { order.push_back("render"); };
  TraversalScene s = run_traversal_scene(o, "cornell", hooks);

  std::vector<std::string> configs = traversal_configs(o);
  std::vector<std::string> expected = {"start"};
  expected.insert(expected.end(), configs.size(), "row");
  expected.push_back("best");
  EXPECT_EQ(order, expected);
  EXPECT_EQ(s.spec, "cornell");
  EXPECT_GT(s.triangles, 0u);
  // Primary rays fill whole 8x8 tiles; bounce rays are exactly the count asked for.
  EXPECT_EQ(s.ray_counts[0] % 64, 0u);
  EXPECT_EQ(s.ray_counts[1], 2000u);
  EXPECT_LE(s.ray_counts[2], 2000u);
  ASSERT_EQ(s.rows.size(), configs.size());
  size_t built = 0;
  for (size_t i = 0; i < s.rows.size(); ++i) {
    const TraversalRow& r = s.rows[i];
    SCOPED_TRACE(r.text);
    EXPECT_EQ(r.text, configs[i]);
    if (!r.refused.empty()) continue;
    ++built;
    ASSERT_EQ(r.sets.size(), 3u);
    EXPECT_EQ(r.sets[0].name, "primary");
    EXPECT_EQ(r.sets[1].name, "incoherent");
    EXPECT_EQ(r.sets[2].name, "shadow");
    for (const RaySetRate& set : r.sets) {
      EXPECT_GT(set.native_mrays, 0);
      EXPECT_EQ(set.ratio, set.tuned_mrays / set.native_mrays);
    }
    EXPECT_GT(r.stats.node_count, 0u);
  }
  std::optional<size_t> best = best_incoherent(s.rows);
  ASSERT_TRUE(best.has_value());
  EXPECT_EQ(s.best_config, s.rows[*best].describe);
  EXPECT_EQ(s.best_ratio, s.rows[*best].sets[1].ratio);
  for (const TraversalRow& r : s.rows) {
    if (r.refused.empty()) {
      EXPECT_LE(r.sets[1].ratio, s.best_ratio);
    }
  }
  EXPECT_FALSE(s.render.has_value());

  nlohmann::json j = traversal_scene_json(s);
  EXPECT_EQ(j["scene"], "cornell");
  EXPECT_EQ(j["configs"].size(), built);
  EXPECT_EQ(j["configs"][0]["ray_sets"]["incoherent"]["ratio"], s.rows[0].sets[1].ratio);
  EXPECT_EQ(j["best_incoherent"]["config"], s.best_config);
  EXPECT_EQ(j["best_incoherent"]["ratio"], s.best_ratio);
  EXPECT_FALSE(j.contains("render"));
}

TEST(AccelMatrix, TraversalEndsWithTheRenderLevelRun) {
  AccelBenchOptions o = tiny();
  o.sweep = false;
  o.repeats = 2;
  o.spp = 1;
  o.scheduler = "tile";
  TraversalScene s = run_traversal_scene(o, "cornell");
  ASSERT_TRUE(s.render.has_value());
  const RenderLevelRun& run = *s.render;
  EXPECT_EQ(run.options.width, 16);
  EXPECT_EQ(run.options.height, 12);
  EXPECT_FALSE(run.options.wavefront);
  EXPECT_EQ(run.source, "best of the table on incoherent rays");
  // Paired rounds from --repeats until the interval is within ±3 %, at most 30.
  const size_t rounds = run.result.native_ms.size();
  ASSERT_GE(rounds, 2u);
  ASSERT_LE(rounds, 30u);
  ASSERT_EQ(run.result.chosen_ms.size(), rounds);
  // The median's interval need not be symmetric: both sides count.
  const double half_width = std::max(run.result.speedup_high / run.result.speedup(),
                                     run.result.speedup() / run.result.speedup_low) -
                            1;
  EXPECT_EQ(run.result.converged, rounds < 30u || half_width <= 0.03);
  EXPECT_DOUBLE_EQ(run.result.native_median_ms, median(run.result.native_ms));
  EXPECT_DOUBLE_EQ(run.result.chosen_median_ms, median(run.result.chosen_ms));
  nlohmann::json j = traversal_scene_json(s);
  EXPECT_EQ(j["render"]["size"], "16x12");
  EXPECT_EQ(j["render"]["scheduler"], "tile");
  EXPECT_EQ(j["render"]["min_repeats"], 2);
  EXPECT_EQ(j["render"]["max_repeats"], 30);
  EXPECT_EQ(j["render"]["rounds"], rounds);
  EXPECT_EQ(j["render"]["speedup_over_native"], run.result.speedup());
  EXPECT_EQ(j["render"]["speedup_ci95"][0], run.result.speedup_low);
  EXPECT_EQ(j["render"]["speedup_ci95"][1], run.result.speedup_high);
}

TEST(AccelMatrix, BuildOnCornell) {
  AccelBenchOptions o = tiny();
  o.sweep = false;
  BuildScene s = run_build_scene(o, "cornell");
  EXPECT_EQ(s.spec, "cornell");
  ASSERT_EQ(s.rows.size(), 1u);
  const BuildRow& r = s.rows[0];
  ASSERT_TRUE(r.refused.empty()) << r.refused;
  ASSERT_EQ(r.tuned_ms.size(), 3u);
  ASSERT_EQ(r.native_ms.size(), 3u);
  EXPECT_DOUBLE_EQ(r.native_median_ms, median(r.native_ms));
  EXPECT_DOUBLE_EQ(r.stats.build_ms, median(r.tuned_ms));
  ASSERT_GT(r.native_median_ms, 0);
  EXPECT_DOUBLE_EQ(r.ratio, r.stats.build_ms / r.native_median_ms);
  EXPECT_GT(r.rss_kib, 0u);
  nlohmann::json j = build_scene_json(s);
  ASSERT_EQ(j["configs"].size(), 1u);
  EXPECT_EQ(j["configs"][0]["ratio"], r.ratio);
  EXPECT_EQ(j["configs"][0]["tuned_ms_runs"].size(), 3u);
}

}  // namespace
}  // namespace tuneray
