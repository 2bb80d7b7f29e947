// The quality ablation on the built-in Cornell box at a tiny size, through the library: which
// rows come back in which order, how they relate to each other and to their repeats, the
// hooks' order, and the truth cache on a second run.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "bench/quality_bench.h"
#include "bench/quality_report.h"
#include "common/temp_dir.h"

namespace tuneray {
namespace {

// Far more than the baseline reaches in its three 2 ms frames (about 50 spp at this size on 2
// cores): with 32, as this test had, a truth as noisy as the rows let a row's error against it
// fall below the truth's own noise estimate in about one run of six.
constexpr int kTruthSpp = 512;

QualityBenchOptions tiny(const testing::TempDir& dir) {
  QualityBenchOptions o;
  o.width = 16;
  o.height = 12;
  o.frame_ms = 2;
  o.frames = 3;
  o.repeats = 2;
  o.truth_dir = dir.file("truth");
  o.truth_spp = kTruthSpp;
  o.bias_spp = 2;
  o.only = {"baseline", "wavefront", "clamp", "bluenoise"};
  return o;
}

TEST(QualityAblation, RowsRelateToTheirRepeatsAndTheBaseline) {
  testing::TempDir dir;
  QualityBenchOptions o = tiny(dir);
  std::vector<std::string> events;
  QualityHooks hooks;
  int truth_spp = 0;
  hooks.loaded = [&](const QualityScene& s) {
    events.push_back("loaded");
    EXPECT_GT(s.triangles, 0u);
  };
  hooks.truth_progress = [&](int spp, double estimate) {
    truth_spp += spp;
    EXPECT_LT(estimate, 0) << "no error target: no estimate";
  };
  hooks.ready = [&](const QualityScene& s) {
    events.push_back("ready");
    EXPECT_EQ(s.frame_ms, 2);
  };
  hooks.repeat_done = [&](const QualityScene&, int rep) {
    events.push_back("repeat " + std::to_string(rep));
  };
  hooks.row = [&](const QualityRow& r) { events.push_back(r.name); };
  QualityScene s = run_quality_scene(o, "cornell", hooks);

  EXPECT_EQ(events, (std::vector<std::string>{"loaded", "ready", "repeat 0", "repeat 1", "baseline",
                                              "wavefront", "bluenoise", "clamp"}));
  EXPECT_EQ(truth_spp, kTruthSpp);
  EXPECT_TRUE(s.truth.rendered);
  EXPECT_EQ(s.truth.spp, kTruthSpp);
  EXPECT_EQ(s.truth_spp, kTruthSpp);
  EXPECT_TRUE(std::filesystem::exists(s.truth_path));
  EXPECT_GT(s.truth_noise_rmse, 0);  // a finite truth is noisy, and its halves say so
  EXPECT_LT(s.truth_noise_rmse, s.rows.at(0).rmse_at_budget);
  ASSERT_EQ(s.rows.size(), 4u);
  const double base = s.rows[0].rmse_at_budget;
  EXPECT_GT(base, 0);
  for (const QualityRow& r : s.rows) {
    SCOPED_TRACE(r.name);
    ASSERT_EQ(r.rmse.size(), 3u);
    ASSERT_EQ(r.time_ms.size(), 3u);
    ASSERT_EQ(r.spp.size(), 3u);
    ASSERT_EQ(r.rmse_repeats.size(), 2u);
    // The last frame's median over the two repeats is the mean of their final RMSEs.
    EXPECT_DOUBLE_EQ(r.rmse.back(), (r.rmse_repeats[0] + r.rmse_repeats[1]) / 2);
    for (size_t f = 1; f < 3; ++f) EXPECT_GT(r.time_ms[f], r.time_ms[f - 1]);
    EXPECT_EQ(r.baseline_rmse, base);
    EXPECT_EQ(r.rmse_vs_baseline(), r.rmse_at_budget / base);
    // The truth's own noise comes off in quadrature, the same for every row.
    EXPECT_NEAR(
        r.exact_rmse_at_budget * r.exact_rmse_at_budget + s.truth_noise_rmse * s.truth_noise_rmse,
        std::max(r.rmse_at_budget * r.rmse_at_budget, s.truth_noise_rmse * s.truth_noise_rmse),
        1e-12);
    EXPECT_EQ(r.exact_baseline_rmse, s.rows[0].exact_rmse_at_budget);
    EXPECT_GT(r.ms_per_spp, 0);
    EXPECT_GE(r.intersect, 0);
  }
  EXPECT_EQ(s.rows[0].rmse_vs_baseline(), 1.0);
  // Only the clamp is biased; the unbiased rows have no bias estimate at all.
  EXPECT_EQ(s.rows[0].bias, 0.0);
  EXPECT_EQ(s.rows[1].bias, 0.0);
  EXPECT_EQ(s.rows[2].bias, 0.0);
  EXPECT_GE(s.rows[3].bias, 0.0);

  RatioMatrix m = ratio_matrix({s}, &QualityRow::rmse_at_budget);
  ASSERT_EQ(m.columns, (std::vector<std::string>{"wavefront", "bluenoise", "clamp"}));
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(m.rows[0].cells[i], s.rows[i + 1].rmse_vs_baseline());
    EXPECT_DOUBLE_EQ(*m.geo_means[i], s.rows[i + 1].rmse_vs_baseline());
  }

  // Same key: the truth now comes from the cache, and the report says so.
  QualityBenchOptions again = o;
  again.only = {"baseline"};
  again.repeats = 1;
  QualityScene cached = run_quality_scene(again, "cornell");
  EXPECT_FALSE(cached.truth.rendered);
  EXPECT_EQ(cached.truth_path, s.truth_path);
  EXPECT_EQ(cached.truth_spp, kTruthSpp);
  ASSERT_EQ(cached.rows.size(), 1u);
  EXPECT_EQ(cached.rows[0].rmse_repeats.size(), 1u);
  EXPECT_EQ(cached.rows[0].rmse.back(), cached.rows[0].rmse_repeats[0]);
}

TEST(QualityAblation, EveryConfigurationByDefaultAndTheSweep) {
  testing::TempDir dir;
  QualityBenchOptions o = tiny(dir);
  o.only.clear();
  o.repeats = 1;
  o.frames = 1;
  o.sweep = true;
  o.target_spp = 1;  // the budget comes from the baseline's measured speed
  QualityScene s = run_quality_scene(o, "cornell");
  std::vector<std::string> names;
  for (const QualityRow& r : s.rows) names.push_back(r.name);
  EXPECT_EQ(names, quality_configurations());
  EXPECT_GT(s.frame_ms, 0);
  ASSERT_EQ(s.sweep.size(), 9u);
  std::vector<int> tiles, batches;
  for (const SweepPoint& p : s.sweep) (p.mode == "tile" ? tiles : batches).push_back(p.size);
  EXPECT_EQ(tiles, (std::vector<int>{8, 16, 32, 64}));
  EXPECT_EQ(batches, (std::vector<int>{256, 1024, 4096, 16384, 65536}));
  nlohmann::ordered_json j = quality_scene_json(s);
  EXPECT_EQ(j["configs"].size(), quality_configurations().size());
  EXPECT_EQ(j["sweep"].size(), 9u);
}

TEST(QualityAblation, UnknownConfigurationsAreRefused) {
  EXPECT_NO_THROW(check_quality_configurations({"baseline", "all"}));
  EXPECT_THROW(check_quality_configurations({"baseline", "fast"}), std::invalid_argument);
}

}  // namespace
}  // namespace tuneray
