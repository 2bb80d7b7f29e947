#include "tuner/replayer.h"

#include <gtest/gtest.h>

#include "synthetic_problem.h"
#include "temp_path.h"

namespace tuneray::tuner {
namespace {

using testing::kernel_cost;
using testing::kernel_schema;
using testing::kernel_space;

TunerOptions replay_options(double epsilon) {
  TunerOptions options;
  options.epsilon = epsilon;
  options.search.max_iterations = 30;
  options.search.max_repeats = 1;
  return options;
}

TEST(Replayer, SameStrategySameRunAndAllCostsFromTheRecording) {
  testing::TempPath path("replay.db");
  const std::vector<State> sequence = {{100}, {500}, {900}, {100}};
  TunerOptions recording_options = replay_options(1.0);
  recording_options.db_path = path.str();
  recording_options.hardware = "test";
  std::vector<std::string> recorded_configs;
  {
    HybridTuner tuner(kernel_space(), kernel_schema(), recording_options);
    for (const State& state : sequence) {
      for (int i = 0; i < 60; ++i) {
        const Config c = tuner.suggest(state);
        recorded_configs.push_back(c.to_string());
        tuner.report(c, kernel_cost(state, c));
      }
    }
  }
  Replayer replayer;
  {
    TuningDb db(path.str());
    replayer.add_recorded(db, *db.find_signature("default", "test"), kernel_space());
  }
  // The recorded strategy (same seed, no database) replays exactly, with no unrecorded cost.
  HybridTuner first(kernel_space(), kernel_schema(), replay_options(1.0));
  const ReplayResult a = replayer.run(first, sequence, 60);
  EXPECT_EQ(a.unrecorded, 0u);
  ASSERT_EQ(a.steps.size(), recorded_configs.size());
  for (size_t i = 0; i < a.steps.size(); ++i) {
    EXPECT_EQ(a.steps[i].config.to_string(), recorded_configs[i]) << "step " << i;
  }
  HybridTuner second(kernel_space(), kernel_schema(), replay_options(1.0));
  const ReplayResult b = replayer.run(second, sequence, 60);
  EXPECT_EQ(b.total_cost, a.total_cost);
}

TEST(Replayer, UnrecordedConfigurationsUseTheFallbackOrFail) {
  Replayer replayer;
  const Space space = kernel_space();
  replayer.add(State{100}, space.default_config(), 2.0);
  replayer.add(State{100}, space.default_config(), 4.0);
  HybridTuner tuner(kernel_space(), kernel_schema(), replay_options(1.0));
  const ReplayResult without = replayer.run(tuner, {{100}}, 5);
  EXPECT_EQ(without.steps[0].cost, 2.0);  // the default is measured first
  EXPECT_TRUE(without.steps[0].recorded);
  EXPECT_GT(without.unrecorded, 0u);
  for (const auto& step : without.steps) {
    if (!step.recorded) {
      EXPECT_TRUE(std::isinf(step.cost));
    }
  }
  replayer.set_fallback([](const State& s, const Config& c) { return kernel_cost(s, c); });
  HybridTuner other(kernel_space(), kernel_schema(), replay_options(1.0));
  const ReplayResult with = replayer.run(other, {{100}}, 5);
  for (const auto& step : with.steps) EXPECT_TRUE(std::isfinite(step.cost));
}

}  // namespace
}  // namespace tuneray::tuner
