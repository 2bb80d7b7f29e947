// The side-by-side build-time comparison: native at the tuned configuration's quality, one timing
// per repeat and side, medians and their ratio.
#include <gtest/gtest.h>

#include <algorithm>

#include "accel/build_bench.h"
#include "test_geometry.h"

namespace tuneray::test {
namespace {

TEST(BuildBench, NativeQualityFollowsTheConfiguration) {
  EXPECT_EQ(native_options_for(parse_bvh_config("quality=low")).quality, RTC_BUILD_QUALITY_LOW);
  EXPECT_EQ(native_options_for(parse_bvh_config("quality=medium")).quality,
            RTC_BUILD_QUALITY_MEDIUM);
  EXPECT_EQ(native_options_for(parse_bvh_config("quality=high,branching=8")).quality,
            RTC_BUILD_QUALITY_HIGH);
}

TEST(BuildBench, InterleavedMediansAndRatio) {
  Mesh mesh = make_soup(5000, 3);
  TunedBvhAccel tuned(parse_bvh_config("quality=high,branching=4"));
  EmbreeNativeAccel native;
  BuildComparison c = compare_build_times(mesh.view(), tuned, native, 3);
  EXPECT_EQ(native.options().quality, RTC_BUILD_QUALITY_HIGH);
  ASSERT_EQ(c.tuned_ms.size(), 3u);
  ASSERT_EQ(c.native_ms.size(), 3u);
  for (const auto* runs : {&c.tuned_ms, &c.native_ms}) {
    std::vector<double> v = *runs;
    std::sort(v.begin(), v.end());
    EXPECT_GT(v[0], 0.0);
    const double median = runs == &c.tuned_ms ? c.tuned_median_ms : c.native_median_ms;
    EXPECT_EQ(median, v[1]);
  }
  EXPECT_DOUBLE_EQ(c.ratio, c.tuned_median_ms / c.native_median_ms);
  EXPECT_EQ(c.tuned.build_ms, c.tuned_median_ms);
  EXPECT_GT(c.tuned.leaf_count, 0u);
  // Both accelerators hold their last build.
  Hit h;
  EXPECT_TRUE(tuned.intersect(Ray{Vec3f(0.5f, 0.5f, -1), 0, Vec3f(0, 0, 1), kInf}, h) ==
              native.intersect(Ray{Vec3f(0.5f, 0.5f, -1), 0, Vec3f(0, 0, 1), kInf}, h));
}

}  // namespace
}  // namespace tuneray::test
