#include "tuning/render_vs_native.h"

#include <filesystem>
#include <stdexcept>

#include "scene/indicators.h"
#include "tuner/hardware_signature.h"
#include "tuner/hybrid_tuner.h"
#include "tuner/tuning_db.h"
#include "tuning/bvh_space.h"
#include "tuning/frame_bench.h"
#include "tuning/interleaved_ratios.h"
#include "tuning/stats.h"
#include "tuning/tune_session.h"
#include "tuning/tuner_state.h"

namespace tuneray {

namespace {

RenderSettings settings_of(const RenderVsNativeOptions& o) {
  return frame_settings(o.width, o.height, o.max_bounces, o.seed, o.wavefront);
}

}  // namespace

RenderVsNative render_vs_native(const Scene& scene, const CameraDesc& camera,
                                const AccelChoice& chosen, const RenderVsNativeOptions& o) {
  if (o.repeats < 2 || o.max_repeats < o.repeats || !(o.target_half_width > 0) || o.spp < 1 ||
      o.width < 1 || o.height < 1 || o.max_bounces < 1)
    throw std::invalid_argument(
        "render vs native: need 2 <= repeats <= max_repeats, a positive target, and spp, size "
        "and bounces >= 1");
  FrameBench bench(scene, settings_of(o), o.spp, Objective::kRender);
  const AccelChoice native = AccelChoice::native();
  RenderVsNative r;
  r.config = chosen.to_string();
  // One untimed frame each builds both trees (FrameBench keeps them) and warms the caches.
  r.native_build_ms = bench.run(native, camera).build_ms;
  FrameCost first = bench.run(chosen, camera);
  if (!first.ok) throw std::runtime_error("render vs native: " + r.config + ": " + first.error);
  r.chosen_build_ms = first.build_ms;
  InterleavedOptions interleaving;
  interleaving.min_rounds = o.repeats;
  interleaving.max_rounds = o.max_repeats;
  interleaving.target_half_width = o.target_half_width;
  // eval's and tune's estimator: one frame slowed by the machine moves neither the speedup nor
  // its interval (tuning/median_interval.h).
  interleaving.estimator = RatioEstimator::kMedian;
  constexpr int kNative = 0, kChosen = 1;
  const InterleavedResult paired = measure_interleaved(
      2, kChosen,
      [&](int candidate) {
        const double ms = bench.run(candidate == kNative ? native : chosen, camera).render_ms;
        (candidate == kNative ? r.native_ms : r.chosen_ms).push_back(ms);
        return ms;
      },
      interleaving);
  const RatioInterval& speedup = paired.ratios[kNative];
  r.paired_speedup = speedup.ratio;
  r.speedup_low = speedup.low;
  r.speedup_high = speedup.high;
  r.converged = paired.converged;
  r.native_median_ms = median(r.native_ms);
  r.chosen_median_ms = median(r.chosen_ms);
  return r;
}

std::optional<DatabaseBest> best_in_database(const std::string& db_path, const Scene& scene,
                                             const CameraDesc& camera,
                                             const RenderVsNativeOptions& o) {
  // TuningDb creates a missing file: a mistyped path must not pass for an empty database.
  if (!std::filesystem::exists(db_path))
    throw std::runtime_error("tuning database '" + db_path + "' does not exist");
  TuneOptions tune;
  tune.objective = Objective::kRender;
  tune.width = o.width;
  tune.height = o.height;
  tune.spp = o.spp;
  tune.max_bounces = o.max_bounces;
  tune.wavefront = o.wavefront;
  const tuner::State state =
      to_tuner_state(compute_indicators(compute_scene_indicators(scene), camera));
  for (bool native_in_space : {true, false}) {
    tune.native_in_space = native_in_space;
    const std::string key = tuning_key(tune);
    {
      tuner::TuningDb db(db_path);
      if (!db.find_signature(key, tuner::hardware_signature())) continue;
    }
    tuner::TunerOptions options;
    options.db_path = db_path;
    options.tuning_key = key;
    options.epsilon = 0;
    tuner::HybridTuner tuner(make_tune_space(tune, settings_of(o)), make_indicator_schema(),
                             options);
    return DatabaseBest{to_accel_choice(tuner.best(state)), key};
  }
  return std::nullopt;
}

}  // namespace tuneray
