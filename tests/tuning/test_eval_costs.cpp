#include "tuning/eval_costs.h"

#include <gtest/gtest.h>

#include <set>

namespace tuneray {
namespace {

AccelChoice with_branching(int branching) {
  BvhConfig bvh;
  bvh.branching = branching;
  return AccelChoice::tuned(bvh);
}

TEST(SyntheticCosts, AreAPureFunctionOfSceneCameraAndConfiguration) {
  const AccelChoice choice = with_branching(4);
  const FrameCost a = synthetic_frame_cost("cornell", Objective::kTotal, 3, choice);
  const FrameCost b = synthetic_frame_cost("cornell", Objective::kTotal, 3, choice);
  EXPECT_TRUE(a.ok);
  EXPECT_EQ(a.render_ms, b.render_ms);
  EXPECT_EQ(a.build_ms, b.build_ms);
  EXPECT_GT(a.render_ms, 0.0);
  EXPECT_GT(a.build_ms, 0.0);
  // Every argument matters.
  EXPECT_NE(synthetic_frame_cost("voxels", Objective::kTotal, 3, choice).render_ms, a.render_ms);
  EXPECT_NE(synthetic_frame_cost("cornell", Objective::kTotal, 4, choice).render_ms, a.render_ms);
  EXPECT_NE(synthetic_frame_cost("cornell", Objective::kTotal, 3, with_branching(8)).render_ms,
            a.render_ms);
  EXPECT_NE(synthetic_frame_cost("cornell", Objective::kTotal, 3, AccelChoice::native()).render_ms,
            a.render_ms);
}

TEST(SyntheticCosts, RenderObjectiveBuildsOnceTotalCountsTheBuild) {
  const AccelChoice choice = with_branching(2);
  const FrameCost render = synthetic_frame_cost("cornell", Objective::kRender, 0, choice);
  const FrameCost total = synthetic_frame_cost("cornell", Objective::kTotal, 0, choice);
  EXPECT_EQ(render.build_ms, 0.0);
  EXPECT_EQ(render.render_ms, total.render_ms);
  EXPECT_EQ(total.cost_ms(Objective::kTotal), total.build_ms + total.render_ms);
}

TEST(SyntheticCosts, TheBestBranchingFactorMovesWithTheCamera) {
  std::set<int> best_per_camera;
  for (int camera = 0; camera < 12; ++camera) {
    int best = 0;
    double best_ms = 0;
    for (int branching : {2, 4, 8}) {
      const double ms =
          synthetic_frame_cost("cornell", Objective::kRender, camera, with_branching(branching))
              .render_ms;
      if (best == 0 || ms < best_ms) best = branching, best_ms = ms;
    }
    best_per_camera.insert(best);
  }
  EXPECT_GE(best_per_camera.size(), 2u);
}

TEST(SyntheticCosts, TheSourceGivesTheFunctionsCosts) {
  auto source = make_synthetic_costs("voxels", Objective::kTotal);
  const AccelChoice choice = with_branching(8);
  EXPECT_EQ(source->frame(choice, 5).build_ms,
            synthetic_frame_cost("voxels", Objective::kTotal, 5, choice).build_ms);
  EXPECT_EQ(source->frame(choice, 5).render_ms,
            synthetic_frame_cost("voxels", Objective::kTotal, 5, choice).render_ms);
}

}  // namespace
}  // namespace tuneray
