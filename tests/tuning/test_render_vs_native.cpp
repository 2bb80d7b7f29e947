// The render-level comparison of `bench traversal`: interleaved repeats of native and the
// chosen configuration on the same frame, medians and their ratio; the database's best found
// under tune's key.
#include <gtest/gtest.h>

#include "tuning_fixtures.h"

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

TEST(RenderVsNative, MediansOfInterleavedRepeatsAndTheirRatio) {
  Scene scene = load_scene("cornell");
  BvhConfig wide;
  wide.branching = 8;
  RenderVsNative r = render_vs_native(scene, scene.cameras[0], AccelChoice::tuned(wide), tiny());
  EXPECT_EQ(r.config, AccelChoice::tuned(wide).to_string());
  ASSERT_EQ(r.native_ms.size(), 3u);
  ASSERT_EQ(r.chosen_ms.size(), 3u);
  for (double ms : r.native_ms) EXPECT_GT(ms, 0.0);
  for (double ms : r.chosen_ms) EXPECT_GT(ms, 0.0);
  EXPECT_DOUBLE_EQ(r.native_median_ms, median(r.native_ms));
  EXPECT_DOUBLE_EQ(r.chosen_median_ms, median(r.chosen_ms));
  EXPECT_DOUBLE_EQ(r.speedup(), r.native_median_ms / r.chosen_median_ms);
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
  none.repeats = 0;
  EXPECT_THROW(render_vs_native(scene, scene.cameras[0], AccelChoice::native(), none),
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
