// Build time of the tuned BVH against Embree's native build at the same quality, measured side
// by side: the two builds alternate (tuned, native, tuned, native, ...) so that load from other
// jobs on the machine hits both alike, and each side reports the median of its repeats.
#pragma once

#include <vector>

#include "accel/accel.h"
#include "accel/bvh_config.h"
#include "accel/embree_native.h"
#include "accel/tuned_bvh.h"

namespace tuneray {

// The native options whose build corresponds to `config`: the same build quality (low: Morton,
// medium: binned SAH, high: SAH with spatial splits); the other native options keep their
// defaults (Embree's default, non-robust, non-compact, static scene).
NativeOptions native_options_for(const BvhConfig& config);

struct BuildComparison {
  std::vector<double> tuned_ms;   // one per repeat, in the order measured
  std::vector<double> native_ms;  // idem, each taken right after the tuned build of its repeat
  double tuned_median_ms = 0;
  double native_median_ms = 0;
  double ratio = 0;  // tuned_median_ms / native_median_ms (0 when native took no time)
  BuildStats tuned;  // statistics of the last tuned build (build_ms: the median)
};

// Builds `geometry` once with each backend untimed (warm-up: first-touch of memory, the tuned
// accelerator's cached primitive boxes), then `repeats` (>= 1) timed pairs, interleaved. `tuned`
// keeps its configuration; `native` is rebuilt with native_options_for(tuned.config()).
// Throws BuildError when either build is refused.
BuildComparison compare_build_times(const GeometryView& geometry, TunedBvhAccel& tuned,
                                    EmbreeNativeAccel& native, int repeats);

}  // namespace tuneray
