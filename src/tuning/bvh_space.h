// The 11 BVH build parameters as a tuner search space, and the mapping between the tuner's
// Config and the accelerator's BvhConfig.
#pragma once

#include "accel/bvh_config.h"
#include "tuner/config.h"
#include "tuner/space.h"

namespace tuneray {

// quality {low, medium, high}; branching {2, 4, 8}; max_depth 8..64; sah_block_size
// {1, 2, 4, 8, 16}; min_leaf 1..8; max_leaf 1..32; cost_ratio = trav/int cost in [1/20, 20]
// (log-scaled); static, compact, robust. Defaults are Embree's recommended ones.
// Morton (quality=low) ignores the SAH block size, the cost ratio and max_leaf (it uses
// min_leaf as its leaf size): they are inactive there, so the search does not spend
// measurements on them. Constraint: min_leaf <= max_leaf.
tuner::Space make_bvh_space();

BvhConfig to_bvh_config(const tuner::Config& config);
// The tuner's configuration for a BvhConfig (conditions applied).
tuner::Config to_tuner_config(const tuner::Space& space, const BvhConfig& bvh);

}  // namespace tuneray
