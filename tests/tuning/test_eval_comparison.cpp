// One camera's comparison: every configuration compared in one interleaved window, costs and
// ratios derived from its rounds, stored whole and read back exactly.
#include "tuning/eval_comparison.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <stdexcept>

#include "common/temp_dir.h"
#include "loaded_machine.h"
#include "tuning/comparison_log.h"
#include "tuning/stats.h"

namespace tuneray {
namespace {

using testing::LoadedMachine;
using testing::MachineLoad;

std::string tuned(int branching, int max_leaf) {
  BvhConfig bvh;
  bvh.branching = branching;
  bvh.max_leaf = max_leaf;
  return AccelChoice::tuned(bvh).to_string();
}

const std::string kDefault = AccelChoice::tuned(BvhConfig{}).to_string();
const std::string kNative = AccelChoice::native().to_string();

double synthetic_ms(const std::string& config, int camera) {
  return synthetic_frame_cost("cornell", Objective::kRender, camera, parse_accel_choice(config))
      .cost_ms(Objective::kRender);
}

InterleavedOptions options(int min_rounds, int max_rounds) {
  InterleavedOptions o;
  o.min_rounds = min_rounds;
  o.max_rounds = max_rounds;
  o.every_pair = true;
  return o;
}

TEST(ComparisonConfigs, DefaultAndNativeFirstThenEveryOtherRoleOnce) {
  EXPECT_EQ(
      comparison_configs(kDefault, tuned(8, 4), tuned(8, 4), {tuned(4, 2), kDefault, tuned(4, 2)}),
      (std::vector<std::string>{kDefault, kNative, tuned(8, 4), tuned(4, 2)}));
  // A search that converged to native Embree adds nothing for it.
  EXPECT_EQ(comparison_configs(kDefault, kNative, tuned(8, 4), {}),
            (std::vector<std::string>{kDefault, kNative, tuned(8, 4)}));
}

TEST(EvalComparison, RatiosAreMediansAndCostsInUnitsOfTheFirstConfiguration) {
  // Six rounds; per round, b / a = 0.5 and c / a = 2, 0.5, 2, 0.5, 2, 2.
  const EvalComparison c{
      {"a", "b", "c"}, {{2, 8, 4, 6, 10, 3}, {1, 4, 2, 3, 5, 1.5}, {4, 4, 8, 3, 20, 6}}, true};
  EXPECT_EQ(c.rounds(), 6);
  // a is the yardstick: its median cost (of 2 3 4 6 8 10), and every other cost that times the
  // median ratio to it.
  EXPECT_DOUBLE_EQ(c.cost_ms("a"), 5.0);
  EXPECT_DOUBLE_EQ(c.cost_ms("b"), 2.5);
  EXPECT_DOUBLE_EQ(c.cost_ms("c"), 10.0);
  const RatioInterval a_over_b = c.ratio("a", "b");
  EXPECT_DOUBLE_EQ(a_over_b.ratio, c.cost_ms("a") / c.cost_ms("b"));
  EXPECT_DOUBLE_EQ(a_over_b.low, 2.0);  // the same ratio in every round: no spread
  EXPECT_DOUBLE_EQ(a_over_b.high, 2.0);
  EXPECT_NEAR(a_over_b.confidence, 1 - 2.0 / 64, 1e-12);
  const RatioInterval c_over_b = c.ratio("c", "b");  // 4, 1, 4, 1, 4, 4: spread
  EXPECT_DOUBLE_EQ(c_over_b.ratio, 4.0);
  EXPECT_DOUBLE_EQ(c_over_b.low, 1.0);
  EXPECT_DOUBLE_EQ(c_over_b.high, 4.0);
  EXPECT_EQ(c.fastest(), "b");
  EXPECT_THROW(c.cost_ms("d"), std::out_of_range);
}

// The comparison's figures resist a stopped frame: one round of the 30 in which the converged
// configuration took 30 times as long (SIGSTOP, a load spike) changes no ratio and no cost.
TEST(EvalComparison, OneStoppedFrameChangesNoFigure) {
  std::vector<std::vector<double>> costs(3);
  for (int round = 0; round < 30; ++round) {
    const double load = 1 + 0.25 * ((round * 7) % 5);  // exact in binary: exact ratios
    costs[0].push_back(40 * load);
    costs[1].push_back(50 * load);
    costs[2].push_back(30 * load);
  }
  const EvalComparison quiet{{kDefault, kNative, "converged"}, costs, true};
  costs[2][11] *= 30;
  const EvalComparison stopped{quiet.configs, costs, true};
  for (const std::string& a : quiet.configs) {
    EXPECT_DOUBLE_EQ(stopped.cost_ms(a), quiet.cost_ms(a)) << a;
    for (const std::string& b : quiet.configs) {
      EXPECT_DOUBLE_EQ(stopped.ratio(a, b).ratio, quiet.ratio(a, b).ratio) << a << " / " << b;
      EXPECT_DOUBLE_EQ(stopped.ratio(a, b).low, quiet.ratio(a, b).low) << a << " / " << b;
      EXPECT_DOUBLE_EQ(stopped.ratio(a, b).high, quiet.ratio(a, b).high) << a << " / " << b;
    }
  }
  EXPECT_NEAR(stopped.ratio(kDefault, "converged").ratio, 4.0 / 3.0, 1e-12);
  EXPECT_NEAR(stopped.cost_ms("converged"), 30 * median(costs[0]) / 40, 1e-12);
  EXPECT_EQ(stopped.fastest(), "converged");
}

// comparisons.tsv of runs before the median: the same JSON, rounds that may stop at 3. They are
// read and derived with the median; their interval is the range of their ratios, and says that
// it is short of 95 %.
TEST(EvalComparison, AComparisonStoppedAtThreeRoundsByTheEarlierRuleIsStillRead) {
  const EvalComparison old = parse_eval_comparison(
      R"({"configs":["a","b"],"costs":[[2.0,2.2,2.1],[1.0,1.0,1.0]],"within_target":true})");
  EXPECT_EQ(old.rounds(), 3);
  EXPECT_TRUE(old.within_target);
  const RatioInterval r = old.ratio("a", "b");
  EXPECT_DOUBLE_EQ(r.ratio, 2.1);
  EXPECT_DOUBLE_EQ(r.low, 2.0);
  EXPECT_DOUBLE_EQ(r.high, 2.2);
  EXPECT_EQ(r.confidence, 0.75);
  EXPECT_DOUBLE_EQ(old.cost_ms("b"), 2.1 / 2.1);
}

TEST(EvalComparison, ALoadChangeBetweenRoundsHitsEveryCandidateAlike) {
  const std::vector<std::string> configs =
      comparison_configs(kDefault, tuned(8, 4), tuned(4, 8), {tuned(8, 16)});
  MachineLoad load;
  // The warm-up, then each round: a machine getting busy.
  load.load = {1.0, 1.2, 1.5, 3.0, 4.0, 4.5, 5.0};
  LoadedMachine interleaved("cornell", Objective::kRender, load);
  const EvalComparison c =
      measure_comparison(interleaved, Objective::kRender, 2, configs, options(3, 30));
  EXPECT_EQ(c.configs, configs);
  // No spread: the interval is exact as soon as it is a 95 % interval, at 6 rounds for a median
  // (the minimum of 3 was for the geometric mean).
  EXPECT_EQ(c.rounds(), 6);
  EXPECT_TRUE(c.within_target);
  for (const std::string& a : configs)
    for (const std::string& b : configs) {
      const RatioInterval r = c.ratio(a, b);
      const double truth = synthetic_ms(a, 2) / synthetic_ms(b, 2);
      EXPECT_NEAR(r.ratio, truth, 1e-12 * truth) << a << " / " << b;
      EXPECT_NEAR(r.low, truth, 1e-12 * truth);
      EXPECT_NEAR(r.high, truth, 1e-12 * truth);
    }
  // The costs themselves carry the load (the median of 1.2, 1.5, 3, 4, 4.5 and 5 times it).
  EXPECT_NEAR(c.cost_ms(kDefault), 3.5 * synthetic_ms(kDefault, 2), 1e-9);

  // Measured one after the other, the median of three frames each (the earlier protocol), the
  // same machine fools the comparison: native Embree, measured later, looks 2.5 times slower
  // relative to the default than it is.
  LoadedMachine sequential("cornell", Objective::kRender, load);
  auto median_of_three = [&](const std::string& config) {
    std::vector<double> ms;
    for (int k = 0; k < 3; ++k)
      ms.push_back(sequential.frame(parse_accel_choice(config), 2).cost_ms(Objective::kRender));
    return median(ms);
  };
  const double fooled = median_of_three(kDefault) / median_of_three(kNative);
  const double truth = synthetic_ms(kDefault, 2) / synthetic_ms(kNative, 2);
  EXPECT_NEAR(fooled / truth, 1.2 / 3.0, 1e-12);
}

TEST(EvalComparison, TheUntimedFirstFramesAreNotCounted) {
  MachineLoad load;
  load.load = {50.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0};  // the warm-up is very slow (cold trees)
  LoadedMachine machine("cornell", Objective::kRender, load);
  const std::vector<std::string> configs =
      comparison_configs(kDefault, tuned(8, 4), tuned(8, 4), {});
  const EvalComparison c =
      measure_comparison(machine, Objective::kRender, 0, configs, options(6, 30));
  ASSERT_EQ(c.rounds(), 6);
  // Not a single round holds a warm-up frame (a median would hide one in its figures).
  for (size_t i = 0; i < configs.size(); ++i)
    for (double ms : c.costs[i]) EXPECT_NEAR(ms, synthetic_ms(configs[i], 0), 1e-12) << configs[i];
}

TEST(EvalComparison, NoisyRoundsGoOnToTheCapAndSaySo) {
  // Alternate rounds hit native Embree alone (a background job waking up): wide intervals.
  class Jittery : public EvalCostSource {
   public:
    FrameCost frame(const AccelChoice& choice, int camera) override {
      FrameCost cost = synthetic_frame_cost("cornell", Objective::kRender, camera, choice);
      if (choice.is_native() && ++native_frames_ % 2 == 0) cost.render_ms *= 1.5;
      return cost;
    }

   private:
    int native_frames_ = 0;
  } jittery;
  const EvalComparison c =
      measure_comparison(jittery, Objective::kRender, 1,
                         comparison_configs(kDefault, tuned(8, 4), kDefault, {}), options(3, 7));
  EXPECT_EQ(c.rounds(), 7);
  EXPECT_FALSE(c.within_target);
  const RatioInterval native_over_default = c.ratio(kNative, kDefault);
  EXPECT_GT(native_over_default.relative_half_width(), 0.03);
}

TEST(EvalComparison, ARefusedBuildNamesTheConfiguration) {
  class Refusing : public EvalCostSource {
   public:
    FrameCost frame(const AccelChoice& choice, int camera) override {
      FrameCost cost = synthetic_frame_cost("cornell", Objective::kRender, camera, choice);
      if (choice.is_native()) {
        cost.ok = false;
        cost.error = "out of memory";
      }
      return cost;
    }
  } refusing;
  try {
    measure_comparison(refusing, Objective::kRender, 3,
                       comparison_configs(kDefault, kDefault, kDefault, {}), options(3, 30));
    FAIL() << "a refused build was compared";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(kNative), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("out of memory"), std::string::npos) << e.what();
  }
}

TEST(EvalComparison, JsonKeepsEveryBitAndRefusesWhatCannotBeAComparison) {
  const EvalComparison c{{"a", "b"}, {{0.1 + 0.2, 1.0 / 3.0}, {2e-300, 7.0}}, true};
  const EvalComparison back = parse_eval_comparison(to_json(c));
  EXPECT_EQ(back.configs, c.configs);
  EXPECT_EQ(back.costs, c.costs);
  EXPECT_TRUE(back.within_target);
  EXPECT_THROW(parse_eval_comparison("{\"configs\":[\"a\"]"), std::runtime_error);
  EXPECT_THROW(parse_eval_comparison(to_json({{"a", "b"}, {{1, 2}, {1}}, false})),
               std::runtime_error);  // rounds of different lengths
  EXPECT_THROW(parse_eval_comparison(to_json({{"a", "b"}, {{1}, {0}}, false})), std::runtime_error);
  EXPECT_THROW(parse_eval_comparison(to_json({{"a", "b"}, {{1}}, false})), std::runtime_error);
}

TEST(ComparisonLog, AStoredComparisonCountsOnlyForTheSameConfigurations) {
  testing::TempDir dir;
  const std::string path = dir.file("comparisons.tsv");
  const EvalComparison c{{"a", "b"}, {{1.0 / 3.0, 2}, {3, 4}}, true};
  {
    ComparisonLog log(path, "run");
    EXPECT_EQ(log.add(4, c).costs, c.costs);
  }
  ComparisonLog again(path, "run");
  ASSERT_TRUE(again.find(4, {"a", "b"}).has_value());
  EXPECT_EQ(again.find(4, {"a", "b"})->costs, c.costs);
  EXPECT_FALSE(again.find(4, {"b", "a"}).has_value());
  EXPECT_FALSE(again.find(4, {"a", "b", "c"}).has_value());
  EXPECT_FALSE(again.find(3, {"a", "b"}).has_value());
  EXPECT_FALSE(ComparisonLog(path, "ru").find(4, {"a", "b"}).has_value());
}

TEST(ComparisonLog, ALineTornByAKillIsMeasuredAgain) {
  testing::TempDir dir;
  const std::string path = dir.file("comparisons.tsv");
  const EvalComparison c{{"a", "b"}, {{1, 2}, {3, 4}}, true};
  const std::string whole = "run\t4\t" + to_json(c);
  // Cut right before the line break: the text is a whole comparison, but the line is not.
  std::ofstream(path, std::ios::binary) << whole;
  ComparisonLog log(path, "run");
  EXPECT_FALSE(log.find(4, {"a", "b"}).has_value());
  log.add(5, c);
  EXPECT_FALSE(ComparisonLog(path, "run").find(4, {"a", "b"}).has_value());
  EXPECT_TRUE(ComparisonLog(path, "run").find(5, {"a", "b"}).has_value());
}

}  // namespace
}  // namespace tuneray
