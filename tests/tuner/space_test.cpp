#include "tuner/space.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "bvh_space.h"
#include "tuner/latin_hypercube.h"

namespace tuneray::tuner {
namespace {

using testing::bvh_space;

TEST(Space, DiscreteValuesOwnEqualCells) {
  Space space;
  space.add_int_set("branching", {2, 4, 8}, 2);
  EXPECT_EQ(space.decode(std::vector<double>{0.0}).get_int("branching"), 2);
  EXPECT_EQ(space.decode(std::vector<double>{0.33}).get_int("branching"), 2);
  EXPECT_EQ(space.decode(std::vector<double>{0.34}).get_int("branching"), 4);
  EXPECT_EQ(space.decode(std::vector<double>{0.99}).get_int("branching"), 8);
  EXPECT_EQ(space.decode(std::vector<double>{1.0}).get_int("branching"), 8);
  EXPECT_EQ(space.encode(space.parse("branching=4")), std::vector<double>{0.5});
}

TEST(Space, IntRangeRoundsToCells) {
  Space space;
  space.add_int("n", 1, 4, 1);
  EXPECT_EQ(space.decode(std::vector<double>{0.24}).get_int("n"), 1);
  EXPECT_EQ(space.decode(std::vector<double>{0.26}).get_int("n"), 2);
  EXPECT_EQ(space.encode(space.parse("n=4")), std::vector<double>{0.875});
}

TEST(Space, LogScaledRealIsGeometric) {
  Space space;
  space.add_real("ratio", 0.01, 100.0, 1.0, Scale::kLog);
  EXPECT_NEAR(space.decode(std::vector<double>{0.5}).get_real("ratio"), 1.0, 1e-12);
  EXPECT_NEAR(space.decode(std::vector<double>{0.75}).get_real("ratio"), 10.0, 1e-9);
  EXPECT_NEAR(space.encode(space.parse("ratio=0.1"))[0], 0.25, 1e-12);
}

TEST(Space, EncodeDecodeRoundTripsEveryDefault) {
  const Space space = bvh_space();
  const Config c = space.default_config();
  const Config back = space.decode(space.encode(c));
  EXPECT_EQ(back.to_string(), c.to_string());
}

TEST(Space, InactiveParametersArePinnedSoDuplicatesCollapse) {
  const Space space = bvh_space();
  std::vector<double> a = space.encode(space.parse("quality=low"));
  std::vector<double> b = a;
  const size_t block = space.index_of("sah_block_size");
  const size_t ratio = space.index_of("cost_ratio");
  a[block] = 0.05;
  b[block] = 0.95;
  a[ratio] = 0.1;
  b[ratio] = 0.9;
  const Config ca = space.decode(a);
  const Config cb = space.decode(b);
  EXPECT_EQ(ca, cb);
  EXPECT_EQ(ca.get_int("sah_block_size"), 1);  // default
  EXPECT_EQ(ca.get_real("cost_ratio"), 1.0);
  // Active under medium quality: they differ.
  const size_t quality = space.index_of("quality");
  a[quality] = b[quality] = 0.5;
  EXPECT_FALSE(space.decode(a) == space.decode(b));
  EXPECT_EQ(space.parse("quality=low,sah_block_size=16"), space.parse("quality=low"));
}

TEST(Space, FeasibleRepairsConstraintViolations) {
  const Space space = bvh_space();
  std::vector<double> point = space.encode(space.parse("min_leaf=8,max_leaf=2"));
  EXPECT_FALSE(space.satisfies_constraints(space.decode(point)));
  const Config repaired = space.feasible(point);
  EXPECT_TRUE(space.satisfies_constraints(repaired));
  EXPECT_EQ(space.decode(point), repaired);
  // Every LHS point, once made feasible, satisfies the constraint.
  Rng rng(5);
  for (auto& p : latin_hypercube(200, space.size(), rng)) {
    const Config c = space.feasible(p);
    EXPECT_LE(c.get_int("min_leaf"), c.get_int("max_leaf"));
  }
}

TEST(Space, RejectsBadDeclarations) {
  Space space;
  space.add_int("a", 0, 3, 1);
  EXPECT_THROW(space.add_int("a", 0, 3, 1), std::invalid_argument);
  EXPECT_THROW(space.add_int("b", 3, 0, 1), std::invalid_argument);
  EXPECT_THROW(space.add_int_set("c", {2, 4}, 3), std::invalid_argument);
  EXPECT_THROW(space.add_real("d", 0.0, 1.0, 0.5, Scale::kLog), std::invalid_argument);
  EXPECT_THROW(space.add_enum("e", {"x", "y"}, "z"), std::invalid_argument);
  EXPECT_THROW(space.add_bool("bad name", false), std::invalid_argument);
}

}  // namespace
}  // namespace tuneray::tuner
