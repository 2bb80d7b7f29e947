#include "tuning/bvh_space.h"

#include <stdexcept>
#include <string>

namespace tuneray {

namespace {

using Predicate = tuner::Space::Predicate;

// The 10 BVH parameters. `tuned` (empty in the BVH-only space) tells when the tuned backend is
// in use; every BVH parameter is inactive otherwise. The BVH-only space keeps its exact
// description (conditions are part of it), so databases tuned before the backend choice existed
// stay valid.
// `min_leaf_max` is 8 in the BVH-only space (its databases' description) and 32 in the backend
// space: Morton trees with leaves of 10 to 30 triangles are the fastest to build and render at
// once under the `total` objective (docs/results.md, thirty-second session).
void add_bvh_params(tuner::Space& space, const Predicate& tuned, int min_leaf_max) {
  space.add_enum("quality", {"low", "medium", "high"}, "medium")
      .add_int_set("branching", {2, 4, 8}, 2)
      .add_int("max_depth", 8, 64, 32)
      .add_int_set("sah_block_size", {1, 2, 4, 8, 16}, 1)
      .add_int("min_leaf", 1, min_leaf_max, 1)
      .add_int("max_leaf", 1, 32, 32)
      .add_real("cost_ratio", 1.0 / 20.0, 20.0, 1.0, tuner::Scale::kLog)
      .add_bool("static", false)
      .add_bool("compact", false)
      .add_bool("robust", false);
  if (tuned)
    for (const char* name :
         {"quality", "branching", "max_depth", "min_leaf", "static", "compact", "robust"})
      space.add_condition(name, tuned);
  // A Space holds one condition per parameter: the SAH ones need both.
  Predicate sah = tuner::Space::when_enum_not("quality", {"low"});
  Predicate sah_only =
      !tuned ? sah : Predicate([tuned, sah](const tuner::Config& c) { return tuned(c) && sah(c); });
  space.add_condition("sah_block_size", sah_only).add_condition("cost_ratio", sah_only);
  // max_leaf shapes Morton trees too: within 8 levels of max_depth Embree's Morton builder stops
  // splitting at Morton bits and cuts balanced subtrees down to leaves of up to max_leaf
  // primitives (the fastest build + render trees of the paper runs are such trees). The BVH-only
  // space keeps a condition that always holds: its description, which marks conditional
  // parameters, is what its databases hold.
  space.add_condition("max_leaf",
                      tuned ? tuned : Predicate([](const tuner::Config&) { return true; }));
  space.add_constraint("min_leaf <= max_leaf", [](const tuner::Config& c) {
    return c.get_int("min_leaf") <= c.get_int("max_leaf");
  });
}

bool has_param(const tuner::Config& c, const std::string& name) {
  for (const tuner::ParamSpec& p : c.params())
    if (p.name == name) return true;
  return false;
}

BvhQuality quality_of(const std::string& label) {
  return label == "low" ? BvhQuality::kLow
                        : (label == "high" ? BvhQuality::kHigh : BvhQuality::kMedium);
}

}  // namespace

tuner::Space make_bvh_space() {
  tuner::Space space;
  add_bvh_params(space, {}, 8);
  return space;
}

tuner::Space make_backend_space() {
  tuner::Space space;
  space.add_enum("backend", {"tuned", "native"}, "tuned")
      .add_enum("native_quality", {"low", "medium", "high"}, "medium");
  space.add_condition("native_quality", tuner::Space::when_enum_not("backend", {"tuned"}));
  const Predicate tuned = tuner::Space::when_enum_not("backend", {"native"});
  add_bvh_params(space, tuned, 32);
  space.add_bool("collapse", true).add_condition("collapse", [tuned](const tuner::Config& c) {
    return tuned(c) && c.get_int("branching") < BvhConfig::kCollapsedWidth;
  });
  space.add_bool("reinsert", false).add_condition("reinsert", [tuned](const tuner::Config& c) {
    return tuned(c) && c.get_int("branching") == 2;
  });
  space.add_bool("optimal_collapse", false)
      .add_condition("optimal_collapse", [tuned](const tuner::Config& c) {
        return tuned(c) && c.get_int("branching") < BvhConfig::kCollapsedWidth &&
               c.get_bool("collapse");
      });
  return space;
}

BvhConfig to_bvh_config(const tuner::Config& c) {
  BvhConfig b;
  b.quality = quality_of(c.get_enum("quality"));
  b.branching = static_cast<int>(c.get_int("branching"));
  b.max_depth = static_cast<int>(c.get_int("max_depth"));
  b.sah_block_size = static_cast<int>(c.get_int("sah_block_size"));
  b.min_leaf = static_cast<int>(c.get_int("min_leaf"));
  b.max_leaf = static_cast<int>(c.get_int("max_leaf"));
  b.set_cost_ratio(static_cast<float>(c.get_real("cost_ratio")));
  b.is_static = c.get_bool("static");
  b.compact = c.get_bool("compact");
  b.robust = c.get_bool("robust");
  // The BVH-only space predates the collapse: its 2- and 4-wide trees were traversed as built
  // (at branching 8 the switch means nothing and keeps its default).
  b.collapse =
      has_param(c, "collapse") ? c.get_bool("collapse") : b.branching >= BvhConfig::kCollapsedWidth;
  b.reinsert = has_param(c, "reinsert") && c.get_bool("reinsert");
  b.optimal_collapse = has_param(c, "optimal_collapse") && c.get_bool("optimal_collapse");
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
  if (has_param(c, "collapse"))
    c.set_bool("collapse", b.collapse);
  else if (b.collapses())
    throw std::invalid_argument("collapse=1 is not part of this search space");
  if (has_param(c, "reinsert"))
    c.set_bool("reinsert", b.reinsert);
  else if (b.reinserts())
    throw std::invalid_argument("reinsert=1 is not part of this search space");
  if (has_param(c, "optimal_collapse"))
    c.set_bool("optimal_collapse", b.optimal_collapse);
  else if (b.collapses_optimally())
    throw std::invalid_argument("optimal_collapse=1 is not part of this search space");
  if (b.ray_weight != 0.0f)  // it prices boxes by a view's rays, which no search space holds
    throw std::invalid_argument("ray_weight is not part of this search space");
  if (has_param(c, "backend")) c.set_enum("backend", "tuned");
  return space.canonical(c);
}

AccelChoice to_accel_choice(const tuner::Config& c) {
  if (has_param(c, "backend") && c.get_enum("backend") == "native")
    return AccelChoice::native(quality_of(c.get_enum("native_quality")));
  return AccelChoice::tuned(to_bvh_config(c));
}

tuner::Config to_tuner_config(const tuner::Space& space, const AccelChoice& choice) {
  tuner::Config c = to_tuner_config(space, choice.bvh);
  if (!choice.is_native()) return c;
  if (!has_param(c, "backend"))
    throw std::invalid_argument("the native backend is not part of this search space");
  c.set_enum("backend", "native").set_enum("native_quality", to_string(choice.native_quality));
  return space.canonical(c);
}

BvhConfig embree_bvh8_config(BvhQuality quality) {
  BvhConfig b;
  b.quality = quality;
  b.branching = 8;
  b.sah_block_size = 4;
  b.min_leaf = 4;
  b.max_leaf = 28;  // 7 blocks of 4: Embree's largest leaf in a BVH8 reference
  return b;
}

std::vector<tuner::Config> tuning_seeds(const tuner::Space& space, bool build_time_counts) {
  std::vector<tuner::Config> seeds = {to_tuner_config(space, embree_bvh8_config())};
  if (build_time_counts) return seeds;
  seeds.push_back(to_tuner_config(space, embree_bvh8_config(BvhQuality::kHigh)));
  // The same leaves from a binary build whose subtrees are reinserted, collapsed by the
  // SAH-optimal plan (spaces with the switches), and laid out depth first in one block
  // (static: faster camera and shadow rays on the shared scenes, docs/bvh.md).
  const tuner::Config defaults = space.default_config();
  if (has_param(defaults, "reinsert")) {
    BvhConfig reinserted = embree_bvh8_config();
    reinserted.branching = 2;
    reinserted.reinsert = true;
    reinserted.optimal_collapse = has_param(defaults, "optimal_collapse");
    reinserted.is_static = true;
    // The same from the spatial-split build at Embree's pricing: inside lost-empire's walls its
    // trees beat both at some cameras (tune, render level 1.015-1.024 -> 1.025-1.045 over native,
    // forty-sixth session); the 0.8 pricing below measured level there.
    BvhConfig split = reinserted;
    split.quality = BvhQuality::kHigh;
    // A pack test priced at 0.8 of a node visit (cost_ratio 1.25): our leaves test two packs per
    // AVX2 pass, so a little larger leaves pay off. A frame's rays against native Embree's rose
    // by about 5 % on the bunny's and lost-empire's open views and stayed level elsewhere
    // (batch_replay, forty-seventh session, docs/bvh.md); whole frames moved within the noise.
    reinserted.set_cost_ratio(kReinsertedSeedCostRatio);
    seeds.push_back(to_tuner_config(space, reinserted));
    seeds.push_back(to_tuner_config(space, split));
  }
  return seeds;
}

}  // namespace tuneray
