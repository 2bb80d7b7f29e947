// `bench render` measures the backend it is given (native by default, as `render`), says which in
// its results, refuses an unknown backend or parameter before rendering, and times Embree's
// pathtracer interleaved with our passes.
#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>
#include <vector>

#include "bench/render_bench.h"
#include "scene/load.h"

namespace tuneray {
namespace {

RenderBenchOptions tiny_options() {
  RenderBenchOptions o;
  o.width = 32;
  o.height = 18;
  o.spp = 1;
  o.repeats = 2;
  o.max_bounces = 2;
  o.embree_reference = false;
  return o;
}

TEST(RenderBench, MeasuresTheBackendItIsGiven) {
  const Scene scene = load_scene("cornell");
  RenderBenchOptions o = tiny_options();
  EXPECT_EQ(o.accel, "native");  // the render command's default
  const RenderSpeed native = measure_render_speed("cornell", scene, o, o.spp);
  EXPECT_EQ(native.accel.rfind("native ", 0), 0u) << native.accel;
  o.accel = "tuned";
  o.bvh = "branching=4,max_leaf=8";
  const RenderSpeed tuned = measure_render_speed("cornell", scene, o, o.spp);
  EXPECT_EQ(tuned.accel.rfind("tuned ", 0), 0u) << tuned.accel;
  EXPECT_NE(tuned.accel.find("branching=4"), std::string::npos) << tuned.accel;
  EXPECT_NE(tuned.accel.find("max_leaf=8"), std::string::npos) << tuned.accel;
  for (const RenderSpeed& r : {native, tuned}) {
    EXPECT_EQ(r.scene, "cornell");
    EXPECT_EQ(r.triangles, scene.triangles.size());
    EXPECT_GT(r.ms_per_spp, 0.0);
    EXPECT_GT(r.mrays, 0.0);
  }
}

TEST(RenderBench, RefusesAnUnknownBackendOrParameter) {
  const Scene scene = load_scene("cornell");
  RenderBenchOptions o = tiny_options();
  o.accel = "optix";
  EXPECT_THROW(measure_render_speed("cornell", scene, o, o.spp), std::invalid_argument);
  o.accel = "tuned";
  o.bvh = "branching=3";
  EXPECT_THROW(measure_render_speed("cornell", scene, o, o.spp), std::invalid_argument);
  o.bvh = "leafsize=4";
  EXPECT_THROW(measure_render_speed("cornell", scene, o, o.spp), std::invalid_argument);
}

TEST(RenderBench, TheEmbreeRatioIsTheMedianOfPerRepeatRatios) {
  EmbreeComparison c;
  c.embree_frame_ms = {100, 200, 300, 90};
  c.our_frame_ms = {50, 100, 100, 90};
  EXPECT_EQ(c.speed_ratios(), (std::vector<double>{2, 2, 3, 1}));
  EXPECT_DOUBLE_EQ(c.speed_ratio(), 2.0);
  // A ratio of medians would be 150 / 95 = 1.58: a slow phase of the host that hit one side of
  // one repeat would move it, the median of paired ratios not.
}

TEST(RenderBench, InterleavesTheEmbreeComparisonRepeatByRepeat) {
  RenderBenchOptions o = tiny_options();
  o.repeats = 3;
  const EmbreeComparison c = compare_with_embree(o);
  if (!c.ok) GTEST_SKIP() << "Embree's pathtracer cannot run: " << c.error;
  ASSERT_EQ(c.our_frame_ms.size(), 3u);
  ASSERT_EQ(c.embree_frame_ms.size(), 3u);
  const std::vector<double> ratios = c.speed_ratios();
  ASSERT_EQ(ratios.size(), 3u);
  for (size_t r = 0; r < 3; ++r) {
    EXPECT_GT(c.our_frame_ms[r], 0.0);
    EXPECT_GT(c.embree_frame_ms[r], 0.0);
    EXPECT_DOUBLE_EQ(ratios[r], c.embree_frame_ms[r] / c.our_frame_ms[r]);
  }
  std::vector<double> sorted = ratios;
  std::sort(sorted.begin(), sorted.end());
  EXPECT_DOUBLE_EQ(c.speed_ratio(), sorted[1]);
  EXPECT_EQ(c.our_accel.rfind("native ", 0), 0u) << c.our_accel;
}

}  // namespace
}  // namespace tuneray
