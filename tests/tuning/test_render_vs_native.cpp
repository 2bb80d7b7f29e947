// The render-level comparison of `bench traversal`: paired rounds of native and the chosen
// configuration on the same frame until the speedup's interval is tight or the cap; the
// database's best found under tune's key.
#include <gtest/gtest.h>

#include "tuning_fixtures.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "scene/load.h"
#include "tuner/temp_path.h"
#include "tuning/render_vs_native.h"
#include "tuning/stats.h"
#include "tuning/tune_session.h"

namespace tuneray {
namespace {

RenderVsNativeOptions tiny() {
  RenderVsNativeOptions o;
  o.width = 16;
  o.height = 12;
  o.repeats = 3;
  return o;
}

TEST(RenderVsNative, PairedRoundsUntilTheIntervalIsTightOrTheCap) {
  Scene scene = load_scene("cornell");
  BvhConfig wide;
  wide.branching = 8;
  RenderVsNativeOptions o = tiny();
  o.max_repeats = 6;
  RenderVsNative r = render_vs_native(scene, scene.cameras[0], AccelChoice::tuned(wide), o);
  EXPECT_EQ(r.config, AccelChoice::tuned(wide).to_string());
  ASSERT_EQ(r.native_ms.size(), r.chosen_ms.size());
  ASSERT_GE(r.native_ms.size(), 3u);
  ASSERT_LE(r.native_ms.size(), 6u);
  // The median's interval need not be symmetric: both sides count.
  const double half_width = std::max(r.speedup_high / r.speedup(), r.speedup() / r.speedup_low) - 1;
  EXPECT_EQ(r.converged, r.native_ms.size() < 6u || half_width <= 0.03);
  for (double ms : r.native_ms) EXPECT_GT(ms, 0.0);
  for (double ms : r.chosen_ms) EXPECT_GT(ms, 0.0);
  EXPECT_DOUBLE_EQ(r.native_median_ms, median(r.native_ms));
  EXPECT_DOUBLE_EQ(r.chosen_median_ms, median(r.chosen_ms));
  // The speedup is the median of the rounds' paired ratios (an even count: the geometric mean
  // of the two middle ones), inside its interval.
  std::vector<double> ratios;
  for (size_t k = 0; k < r.native_ms.size(); ++k) ratios.push_back(r.native_ms[k] / r.chosen_ms[k]);
  std::sort(ratios.begin(), ratios.end());
  const size_t n = ratios.size();
  const double middle = n % 2 ? ratios[n / 2] : std::sqrt(ratios[n / 2 - 1] * ratios[n / 2]);
  EXPECT_NEAR(r.speedup(), middle, 1e-12);
  EXPECT_LE(r.speedup_low, r.speedup());
  EXPECT_GE(r.speedup_high, r.speedup());
  EXPECT_GT(r.native_build_ms, 0.0);  // both trees were built, outside the timed frames
  EXPECT_GT(r.chosen_build_ms, 0.0);
}

TEST(RenderVsNative, RefusedConfigurationAndBadOptionsThrow) {
  Scene scene = load_scene("voxels");
  BvhConfig refused;
  refused.max_depth = 8;
  refused.max_leaf = 1;
  EXPECT_THROW(render_vs_native(scene, scene.cameras[0], AccelChoice::tuned(refused), tiny()),
               std::runtime_error);
  RenderVsNativeOptions none = tiny();
  none.repeats = 1;  // an interval needs two rounds
  EXPECT_THROW(render_vs_native(scene, scene.cameras[0], AccelChoice::native(), none),
               std::invalid_argument);
  RenderVsNativeOptions capped_below = tiny();
  capped_below.max_repeats = 2;
  EXPECT_THROW(render_vs_native(scene, scene.cameras[0], AccelChoice::native(), capped_below),
               std::invalid_argument);
}

TEST(RenderVsNative, BestInDatabaseUsesTunesKey) {
  const tuner::testing::TempPath db("render-vs-native.db");
  EXPECT_THROW(best_in_database(db.str(), load_scene("cornell"), CameraDesc{}, tiny()),
               std::runtime_error);  // no such file (and none is created)
  TuneOptions t = testing::tiny_tune_session(db.str());
  t.iterations = 3;
  t.baseline_repeats = 1;
  run_tune_session(t);

  Scene scene = load_scene("cornell");
  auto found = best_in_database(db.str(), scene, scene.cameras[0], tiny());
  ASSERT_TRUE(found.has_value());
  EXPECT_EQ(found->tuning_key, tuning_key(t));
  RenderVsNativeOptions other = tiny();
  other.spp = 2;  // tune never measured 2 spp
  EXPECT_FALSE(best_in_database(db.str(), scene, scene.cameras[0], other).has_value());
}

}  // namespace
}  // namespace tuneray
