#include "tuning/bvh_space.h"

namespace tuneray {

tuner::Space make_bvh_space() {
  tuner::Space space;
  space.add_enum("quality", {"low", "medium", "high"}, "medium")
      .add_int_set("branching", {2, 4, 8}, 2)
      .add_int("max_depth", 8, 64, 32)
      .add_int_set("sah_block_size", {1, 2, 4, 8, 16}, 1)
      .add_int("min_leaf", 1, 8, 1)
      .add_int("max_leaf", 1, 32, 32)
      .add_real("cost_ratio", 1.0 / 20.0, 20.0, 1.0, tuner::Scale::kLog)
      .add_bool("static", false)
      .add_bool("compact", false)
      .add_bool("robust", false);
  auto sah_only = tuner::Space::when_enum_not("quality", {"low"});
  space.add_condition("sah_block_size", sah_only)
      .add_condition("max_leaf", sah_only)
      .add_condition("cost_ratio", sah_only);
  space.add_constraint("min_leaf <= max_leaf", [](const tuner::Config& c) {
    return c.get_int("min_leaf") <= c.get_int("max_leaf");
  });
  return space;
}

BvhConfig to_bvh_config(const tuner::Config& c) {
  BvhConfig b;
  const std::string& q = c.get_enum("quality");
  b.quality =
      q == "low" ? BvhQuality::kLow : (q == "high" ? BvhQuality::kHigh : BvhQuality::kMedium);
  b.branching = static_cast<int>(c.get_int("branching"));
  b.max_depth = static_cast<int>(c.get_int("max_depth"));
  b.sah_block_size = static_cast<int>(c.get_int("sah_block_size"));
  b.min_leaf = static_cast<int>(c.get_int("min_leaf"));
  b.max_leaf = static_cast<int>(c.get_int("max_leaf"));
  b.set_cost_ratio(static_cast<float>(c.get_real("cost_ratio")));
  b.is_static = c.get_bool("static");
  b.compact = c.get_bool("compact");
  b.robust = c.get_bool("robust");
  return b;
}

tuner::Config to_tuner_config(const tuner::Space& space, const BvhConfig& b) {
  tuner::Config c = space.default_config();
  c.set_enum("quality", to_string(b.quality))
      .set_int("branching", b.branching)
      .set_int("max_depth", b.max_depth)
      .set_int("sah_block_size", b.sah_block_size)
      .set_int("min_leaf", b.min_leaf)
      .set_int("max_leaf", b.max_leaf)
      .set_real("cost_ratio", b.cost_ratio())
      .set_bool("static", b.is_static)
      .set_bool("compact", b.compact)
      .set_bool("robust", b.robust);
  return space.canonical(c);
}

}  // namespace tuneray
