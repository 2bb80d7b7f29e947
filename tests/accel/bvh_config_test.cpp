#include "accel/bvh_config.h"

#include <gtest/gtest.h>

#include <stdexcept>

#include "accel/factory.h"

namespace tuneray {
namespace {

TEST(BvhConfig, DefaultsAreEmbreeRecommended) {
  BvhConfig c;
  EXPECT_EQ(c.to_string(),
            "quality=medium,branching=2,max_depth=32,sah_block_size=1,min_leaf=1,max_leaf=32,"
            "trav_cost=1,int_cost=1,static=0,compact=0,robust=0,collapse=1,optimal_collapse=0,"
            "reinsert=0");
  EXPECT_EQ(parse_bvh_config(""), c);
}

TEST(BvhConfig, ToStringParsesBack) {
  BvhConfig c = parse_bvh_config(
      "quality=high,branching=8,max_depth=40,sah_block_size=4,min_leaf=2,max_leaf=6,"
      "trav_cost=3,int_cost=0.5,static=1,compact=1,robust=1");
  EXPECT_EQ(c.quality, BvhQuality::kHigh);
  EXPECT_EQ(c.branching, 8);
  EXPECT_EQ(c.max_depth, 40);
  EXPECT_EQ(c.sah_block_size, 4);
  EXPECT_EQ(c.min_leaf, 2);
  EXPECT_EQ(c.max_leaf, 6);
  EXPECT_FLOAT_EQ(c.cost_ratio(), 6.0f);
  EXPECT_TRUE(c.is_static && c.compact && c.robust);
  EXPECT_EQ(parse_bvh_config(c.to_string()), c);
}

TEST(BvhConfig, CostRatioSetsBothCosts) {
  BvhConfig c = parse_bvh_config("cost_ratio=4");
  EXPECT_FLOAT_EQ(c.trav_cost, 4.0f);
  EXPECT_FLOAT_EQ(c.int_cost, 1.0f);
  c.set_cost_ratio(1000.0f);
  EXPECT_FLOAT_EQ(c.cost_ratio(), 20.0f);
  c.set_cost_ratio(0.0f);
  EXPECT_FLOAT_EQ(c.cost_ratio(), 0.05f);
}

TEST(BvhConfig, MinLeafAboveMaxLeafIsRepairedDownwards) {
  BvhConfig c;
  c.min_leaf = 8;
  c.max_leaf = 3;
  std::string note = c.validate();
  EXPECT_EQ(c.min_leaf, 3);
  EXPECT_EQ(c.max_leaf, 3);
  EXPECT_NE(note.find("min_leaf"), std::string::npos);
  EXPECT_EQ(parse_bvh_config("min_leaf=8,max_leaf=3").min_leaf, 3);
}

void expect_rejected(const std::string& text, const std::string& fragment) {
  try {
    parse_bvh_config(text);
    FAIL() << "accepted '" << text << "'";
  } catch (const std::invalid_argument& e) {
    std::string msg = e.what();
    EXPECT_NE(msg.find(fragment), std::string::npos) << msg;
    EXPECT_NE(msg.find("branching=2|4|8"), std::string::npos) << "no list of ranges: " << msg;
  }
}

TEST(BvhConfig, RejectsUnknownAndOutOfRange) {
  expect_rejected("qualiti=high", "unknown parameter 'qualiti'");
  expect_rejected("quality=ultra", "quality");
  expect_rejected("branching=16", "branching");
  expect_rejected("branching=3", "branching");
  expect_rejected("max_depth=7", "max_depth");
  expect_rejected("max_depth=65", "max_depth");
  expect_rejected("sah_block_size=3", "sah_block_size");
  expect_rejected("sah_block_size=32", "sah_block_size");
  expect_rejected("min_leaf=0", "min_leaf");
  expect_rejected("min_leaf=33", "min_leaf");
  expect_rejected("max_leaf=33", "max_leaf");
  expect_rejected("int_cost=0", "int_cost");
  expect_rejected("trav_cost=-1", "trav_cost");
  expect_rejected("trav_cost=21", "trav_cost");
  expect_rejected("cost_ratio=100", "cost_ratio");
  expect_rejected("cost_ratio=2,int_cost=1", "either");
  expect_rejected("static=maybe", "static");
  expect_rejected("branching=4x", "integer");
  expect_rejected("branching", "malformed");
}

TEST(BvhConfig, FactoryMakesTunedBackend) {
  auto accel = make_accel("tuned", "branching=4,compact=1");
  EXPECT_EQ(accel->name(), "tuned");
  EXPECT_NE(accel->describe().find("branching=4"), std::string::npos);
  EXPECT_THROW(make_accel("tuned", "branching=5"), std::invalid_argument);
}

}  // namespace
}  // namespace tuneray
