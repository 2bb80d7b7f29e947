// The 11 BVH build parameters as a tuner search space, the same with the backend choice in
// front (tuned BVH or native Embree), and the mappings between the tuner's Config and the
// accelerator's BvhConfig / AccelChoice.
#pragma once

#include <vector>

#include "accel/bvh_config.h"
#include "tuner/config.h"
#include "tuner/space.h"
#include "tuning/accel_choice.h"

namespace tuneray {

// quality {low, medium, high}; branching {2, 4, 8}; max_depth 8..64; sah_block_size
// {1, 2, 4, 8, 16}; min_leaf 1..8 (1..32 in the backend space); max_leaf 1..32; cost_ratio =
// trav/int cost in [1/20, 20] (log-scaled); static, compact, robust. Defaults are Embree's
// recommended ones. Morton (quality=low) ignores the SAH block size and the cost ratio: they are
// inactive there, so the search does not spend measurements on them. It uses min_leaf as its leaf
// size, and max_leaf as the leaf size of the balanced subtrees it builds within 8 levels of
// max_depth, so both stay active. Constraint: min_leaf <= max_leaf.
tuner::Space make_bvh_space();

// backend {tuned, native} (default tuned: the study's default configuration is Embree's
// recommended build of our tree), native_quality {low, medium, high} (default medium, what
// `render --accel native` uses; active only under native), then the 10 parameters of
// make_bvh_space(), active only under tuned (so every native point is one of three
// configurations and the search reuses their samples), then collapse (default on; active under
// tuned at branching 2 and 4; the BVH-only space lacks it and means collapse=0, as its databases
// were measured), then reinsert (default off; active under tuned at branching 2; absent from the
// BVH-only space, which means reinsert=0), then optimal_collapse (default off; active where the
// tree is collapsed; absent from the BVH-only space, which means 0). The first simplex spans both
// backends, so native Embree is measured early in every search and the tuner can never settle on
// something it measured slower than native.
tuner::Space make_backend_space();

// Reads the BVH parameters of a configuration of either space (and of make_render_space()).
BvhConfig to_bvh_config(const tuner::Config& config);
// The tuner's configuration for a BvhConfig (conditions applied; tuned backend if the space has
// the choice).
tuner::Config to_tuner_config(const tuner::Space& space, const BvhConfig& bvh);

// The accelerator a configuration of either space selects (tuned when the space has no backend
// parameter).
AccelChoice to_accel_choice(const tuner::Config& config);
// The tuner's configuration for a choice (conditions applied). Throws std::invalid_argument for
// a native choice in a space without the backend parameter.
tuner::Config to_tuner_config(const tuner::Space& space, const AccelChoice& choice);

// Embree's own choice for its triangle BVH on AVX2 (bvh8.triangle4: 8 children, SAH counted in
// blocks of 4 triangles, leaves of 4 to 28 triangles, equal costs) as our tuned BVH.
BvhConfig embree_bvh8_config(BvhQuality quality = BvhQuality::kMedium);

// The search seeds of tuning (tuner::TunerOptions::search_seeds) for a space of this file or of
// make_render_space(): the tuned BVH with Embree's BVH8 settings at medium quality, and, when
// only render time counts, the same at high quality and the same leaves from a binary build with
// its subtrees reinserted, collapsed by the SAH-optimal plan and laid out in one block (static),
// at medium quality with a pack test priced below a node visit (kReinsertedSeedCostRatio) and at
// high quality at Embree's pricing (spatial splits, reinsertion and the relayout cost build time
// every frame under the `total` objective, where the search can still find them).
// Seeding puts a tree as good as native's into every first simplex; the default configuration stays
// the start point.
std::vector<tuner::Config> tuning_seeds(const tuner::Space& space, bool build_time_counts);

// cost_ratio (node visit over pack test) of the medium-quality reinserted seed.
inline constexpr float kReinsertedSeedCostRatio = 1.25f;

}  // namespace tuneray
