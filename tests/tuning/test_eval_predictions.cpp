// The study's predictors on made-up searches (eval_predictions.h): the nearest neighbour hands
// on its nearest training camera's converged configuration, and the RBF predictor learns from
// the training cameras' samples which configuration suits which state.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "tuning/bvh_space.h"
#include "tuning/eval_predictions.h"
#include "tuning/eval_search.h"
#include "tuning/tuner_state.h"

namespace tuneray {
namespace {

EvalProfile predictor_profile(int cameras) {
  EvalProfile p;
  p.cameras = cameras;
  p.repetitions = 15;
  p.train_fraction = 0.8;
  return p;
}

// A scene of `cameras` cameras, camera c at the normalised state `state_of(c, dims)`.
template <class StateOf>
EvalScene scene_of(int cameras, size_t dims, StateOf state_of) {
  EvalScene scene;
  scene.name = "made-up";
  for (int c = 0; c < cameras; ++c) scene.normalised.push_back(state_of(c, dims));
  return scene;
}

TEST(EvalPredictions, TheNearestNeighbourHandsOnTheNearestTrainingCamerasConfiguration) {
  const int cameras = 20;
  const EvalProfile p = predictor_profile(cameras);
  const tuner::Space space = eval_space(p);
  const tuner::IndicatorSchema schema = make_indicator_schema();
  // Camera c sits at (c / 20)^2 on every indicator (no two cameras equally far from a third);
  // its search converged to max_leaf = c + 4.
  auto position = [](int c) { return (c / 20.0) * (c / 20.0); };
  const EvalScene scene = scene_of(cameras, schema.size(), [&](int c, size_t dims) {
    return std::vector<double>(dims, position(c));
  });
  std::vector<CameraSearch> searches(cameras);
  for (int c = 0; c < cameras; ++c) {
    BvhConfig b;
    b.max_leaf = c + 4;
    CameraSearch& s = searches[static_cast<size_t>(c)];
    s.incumbent = to_tuner_config(space, AccelChoice::tuned(b));
    s.samples = {{s.incumbent.to_string(), 5.0}};
  }
  const std::vector<EvalPrediction> predictions =
      predict_held_out_cameras(p, scene, space, schema, searches);
  ASSERT_EQ(predictions.size(), static_cast<size_t>(p.repetitions * 4 * 2));
  int checked = 0;
  for (const EvalPrediction& pr : predictions) {
    if (pr.predictor != "nn") continue;
    // Which cameras trained in this repetition: every camera but the four held out.
    std::vector<bool> held_out(cameras, false);
    for (const EvalPrediction& other : predictions)
      if (other.repetition == pr.repetition) held_out[static_cast<size_t>(other.camera)] = true;
    int nearest = -1;
    for (int c = 0; c < cameras; ++c)
      if (!held_out[static_cast<size_t>(c)] &&
          (nearest < 0 || std::abs(position(c) - position(pr.camera)) <
                              std::abs(position(nearest) - position(pr.camera))))
        nearest = c;
    BvhConfig expected;
    expected.max_leaf = nearest + 4;
    EXPECT_EQ(pr.config, AccelChoice::tuned(expected).to_string()) << "camera " << pr.camera;
    ++checked;
  }
  EXPECT_EQ(checked, p.repetitions * 4);
}

// Half the cameras see one part of the scene, where configuration `a` is the faster by 10 %;
// the other half another part, where `b` is. Every search measured both; the RBF predictor
// must tell the held-out cameras of either part which one is theirs.
TEST(EvalPredictions, TheRbfPredictorLearnsWhichConfigurationSuitsWhichState) {
  const int cameras = 20;
  const EvalProfile p = predictor_profile(cameras);
  const tuner::Space space = eval_space(p);
  const tuner::IndicatorSchema schema = make_indicator_schema();
  auto part = [](int c) { return c % 2; };
  const EvalScene scene = scene_of(cameras, schema.size(), [&](int c, size_t dims) {
    return std::vector<double>(dims, part(c) == 0 ? 0.3 : 0.7);
  });
  BvhConfig a_bvh;
  a_bvh.branching = 8;
  a_bvh.sah_block_size = 4;
  a_bvh.min_leaf = 4;
  a_bvh.max_leaf = 28;
  const std::string a = to_tuner_config(space, AccelChoice::tuned(a_bvh)).to_string();
  const std::string b = to_tuner_config(space, AccelChoice::native()).to_string();
  std::vector<CameraSearch> searches(cameras);
  for (int c = 0; c < cameras; ++c) {
    CameraSearch& s = searches[static_cast<size_t>(c)];
    for (int k = 0; k < 40; ++k) {
      s.samples.emplace_back(a, part(c) == 0 ? 5.0 : 5.5);
      s.samples.emplace_back(b, part(c) == 0 ? 5.5 : 5.0);
    }
    s.incumbent = space.parse(part(c) == 0 ? a : b);
  }
  int right = 0, asked = 0;
  for (const EvalPrediction& pr : predict_held_out_cameras(p, scene, space, schema, searches)) {
    if (pr.predictor != "rbf") continue;
    ++asked;
    right += pr.config == to_accel_choice(space.parse(part(pr.camera) == 0 ? a : b)).to_string();
  }
  EXPECT_EQ(asked, p.repetitions * 4);
  EXPECT_EQ(right, asked);
}

}  // namespace
}  // namespace tuneray
