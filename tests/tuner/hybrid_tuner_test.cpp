#include "tuner/hybrid_tuner.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include "bvh_space.h"
#include "synthetic_problem.h"

namespace tuneray::tuner {
namespace {

using testing::kernel_cost;
using testing::kernel_schema;
using testing::kernel_space;

struct EventCounts {
  int started = 0;
  int resumed = 0;
  int finished = 0;
  int predicted = 0;
};

EventCounts* attach_counter(HybridTuner& tuner, EventCounts& counts) {
  tuner.set_event_listener([&counts](const TunerEvent& e) {
    if (e.kind == TunerEventKind::kSearchStarted) ++counts.started;
    if (e.kind == TunerEventKind::kSearchResumed) ++counts.resumed;
    if (e.kind == TunerEventKind::kSearchFinished) ++counts.finished;
    if (e.kind == TunerEventKind::kPredicted) ++counts.predicted;
  });
  return &counts;
}

void run_state(HybridTuner& tuner, double size, int steps) {
  const State state{size};
  for (int i = 0; i < steps; ++i) {
    const Config c = tuner.suggest(state);
    tuner.report(c, kernel_cost(state, c));
  }
}

TunerOptions fast_options(double epsilon) {
  TunerOptions options;
  options.epsilon = epsilon;
  options.search.max_iterations = 30;
  options.search.max_repeats = 1;  // the synthetic cost is noise-free
  return options;
}

TEST(HybridTuner, EpsilonOneSearchesAtEveryStateChange) {
  HybridTuner tuner(kernel_space(), kernel_schema(), fast_options(1.0));
  EventCounts counts;
  attach_counter(tuner, counts);
  const double sizes[] = {100, 400, 100, 700, 400, 700};
  for (double size : sizes) run_state(tuner, size, 5);
  // Six state changes: three new searches, three resumed (unfinished after 5 steps).
  EXPECT_EQ(counts.started + counts.resumed, 6);
  EXPECT_EQ(counts.started, 3);
  EXPECT_EQ(counts.predicted, 0);
}

TEST(HybridTuner, EpsilonZeroAfterTrainingNeverSearches) {
  HybridTuner tuner(kernel_space(), kernel_schema(), fast_options(1.0));
  for (double size : {0.0, 300.0, 600.0, 900.0}) run_state(tuner, size, 400);
  for (const auto& s : tuner.summaries()) EXPECT_FALSE(s.searching);
  tuner.set_epsilon(0.0);
  EventCounts counts;
  attach_counter(tuner, counts);
  for (double size : {150.0, 450.0, 0.0, 750.0, 1000.0, 300.0}) run_state(tuner, size, 3);
  EXPECT_EQ(counts.started + counts.resumed, 0);
  EXPECT_EQ(counts.predicted, 6);
}

TEST(HybridTuner, SearchFindsTheOptimumAndSummaryReportsIt) {
  HybridTuner tuner(kernel_space(), kernel_schema(), fast_options(1.0));
  run_state(tuner, 450.0, 300);  // best block 2^4 = 16, unroll 4
  const auto summary = tuner.summary(State{450.0});
  ASSERT_TRUE(summary);
  EXPECT_TRUE(summary->searched);
  EXPECT_FALSE(summary->searching);
  EXPECT_TRUE(summary->converged);
  EXPECT_GT(summary->search_iterations, 0);
  ASSERT_TRUE(summary->incumbent);
  EXPECT_EQ(summary->incumbent->get_int("block"), 16);
  EXPECT_EQ(summary->incumbent->get_int("unroll"), 4);
  EXPECT_DOUBLE_EQ(summary->incumbent_cost, 5.5);
  EXPECT_EQ(tuner.best(State{450.0}), *summary->incumbent);
  EXPECT_EQ(tuner.mode(), TunerMode::kExploit);
  EXPECT_EQ(tuner.candidates().size(), 1u);
}

TEST(HybridTuner, UnseenStatesGetNearBestPredictionsWithoutSearching) {
  TunerOptions options = fast_options(1.0);
  options.predictor = PredictorKind::kNearestNeighbour;
  HybridTuner tuner(kernel_space(), kernel_schema(), options);
  for (double size : {0.0, 150.0, 300.0, 450.0, 600.0, 750.0, 900.0}) run_state(tuner, size, 300);
  tuner.set_epsilon(0.0);
  for (double size : {160.0, 440.0, 760.0}) {
    const State state{size};
    const Config c = tuner.suggest(state);
    // The nearest trained state's optimum is one block step away at most: within 10 %.
    Config best = c;
    best.set_int("block", 1 << static_cast<int>(std::lround(1.0 + size / 150.0)));
    best.set_int("unroll", 4);
    EXPECT_LE(kernel_cost(state, c), 1.10 * kernel_cost(state, best)) << c.to_string();
    EXPECT_EQ(tuner.mode(), TunerMode::kExploit);
  }
}

TEST(HybridTuner, ThresholdForcesSearchOfFarStatesWarmStarted) {
  TunerOptions options = fast_options(0.0);
  options.nn_threshold = 0.05;  // 50 units of size
  HybridTuner tuner(kernel_space(), kernel_schema(), options);
  EventCounts counts;
  attach_counter(tuner, counts);
  run_state(tuner, 300.0, 200);  // nothing known: searched even with epsilon 0
  run_state(tuner, 320.0, 2);    // near: predicted
  run_state(tuner, 600.0, 2);    // far: searched
  EXPECT_EQ(counts.started, 2);
  EXPECT_EQ(counts.predicted, 1);
}

TEST(HybridTuner, FailuresAreRecordedAndNeverBest) {
  HybridTuner tuner(kernel_space(), kernel_schema(), fast_options(1.0));
  const State state{450.0};
  int failures = 0;
  for (int i = 0; i < 300; ++i) {
    const Config c = tuner.suggest(state);
    if (c.get_int("unroll") == 8) {  // e.g. a build that runs out of registers
      tuner.report_failure(c, {{"build_ms", 1.0}});
      ++failures;
    } else {
      tuner.report(c, kernel_cost(state, c));
    }
  }
  EXPECT_GT(failures, 0);
  const Config best = tuner.best(state);
  EXPECT_NE(best.get_int("unroll"), 8);
  EXPECT_EQ(best.get_int("block"), 16);
  EXPECT_TRUE(std::isfinite(tuner.summary(state)->incumbent_cost));
  for (double theta : tuner.gq().theta()) EXPECT_TRUE(std::isfinite(theta));
}

// The winner's curse: a configuration measured once on a lucky frame must not become the best
// over one measured seven times that is faster in truth; measured equally often, the lower
// median still wins.
TEST(HybridTuner, OneLuckyFrameDoesNotMakeTheBest) {
  const Space space = kernel_space();
  HybridTuner tuner(space, kernel_schema(), fast_options(1.0));
  const State state{300.0};
  tuner.suggest(state);
  auto config = [&](int block) { return space.default_config().set_int("block", block); };
  const Config lucky = config(1), steady = config(2);
  tuner.report(lucky, 7.4);
  for (double ms : {8.1, 8.3, 7.9, 8.4, 8.2, 8.3, 8.0}) tuner.report(steady, ms);
  for (int block : {4, 8, 16, 32}) tuner.report(config(block), 10.0 + block / 8.0);
  EXPECT_EQ(tuner.best(state), steady);

  // The lucky configuration measured as often, at the same costs shifted 0.1 lower: it is
  // faster, and now the best.
  for (double ms : {8.2, 7.8, 8.3, 8.1, 8.2, 7.9}) tuner.report(lucky, ms - 0.1);
  EXPECT_EQ(tuner.best(state), lucky);
}

// The finalists are the measured configurations in the order best() ranks them: the lucky
// single frame behind the steady one, failures never, nothing for a state never seen.
TEST(HybridTuner, FinalistsAreRankedLikeTheBestAndSkipFailures) {
  const Space space = kernel_space();
  HybridTuner tuner(space, kernel_schema(), fast_options(1.0));
  const State state{300.0};
  EXPECT_TRUE(tuner.finalists(state, 3).empty());
  tuner.suggest(state);
  auto config = [&](int block) { return space.default_config().set_int("block", block); };
  tuner.report(config(1), 7.4);
  for (double ms : {8.1, 8.3, 7.9, 8.4, 8.2, 8.3, 8.0}) tuner.report(config(2), ms);
  for (int block : {4, 8, 16}) tuner.report(config(block), 10.0 + block / 8.0);
  tuner.report_failure(config(32));

  // Medians 7.4, 8.2, 10.5, 11, 12: prior 10.5, so the scores are 8.95 (one lucky frame),
  // 8.49 (seven steady ones), 10.5, 10.75 and 11.25.
  const std::vector<Config> top = tuner.finalists(state, 3);
  ASSERT_EQ(top.size(), 3u);
  EXPECT_EQ(top[0], tuner.best(state));
  EXPECT_EQ(top[0], config(2));
  EXPECT_EQ(top[1], config(1));
  EXPECT_EQ(top[2], config(4));
  const std::vector<Config> all = tuner.finalists(state, 10);
  ASSERT_EQ(all.size(), 5u);  // the failure is not a finalist
  EXPECT_EQ(all[3], config(8));
  EXPECT_EQ(all[4], config(16));
  EXPECT_TRUE(tuner.finalists(State{900.0}, 3).empty());
}

TEST(HybridTuner, ConditionalParametersAreNotSearchedWhenInactive) {
  const Space space = testing::bvh_space();
  IndicatorSchema schema;
  schema.add("triangles", 0, 1e7);
  TunerOptions options = fast_options(1.0);
  options.search.max_iterations = 40;
  HybridTuner tuner(space, schema, options);
  const State state{1e6};
  for (int i = 0; i < 300; ++i) {
    const Config c = tuner.suggest(state);
    EXPECT_LE(c.get_int("min_leaf"), c.get_int("max_leaf"));
    if (c.get_enum("quality") == "low") {
      EXPECT_EQ(c.get_int("sah_block_size"), 1) << c.to_string();
      EXPECT_EQ(c.get_real("cost_ratio"), 1.0) << c.to_string();
    }
    // Low quality builds fastest here; block size would matter only if it were active.
    const double quality = c.get_enum("quality") == "low" ? 1.0 : 2.0;
    tuner.report(c, quality + 0.01 * std::abs(c.get_int("max_leaf") - 8));
  }
  EXPECT_EQ(tuner.best(state).get_enum("quality"), "low");
}

TEST(HybridTuner, RejectsMisuse) {
  HybridTuner tuner(kernel_space(), kernel_schema(), fast_options(0.5));
  const Config c = tuner.space().default_config();
  EXPECT_THROW(tuner.report(c, 1.0), std::logic_error);  // before suggest
  tuner.suggest(State{10.0});
  EXPECT_THROW(tuner.report(c, -1.0), std::invalid_argument);
  EXPECT_THROW(tuner.report(c, std::nan("")), std::invalid_argument);
  EXPECT_THROW(tuner.suggest(State{1.0, 2.0}), std::invalid_argument);
  TunerOptions bad;
  bad.epsilon = 2.0;
  EXPECT_THROW(HybridTuner(kernel_space(), kernel_schema(), bad), std::invalid_argument);
  TunerOptions foreign_seed;
  Space other;
  other.add_int("x", 0, 3, 0);
  foreign_seed.search_seeds = {other.default_config()};
  EXPECT_THROW(HybridTuner(kernel_space(), kernel_schema(), foreign_seed), std::invalid_argument);
}

// A search seed is measured in the first simplex of every new search.
TEST(HybridTuner, SearchSeedsAreMeasuredInEverySearch) {
  TunerOptions options = fast_options(1.0);
  Config seed = kernel_space().default_config();
  seed.set_int("block", 64).set_int("unroll", 4);
  options.search_seeds = {seed};
  HybridTuner tuner(kernel_space(), kernel_schema(), options);
  for (double size : {100.0, 700.0}) {
    const State state{size};
    bool measured = false;
    for (int i = 0; i < 6; ++i) {
      const Config c = tuner.suggest(state);
      measured |= c == seed;
      tuner.report(c, kernel_cost(state, c));
    }
    EXPECT_TRUE(measured) << "state " << size;
  }
}

// Held-out states of the kernel problem (20, between and beyond the trained ones) for which the
// predictor `kind`, trained online on searches of 7 states, picks a configuration within 5 % of
// the optimum.
int picks_near_optimum(PredictorKind kind) {
  TunerOptions options = fast_options(1.0);
  options.predictor = kind;
  HybridTuner tuner(kernel_space(), kernel_schema(), options);
  for (double size : {0.0, 150.0, 300.0, 450.0, 600.0, 750.0, 900.0}) run_state(tuner, size, 40);
  tuner.set_epsilon(0.0);
  int near = 0;
  for (int i = 0; i < 20; ++i) {
    const State state{25.0 + 50.0 * i};
    const Config chosen = tuner.suggest(state);
    double best = std::numeric_limits<double>::infinity();
    for (int block : {1, 2, 4, 8, 16, 32, 64, 128}) {
      for (int unroll : {1, 2, 4, 8}) {
        Config c = chosen;
        c.set_int("block", block).set_int("unroll", unroll);
        best = std::min(best, kernel_cost(state, c));
      }
    }
    if (kernel_cost(state, chosen) <= 1.05 * best) ++near;
  }
  return near;
}

// The RBF's smooth features, trained on what searches measure, do not follow an optimum that
// crosses all eight block sizes: alone it spreads one configuration over every state (before the
// check below, the combined predictor did the same: 4 of 20). The combined predictor lets it
// override the nearest neighbour only if, at the neighbour's own state, it picks the
// configuration measured best there, so it keeps the neighbour's answers here.
TEST(HybridTuner, BothKeepsTheNeighbourWhereTheRbfCannotFitTheProblem) {
  const int nn = picks_near_optimum(PredictorKind::kNearestNeighbour);
  const int rbf = picks_near_optimum(PredictorKind::kRbf);
  const int both = picks_near_optimum(PredictorKind::kBoth);
  std::printf("kernel problem, held-out states within 5 %%: NN %d, RBF %d, both %d of 20\n", nn,
              rbf, both);
  EXPECT_GE(nn, 18);
  EXPECT_LE(rbf, 10);
  EXPECT_GE(both, nn - 1);
}

}  // namespace
}  // namespace tuneray::tuner
