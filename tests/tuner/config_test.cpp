#include "tuner/config.h"

#include <gtest/gtest.h>

#include <unordered_set>

#include "bvh_space.h"
#include "tuner/space.h"

namespace tuneray::tuner {
namespace {

using testing::bvh_space;

TEST(Config, NamedAccessReturnsDefaults) {
  const Config c = bvh_space().default_config();
  EXPECT_EQ(c.get_enum("quality"), "medium");
  EXPECT_EQ(c.get_int("branching"), 2);
  EXPECT_EQ(c.get_int("max_depth"), 32);
  EXPECT_EQ(c.get_real("cost_ratio"), 1.0);
  EXPECT_FALSE(c.get_bool("robust"));
  EXPECT_THROW(c.get_int("quality"), std::invalid_argument);
  EXPECT_THROW(c.get_int("nope"), std::invalid_argument);
}

TEST(Config, StringFormRoundTrips) {
  const Space space = bvh_space();
  Config c = space.default_config();
  c.set_enum("quality", "high").set_int("branching", 8).set_real("cost_ratio", 0.1 + 0.2);
  c.set_bool("compact", true);
  const std::string text = c.to_string();
  EXPECT_EQ(text,
            "quality=high,branching=8,max_depth=32,sah_block_size=1,min_leaf=1,max_leaf=32,"
            "cost_ratio=0.30000000000000004,static=false,compact=true,robust=false");
  EXPECT_EQ(space.parse(text), c);
  EXPECT_EQ(space.parse("branching=4").get_int("branching"), 4);  // the rest default
  EXPECT_THROW(space.parse("branching=3"), std::invalid_argument);
  EXPECT_THROW(space.parse("colour=red"), std::invalid_argument);
  EXPECT_THROW(space.parse("static=yes"), std::invalid_argument);
}

TEST(Config, EqualityAndHashFollowValues) {
  const Space space = bvh_space();
  const Config a = space.parse("max_depth=40");
  const Config b = space.parse("max_depth=40");
  const Config c = space.parse("max_depth=41");
  EXPECT_EQ(a, b);
  EXPECT_EQ(a.hash(), b.hash());
  EXPECT_FALSE(a == c);
  std::unordered_set<Config> set{a, b, c};
  EXPECT_EQ(set.size(), 2u);
}

}  // namespace
}  // namespace tuneray::tuner
