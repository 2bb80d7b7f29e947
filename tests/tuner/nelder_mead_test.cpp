#include "tuner/nelder_mead.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <unordered_set>

#include "test_functions.h"
#include "tuner/space.h"

namespace tuneray::tuner {
namespace {

using testing::gaussian;
using testing::run_search;

constexpr int kSeeds = 50;
constexpr int kRequiredSuccesses = 45;  // 90 % of 50

// 1 + sum (x_i - a_i)^2 over [-5,5]^3 with 5 % multiplicative Gaussian noise.
// Success: every coordinate within 0.25 of the optimum (2.5 % of the range), 80 iterations.
TEST(NelderMead, FindsNoisyQuadraticMinimum) {
  Space space;
  space.add_real("x", -5, 5, 0).add_real("y", -5, 5, 0).add_real("z", -5, 5, 0);
  const double optimum[3] = {1.5, -2.0, 3.0};
  int successes = 0;
  for (int seed = 0; seed < kSeeds; ++seed) {
    Rng noise(1000 + seed);
    NelderMead search(space, NelderMeadOptions{}, space.encode(space.default_config()), seed);
    const auto run = run_search(search, [&](const Config& c) {
      const double d[3] = {c.get_real("x") - optimum[0], c.get_real("y") - optimum[1],
                           c.get_real("z") - optimum[2]};
      const double f = 1.0 + d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
      return f * (1.0 + 0.05 * gaussian(noise));
    });
    const Config& best = run.incumbent;
    const bool found = std::abs(best.get_real("x") - optimum[0]) <= 0.25 &&
                       std::abs(best.get_real("y") - optimum[1]) <= 0.25 &&
                       std::abs(best.get_real("z") - optimum[2]) <= 0.25;
    successes += found;
    EXPECT_LE(search.iterations(), 80);
  }
  std::printf("%d of %d seeds found the minimum\n", successes, kSeeds);
  EXPECT_GE(successes, kRequiredSuccesses);
}

// Rosenbrock 1 + (1-x)^2 + 100 (y-x^2)^2 over [-2,2]^2 from (-1.2, 1), noise-free (so one
// repeat per point): its curved valley tests the moves, not the noise handling.
// Success: within 0.01 (Euclidean) of (1, 1) with a budget of 200 iterations.
TEST(NelderMead, FindsRosenbrockMinimum) {
  Space space;
  space.add_real("x", -2, 2, -1.2).add_real("y", -2, 2, 1.0);
  NelderMeadOptions options;
  options.max_iterations = 200;
  options.x_tolerance = 1e-4;
  options.max_repeats = 1;
  int successes = 0;
  for (int seed = 0; seed < kSeeds; ++seed) {
    NelderMead search(space, options, space.encode(space.default_config()), seed);
    const auto run = run_search(search, [&](const Config& c) {
      const double x = c.get_real("x");
      const double y = c.get_real("y");
      return 1.0 + (1 - x) * (1 - x) + 100 * (y - x * x) * (y - x * x);
    });
    successes +=
        std::hypot(run.incumbent.get_real("x") - 1, run.incumbent.get_real("y") - 1) <= 0.01;
  }
  std::printf("%d of %d seeds found the minimum\n", successes, kSeeds);
  EXPECT_GE(successes, kRequiredSuccesses);
}

// Mixed integer / value set / enum / real, 2 % noise. Success: the exact discrete optimum
// (i = 13, s = 8, kind = c) and |r - 0.7| <= 0.1, with a budget of 120 iterations (four
// dimensions, three of them plateaus).
TEST(NelderMead, FindsMixedIntegerEnumMinimum) {
  Space space;
  space.add_int("i", 0, 20, 0)
      .add_int_set("s", {1, 2, 4, 8, 16, 32}, 1)
      .add_enum("kind", {"a", "b", "c", "d"}, "a")
      .add_real("r", 0, 1, 0.5);
  const double penalty[4] = {0.6, 0.3, 0.0, 0.4};
  NelderMeadOptions options;
  options.max_iterations = 120;
  int successes = 0;
  for (int seed = 0; seed < kSeeds; ++seed) {
    Rng noise(3000 + seed);
    NelderMead search(space, options, space.encode(space.default_config()), seed);
    const auto run = run_search(search, [&](const Config& c) {
      const double i = static_cast<double>(c.get_int("i"));
      const double s = std::log2(static_cast<double>(c.get_int("s")));
      const double r = c.get_real("r");
      const int kind = c.get_enum("kind")[0] - 'a';
      const double f = 1.0 + (i - 13) * (i - 13) / 20.0 + (s - 3) * (s - 3) / 4.0 + penalty[kind] +
                       4.0 * (r - 0.7) * (r - 0.7);
      return f * (1.0 + 0.02 * gaussian(noise));
    });
    const Config& best = run.incumbent;
    successes += best.get_int("i") == 13 && best.get_int("s") == 8 &&
                 best.get_enum("kind") == "c" && std::abs(best.get_real("r") - 0.7) <= 0.1;
  }
  std::printf("%d of %d seeds found the minimum\n", successes, kSeeds);
  EXPECT_GE(successes, kRequiredSuccesses);
}

// Seeds: a plateau (cost 100) with one narrow basin far from the default (all zeros). A seed
// inside the basin is measured among the first simplex's points, and every seeded search ends
// at least as good as the seed; unseeded searches from the default mostly never see the basin.
TEST(NelderMead, SeedsJoinTheFirstSimplexAndTheSearchEndsNoWorse) {
  Space space;
  for (const char* name : {"a", "b", "c", "d", "e", "f"}) space.add_int(name, 0, 20, 0);
  auto cost = [](const Config& c) {
    double d2 = 0;
    for (const char* name : {"a", "b", "c", "d", "e", "f"}) {
      const double d = c.get_int(name) - 17;
      d2 += d * d;
    }
    return d2 < 30 ? 1.0 + d2 : 100.0;
  };
  Config seed = space.default_config();
  for (const char* name : {"a", "b", "c", "d", "e", "f"}) seed.set_int(name, 15);
  const double seed_cost = cost(seed);  // 25: inside the basin, not at its bottom
  int unseeded_in_basin = 0;
  for (int s = 0; s < 20; ++s) {
    const std::vector<double> start = space.encode(space.default_config());
    NelderMead seeded(space, NelderMeadOptions{}, start, s, {space.encode(seed), start});
    std::vector<Config> order;
    const auto run = run_search(seeded, [&](const Config& c) {
      order.push_back(c);
      return cost(c);
    });
    ASSERT_GE(order.size(), space.size() + 1);
    const auto first = order.begin() + static_cast<std::ptrdiff_t>(space.size() + 1);
    EXPECT_NE(std::find(order.begin(), first, seed), first) << "seed " << s;
    EXPECT_LE(cost(run.incumbent), seed_cost) << "seed " << s;
    // The seed equal to the start point is skipped: the first simplex has n + 1 distinct points.
    const std::unordered_set<Config, ConfigHash> distinct(order.begin(), first);
    EXPECT_EQ(distinct.size(), space.size() + 1) << "seed " << s;

    NelderMead plain(space, NelderMeadOptions{}, start, s);
    unseeded_in_basin += cost(run_search(plain, cost).incumbent) < 100.0;
  }
  std::printf("%d of 20 unseeded searches reached the basin\n", unseeded_in_basin);
  EXPECT_LT(unseeded_in_basin, 10);
}

TEST(NelderMead, NeverMeasuresARoundedDuplicateTwiceWithoutWantingMoreRepeats) {
  Space space;
  space.add_int("a", 0, 3, 0).add_int("b", 0, 3, 0);
  NelderMeadOptions options;
  options.max_repeats = 1;  // deterministic cost: one measurement per configuration suffices
  options.min_repeats = 1;
  NelderMead search(space, options, space.encode(space.default_config()), 7);
  const auto run = run_search(search, [](const Config& c) {
    return 1.0 + std::abs(c.get_int("a") - 2) + std::abs(c.get_int("b") - 1);
  });
  // With one repeat wanted, only the incumbent gets a second measurement (max_repeats + 1).
  for (const auto& [config, costs] : run.table) {
    EXPECT_LE(costs.size(), 2u) << config.to_string();
  }
  EXPECT_EQ(run.measurements, static_cast<int>([&] {
              size_t total = 0;
              for (const auto& entry : run.table) total += entry.second.size();
              return total;
            }()));
  // 16 configurations exist; without reuse a search of this length would measure far more.
  EXPECT_LE(run.table.size(), 16u);
}

TEST(NelderMead, MovesRespectConstraints) {
  Space space;
  space.add_int("min_leaf", 1, 8, 1).add_int("max_leaf", 1, 32, 32);
  space.add_constraint("min_leaf <= max_leaf", [](const Config& c) {
    return c.get_int("min_leaf") <= c.get_int("max_leaf");
  });
  NelderMead search(space, NelderMeadOptions{}, space.encode(space.default_config()), 3);
  // The unconstrained optimum (min 8, max 1) is infeasible.
  const auto run = run_search(search, [](const Config& c) {
    return 1.0 + (8 - c.get_int("min_leaf")) + (c.get_int("max_leaf") - 1) / 4.0;
  });
  for (const auto& [config, costs] : run.table) {
    EXPECT_LE(config.get_int("min_leaf"), config.get_int("max_leaf")) << config.to_string();
  }
}

TEST(NelderMead, FailuresAreMeasuredOnceAndAvoided) {
  Space space;
  space.add_real("x", 0, 1, 0.5);
  NelderMead search(space, NelderMeadOptions{}, space.encode(space.default_config()), 11);
  const auto run = run_search(search, [](const Config& c) {
    const double x = c.get_real("x");
    return x > 0.8 ? std::numeric_limits<double>::infinity() : 1.0 + (x - 0.7) * (x - 0.7);
  });
  for (const auto& [config, costs] : run.table) {
    if (std::isinf(costs.front())) {
      EXPECT_EQ(costs.size(), 1u);
    }
  }
  EXPECT_NEAR(run.incumbent.get_real("x"), 0.7, 0.05);
}

TEST(NelderMead, SerialisedSearchContinuesIdentically) {
  Space space;
  space.add_real("x", -1, 1, 0).add_int("n", 0, 10, 5).add_enum("e", {"p", "q"}, "p");
  auto cost = [](const Config& c) {
    return 1.0 + c.get_real("x") * c.get_real("x") + std::abs(c.get_int("n") - 3) +
           (c.get_enum("e") == "q" ? 0.0 : 0.5);
  };
  NelderMead original(space, NelderMeadOptions{}, space.encode(space.default_config()), 5);
  testing::CostTable table;
  const NelderMead::Lookup lookup = table.lookup();
  for (int i = 0; i < 15; ++i) {
    const auto next = original.next(lookup);
    ASSERT_TRUE(next);
    table.costs[*next].push_back(cost(*next));
  }
  NelderMead copy = NelderMead::deserialise(space, NelderMeadOptions{}, original.serialise());
  EXPECT_EQ(copy.serialise(), original.serialise());
  testing::expect_same_requests(original, copy, table, cost, 30);
}

}  // namespace
}  // namespace tuneray::tuner
