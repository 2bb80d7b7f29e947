// Inputs shared by the tuning tests: a BVH configuration with every parameter off its default,
// and a tune session small enough for a test (built-in Cornell box, one camera, 16x12).
#pragma once

#include <string>

#include "accel/bvh_config.h"
#include "tuning/tune_session.h"

namespace tuneray::testing {

// The default of the BVH-only space (make_bvh_space): Embree's recommended parameters, trees
// traversed as built (that space has no collapse switch).
inline BvhConfig bvh_only_defaults() {
  BvhConfig b;
  b.collapse = false;
  return b;
}

inline BvhConfig every_parameter_changed() {
  BvhConfig b;
  b.quality = BvhQuality::kHigh;
  b.branching = 8;
  b.max_depth = 40;
  b.sah_block_size = 4;
  b.min_leaf = 2;
  b.max_leaf = 12;
  b.set_cost_ratio(4.0f);
  b.is_static = true;
  b.compact = true;
  b.robust = true;
  return b;
}

// Callers set iterations, epsilon and repeats where their test depends on them.
inline TuneOptions tiny_tune_session(const std::string& db_path) {
  TuneOptions o;
  o.scene = "cornell";
  o.db_path = db_path;
  o.cameras = 1;
  o.width = 16;
  o.height = 12;
  o.compare_max_rounds = 6;  // 16x12 frames are noisy: keep the comparison's rounds few
  o.progress = false;
  return o;
}

}  // namespace tuneray::testing
