// `bench render` measures the backend it is given (native by default, as `render`), says which in
// its results, and refuses an unknown backend or parameter before rendering.
#include <gtest/gtest.h>

#include <stdexcept>

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

}  // namespace
}  // namespace tuneray
