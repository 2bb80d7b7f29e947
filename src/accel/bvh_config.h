// The 11 build parameters of the tuned BVH (DESIGN §3), defaults = Embree's recommended
// rtcDefaultBuildArguments, and our switches (static, compact, robust off; collapse on). A plain
// struct so the tuner can fill it directly.
#pragma once

#include <string>

namespace tuneray {

enum class BvhQuality { kLow, kMedium, kHigh };  // Morton, binned SAH, SAH + spatial splits

const char* to_string(BvhQuality quality);

struct BvhConfig {
  BvhQuality quality = BvhQuality::kMedium;
  int branching = 2;       // 2, 4 or 8: children per node, also the SIMD width of the box test
  int max_depth = 32;      // 8..64
  int sah_block_size = 1;  // 1, 2, 4, 8, 16
  int min_leaf = 1;        // 1..32 (Morton uses it as its leaf size)
  int max_leaf = 32;       // 1..32
  // Embree only uses the ratio trav_cost / int_cost; both are reported.
  float trav_cost = 1.0f;  // (0, 20]
  float int_cost = 1.0f;   // (0, 20]; 0 aborts Embree 3.13, hence the open lower bound
  bool is_static = false;  // true: nodes and leaves re-laid out depth-first in one allocation
  bool compact = false;    // true: quantized child boxes + triangle indices
  bool robust = false;     // true: watertight triangle test + conservative box test
  // true: a branching-2 or -4 tree is collapsed into 8-wide nodes after the build
  // (accel/bvh_collapse.h); no effect at branching 8.
  bool collapse = true;
  // true: the collapse chooses each wide node's children by an SAH-optimal plan instead of the
  // greedy rule (accel/bvh_collapse_plan.h); no effect without a collapse.
  bool optimal_collapse = false;
  // true: a branching-2 tree is optimised by moving subtrees where they lower its SAH cost
  // before it is collapsed (accel/bvh_reinsert.h); no effect at branching 4 or 8.
  bool reinsert = false;
  // In [0, 1]: how much the passes after the build (reinsertion, collapse) price a box by the
  // share of a view's sampled rays through it instead of by its area (accel/ray_sample.h). Takes
  // effect only where the accelerator holds a ray sample (TunedBvhAccel::set_ray_sample) and the
  // reinsertion or the SAH-optimal collapse runs (a greedy collapse after a reinsertion then
  // uses it too); 0 prices by area alone.
  float ray_weight = 0.0f;

  static constexpr int kCollapsedWidth = 8;
  // Whether the build's tree is collapsed (collapse on and fewer than 8 children a node).
  bool collapses() const { return collapse && branching < kCollapsedWidth; }
  // Whether that collapse follows the SAH-optimal plan.
  bool collapses_optimally() const { return optimal_collapse && collapses(); }
  // Whether the build's tree is reinserted (reinsert on and a binary build).
  bool reinserts() const { return reinsert && branching == 2; }

  float cost_ratio() const { return trav_cost / int_cost; }
  // Sets trav_cost = ratio, int_cost = 1; the ratio is clamped to [1/20, 20] so both costs stay
  // in (0, 20]. This is the single real the tuner sees (log-scaled on its side).
  void set_cost_ratio(float ratio);

  // Throws std::invalid_argument naming the parameter and its valid range. min_leaf > max_leaf
  // is repaired by lowering min_leaf to max_leaf (max_leaf is the bound Embree enforces); the
  // returned string describes the repair (empty if none).
  std::string validate();

  // `quality=medium,branching=2,max_depth=32,...` with all 11 parameters and the switches
  // (ray_weight only when not 0); parses back.
  std::string to_string() const;

  bool operator==(const BvhConfig&) const = default;
};

// Parses any subset of the parameters from `key=value,...` (keys: quality, branching, max_depth,
// sah_block_size, min_leaf, max_leaf, trav_cost, int_cost, cost_ratio, static, compact, robust,
// collapse, optimal_collapse, reinsert, ray_weight)
// on top of the defaults, then validates. Throws std::invalid_argument listing the valid ranges.
BvhConfig parse_bvh_config(const std::string& text);

// The valid ranges, one line per parameter (used in error messages and --help).
std::string bvh_config_ranges();

}  // namespace tuneray
