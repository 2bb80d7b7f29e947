// The arithmetic of the quality ablation on hand-made runs: per-frame medians, RMSE at the
// common budget, the ratio matrix and its geometric means, and the JSON rows.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "bench/quality_bench.h"
#include "bench/quality_report.h"

namespace tuneray {
namespace {

FrameRun run(std::vector<double> time, std::vector<double> spp, std::vector<double> rmse,
             double mrays) {
  return {std::move(time), std::move(spp), std::move(rmse), mrays};
}

TEST(QualityArithmetic, RowIsTheMedianOfTheRepeatsFrameByFrame) {
  std::vector<FrameRun> runs = {run({100, 400}, {2, 8}, {0.2, 0.1}, 5),
                                run({120, 480}, {2, 6}, {0.4, 0.3}, 1),
                                run({90, 300}, {4, 10}, {0.3, 0.2}, 3)};
  QualityRow r = summarize_runs("x", runs, 200);
  EXPECT_EQ(r.name, "x");
  EXPECT_EQ(r.time_ms, (std::vector<double>{100, 400}));
  EXPECT_EQ(r.spp, (std::vector<double>{2, 8}));
  EXPECT_EQ(r.rmse, (std::vector<double>{0.3, 0.2}));
  EXPECT_EQ(r.rmse_repeats, (std::vector<double>{0.1, 0.3, 0.2}));
  // ms per spp of each run: 50, 80, 30 -> 50; Mrays/s 5, 1, 3 -> 3.
  EXPECT_DOUBLE_EQ(r.ms_per_spp, 50);
  EXPECT_DOUBLE_EQ(r.mrays_per_s, 3);
  // Time over budget: 2, 2.4, 1.5 -> 2.
  EXPECT_DOUBLE_EQ(r.time_over_budget, 2);
  // RMSE at 200 ms, per run: run 1 halfway in log time between 100 and 400 ms, so halfway in
  // log RMSE: 0.2 * sqrt(0.5); run 2 at 200 < 120..480 likewise; run 3 between 90 and 300.
  double run1 = 0.2 * std::sqrt(0.5);
  double w2 = std::log(200.0 / 120) / std::log(4.0);
  double run2 = std::exp(std::log(0.4) + w2 * std::log(0.3 / 0.4));
  double w3 = std::log(200.0 / 90) / std::log(300.0 / 90);
  double run3 = std::exp(std::log(0.3) + w3 * std::log(0.2 / 0.3));
  std::vector<double> at = {run1, run2, run3};
  std::sort(at.begin(), at.end());
  EXPECT_NEAR(r.rmse_at_budget, at[1], 1e-15);
}

TEST(QualityArithmetic, EvenRepeatsTakeTheMeanOfTheMiddleTwo) {
  QualityRow r = summarize_runs("x", {run({10}, {1}, {0.5}, 2), run({30}, {3}, {0.1}, 4)}, 10);
  EXPECT_DOUBLE_EQ(r.time_ms[0], 20);
  EXPECT_DOUBLE_EQ(r.rmse[0], 0.3);
  EXPECT_DOUBLE_EQ(r.mrays_per_s, 3);
  // At 10 ms: run 1 exactly 0.5; run 2 extrapolated back with slope -1/2: 0.1 * sqrt(3).
  EXPECT_NEAR(r.rmse_at_budget, (0.5 + 0.1 * std::sqrt(3.0)) / 2, 1e-15);
}

QualityRow row(const std::string& name, double rmse_at_budget, double ms_per_spp) {
  QualityRow r;
  r.name = name;
  r.rmse_at_budget = rmse_at_budget;
  r.ms_per_spp = ms_per_spp;
  return r;
}

TEST(QualityArithmetic, RatioMatrixAgainstTheBaselineWithGeometricMeans) {
  QualityScene a, b, c;
  a.name = "a";
  a.rows = {row("baseline", 0.4, 2), row("wavefront", 0.2, 1), row("clamp", 0.1, 4)};
  b.name = "b";
  b.rows = {row("baseline", 0.2, 4), row("wavefront", 0.025, 1), row("adaptive", 0.3, 8)};
  c.name = "c";  // no baseline: no ratios
  c.rows = {row("wavefront", 0.1, 1)};
  RatioMatrix m = ratio_matrix({a, b, c}, &QualityRow::rmse_at_budget);
  ASSERT_EQ(m.columns, (std::vector<std::string>{"wavefront", "clamp", "adaptive"}));
  ASSERT_EQ(m.rows.size(), 3u);
  EXPECT_EQ(m.rows[0].scene, "a");
  EXPECT_EQ(m.rows[0].cells[0], 0.5);
  EXPECT_EQ(m.rows[0].cells[1], 0.25);
  EXPECT_FALSE(m.rows[0].cells[2].has_value());
  EXPECT_EQ(m.rows[1].cells[0], 0.125);
  EXPECT_FALSE(m.rows[1].cells[1].has_value());
  EXPECT_DOUBLE_EQ(*m.rows[1].cells[2], 1.5);
  for (const auto& cell : m.rows[2].cells) EXPECT_FALSE(cell.has_value());
  ASSERT_EQ(m.geo_means.size(), 3u);
  EXPECT_DOUBLE_EQ(*m.geo_means[0], 0.25);  // sqrt(0.5 x 0.125)
  EXPECT_DOUBLE_EQ(*m.geo_means[1], 0.25);
  EXPECT_DOUBLE_EQ(*m.geo_means[2], 1.5);

  RatioMatrix t = ratio_matrix({a, b}, &QualityRow::ms_per_spp);
  EXPECT_EQ(t.rows[0].cells[0], 0.5);
  EXPECT_EQ(t.rows[1].cells[0], 0.25);
  EXPECT_DOUBLE_EQ(*t.geo_means[0], std::sqrt(0.125));
}

TEST(QualityArithmetic, NoColumnsWithoutRowsOtherThanTheBaseline) {
  QualityScene a;
  a.rows = {row("baseline", 0.4, 2)};
  RatioMatrix m = ratio_matrix({a}, &QualityRow::rmse_at_budget);
  EXPECT_TRUE(m.columns.empty());
  EXPECT_TRUE(m.geo_means.empty());
}

TEST(QualityArithmetic, JsonRowsCarryTheRatioToTheBaseline) {
  QualityScene s;
  s.spec = "cornell";
  s.name = "cornell box";
  s.truth_spp = 64;
  QualityRow before = row("wavefront", 0.3, 1);  // ran before the baseline: no ratio
  QualityRow base = row("baseline", 0.4, 2);
  base.baseline_rmse = 0.4;
  QualityRow after = row("clamp", 0.1, 4);
  after.baseline_rmse = 0.4;
  after.bias = 0.01;
  // Against the exact image (run_quality_scene fills these in from the truth's noise).
  after.exact_rmse_at_budget = 0.05;
  after.exact_baseline_rmse = 0.2;
  s.truth_noise_rmse = 0.3;
  s.rows = {before, base, after};
  s.sweep = {{"tile", 16, 2.5}};
  nlohmann::ordered_json j = quality_scene_json(s);
  EXPECT_EQ(j["scene"], "cornell");
  EXPECT_EQ(j["name"], "cornell box");
  EXPECT_EQ(j["truth_spp"], 64);
  ASSERT_EQ(j["configs"].size(), 3u);
  EXPECT_EQ(j["configs"][0]["rmse_vs_baseline"], 0.0);
  EXPECT_EQ(j["configs"][1]["rmse_vs_baseline"], 1.0);
  EXPECT_EQ(j["configs"][2]["rmse_vs_baseline"], 0.25);
  EXPECT_EQ(j["configs"][2]["bias"], 0.01);
  EXPECT_EQ(j["configs"][2]["exact_rmse_vs_baseline"], 0.25);
  EXPECT_EQ(j["configs"][1]["exact_rmse_vs_baseline"], 0.0);  // not filled in
  EXPECT_EQ(j["truth_noise_rmse"], 0.3);
  EXPECT_EQ(j["sweep"][0]["mode"], "tile");
  EXPECT_EQ(j["sweep"][0]["size"], 16);
  std::vector<std::string> keys;
  for (auto& [key, value] : j["configs"][0].items()) keys.push_back(key);
  EXPECT_EQ(keys, (std::vector<std::string>{
                      "config", "ms_per_spp", "intersect_ms_per_spp", "shading_ms_per_spp",
                      "shadow_ms_per_spp", "mrays_per_s", "spp", "time_ms", "rmse", "rmse_repeats",
                      "rmse_at_budget", "time_over_budget", "rmse_vs_baseline",
                      "exact_rmse_at_budget", "exact_rmse_vs_baseline", "bias"}));
}

TEST(QualityArithmetic, PlotDataHasOneBlockPerRow) {
  QualityScene a;
  a.name = "a";
  a.rows = {row("baseline", 1, 1), row("clamp", 1, 1)};
  a.rows[0].time_ms = {1, 2};
  a.rows[0].rmse = {0.5, 0.25};
  std::ostringstream data;
  append_plot_data(data, a);
  EXPECT_EQ(data.str(), "\"a baseline\"\n1 0.5\n2 0.25\n\n\n\"a clamp\"\n\n\n");
}

}  // namespace
}  // namespace tuneray
