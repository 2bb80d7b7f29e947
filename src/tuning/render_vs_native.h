// A configuration against native Embree at the level that matters, a rendered frame: the same
// scene, camera, spp and scheduler, frames of the two interleaved (tuning/interleaved_ratios.h),
// repeated until the speedup's 95 % confidence interval is within ±3 % or a cap is reached. Rays
// per second on fixed ray sets (`bench traversal`'s table) leave out what a frame adds around
// the traversal (shading, shadow rays, wave compaction) and how the tree's shape meets the
// renderer's rays, so the table alone cannot say whether a configuration wins in the render.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "render/render_settings.h"
#include "scene/scene.h"
#include "tuning/accel_choice.h"

namespace tuneray {

// Defaults are `tune`'s, so that a database it wrote is found under the same tuning key.
struct RenderVsNativeOptions {
  int width = 320, height = 180;
  uint32_t spp = 1;
  int max_bounces = 3;
  int repeats = 6;       // at least this many timed frames of each, after one untimed frame each
  int max_repeats = 30;  // the cap (>= repeats)
  double target_half_width = 0.03;  // of the speedup's 95 % confidence interval
  bool wavefront = QualityOptions{}.wavefront;
  uint64_t seed = 1;
};

struct RenderVsNative {
  std::string config;  // the configuration compared (AccelChoice text)
  // Render time of each timed frame, in order; entry k of both lists is round k of the pairs.
  std::vector<double> native_ms, chosen_ms;
  double native_median_ms = 0, chosen_median_ms = 0;
  double native_build_ms = 0, chosen_build_ms = 0;
  // native / chosen: the median over rounds of the paired ratios, > 1 when the configuration
  // renders faster than native Embree; its distribution-free 95 % interval (none below 6 rounds,
  // so fewer never stop the rounds early).
  double paired_speedup = 0, speedup_low = 0, speedup_high = 0;
  bool converged = false;  // the interval reached the target before the cap
  double speedup() const { return paired_speedup; }
};

// Native Embree is built as `render --accel native` builds it (medium quality). Throws
// std::invalid_argument for bad options and std::runtime_error when `chosen` is refused.
RenderVsNative render_vs_native(const Scene& scene, const CameraDesc& camera,
                                const AccelChoice& chosen, const RenderVsNativeOptions& options);

struct DatabaseBest {
  AccelChoice choice;
  std::string tuning_key;  // where it was found
};

// The best configuration a `tune` database holds for `scene` seen from `camera`: the tuner's
// best for the camera's state (its best measured configuration if that state was tuned, else
// the prediction from the states that were), under the key `tune --objective render` uses for
// these options (backend space first, then the tuned-only one). nullopt when the database holds
// neither key for this machine; std::runtime_error when the file does not exist.
std::optional<DatabaseBest> best_in_database(const std::string& db_path, const Scene& scene,
                                             const CameraDesc& camera,
                                             const RenderVsNativeOptions& options);

}  // namespace tuneray
