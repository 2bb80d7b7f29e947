#include "tuner/nelder_mead.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

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
  std::unordered_map<Config, std::vector<double>> table;
  const NelderMead::Lookup lookup = [&](const Config& c) -> const std::vector<double>* {
    const auto it = table.find(c);
    return it == table.end() ? nullptr : &it->second;
  };
  for (int i = 0; i < 15; ++i) {
    const auto next = original.next(lookup);
    ASSERT_TRUE(next);
    table[*next].push_back(cost(*next));
  }
  NelderMead copy = NelderMead::deserialise(space, NelderMeadOptions{}, original.serialise());
  EXPECT_EQ(copy.serialise(), original.serialise());
  for (int i = 0; i < 30; ++i) {
    const auto a = original.next(lookup);
    const auto b = copy.next(lookup);
    ASSERT_EQ(a.has_value(), b.has_value());
    if (!a) break;
    EXPECT_EQ(*a, *b);
    table[*a].push_back(cost(*a));
  }
}

}  // namespace
}  // namespace tuneray::tuner
