// The renderer's BVH parameter space (DESIGN §3), used by several tests as a realistic space.
#pragma once

#include "tuner/space.h"

namespace tuneray::tuner::testing {

inline Space bvh_space() {
  Space space;
  space.add_enum("quality", {"low", "medium", "high"}, "medium")
      .add_int_set("branching", {2, 4, 8}, 2)
      .add_int("max_depth", 8, 64, 32)
      .add_int_set("sah_block_size", {1, 2, 4, 8, 16}, 1)
      .add_int("min_leaf", 1, 8, 1)
      .add_int("max_leaf", 1, 32, 32)
      .add_real("cost_ratio", 0.05, 20.0, 1.0, Scale::kLog)
      .add_bool("static", false)
      .add_bool("compact", false)
      .add_bool("robust", false);
  space.add_constraint("min_leaf <= max_leaf", [](const Config& c) {
    return c.get_int("min_leaf") <= c.get_int("max_leaf");
  });
  space.add_condition("sah_block_size", Space::when_enum_not("quality", {"low"}));
  space.add_condition("cost_ratio", Space::when_enum_not("quality", {"low"}));
  return space;
}

}  // namespace tuneray::tuner::testing
