// `tuneray tune`: the renderer tuning its BVH online along a camera path. For each camera
// position: compute the indicators, ask the tuner, rebuild the BVH if the configuration changed,
// render, report the cost. Everything goes to the tuning database, so a second run on the same
// database starts with trained predictors. The search space holds the backend (tuned BVH or
// native Embree) unless told otherwise, and every camera ends with the chosen configuration
// measured against the default one and against native Embree in the same interleaved repeats.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "tuner/space.h"
#include "tuning/frame_bench.h"
#include "tuning/interleaved_ratios.h"

namespace tuneray {

struct TuneOptions {
  std::string scene = "cornell";
  std::string scenes_dir;
  Objective objective = Objective::kRender;
  std::string db_path = "tuning.db";
  double epsilon = 0.1;
  std::string predictor = "both";  // nn | rbf | both
  int iterations = 80;             // frames per camera position
  int cameras = 10;                // positions sampled along the path
  int camera_path = 0;             // which path of the scene (automatic when it has none)
  uint32_t spp = 1;
  int width = 320, height = 180;
  int max_bounces = 3;
  uint64_t seed = 1;
  // After each camera's search, default, native and chosen are measured in interleaved rounds
  // (tuning/interleaved_ratios.h): at least baseline_repeats (and 2) rounds, then until the 95 %
  // interval of every ratio between them is within ±compare_target, at most compare_max_rounds.
  int baseline_repeats = 3;
  // Before that, the search's `finalists` best configurations (tuner::HybridTuner::finalists)
  // and native Embree (when in the space) race in `race_rounds` interleaved rounds at the same
  // camera, and the fastest by median is chosen: the best of 40 noisy frames is biased towards a
  // lucky one, and a race of a few is cheap. 0 finalists: the tuner's best, unraced.
  int finalists = 3;
  int race_rounds = 4;
  int compare_max_rounds = 30;
  double compare_target = 0.03;
  // The scheduler frames are measured on (with work_sizes: the one the search starts from). The
  // renderer's default, since the speed that matters is the one users get.
  bool wavefront = QualityOptions{}.wavefront;
  // Native Embree as a choice of the search (make_backend_space); false: the tuned BVH only.
  bool native_in_space = true;
  // Also tune the scheduler and its work size (tuning/render_space.h), under another tuning key.
  bool work_sizes = false;
  bool progress = true;
};

struct CameraTuneResult {
  int camera = 0;
  std::string mode;  // "search" or "exploit"
  int frames = 0;
  // Costs over the same interleaved rounds, in the units of the default's median
  // (EvalComparison::cost_ms); a configuration that is two of these is measured once and given
  // to both.
  double default_ms = 0;  // the default configuration (Embree's recommended, tuned BVH)
  double chosen_ms = 0;   // the configuration the tuner settled on
  double native_ms = 0;   // native Embree as `render --accel native` builds it
  // speedup() and vs_native(): medians of the per-round ratios, each with its 95 % interval
  // (exactly 1 for a configuration and itself). Medians are not transitive, so native_ms /
  // chosen_ms can differ from vs_native() by the noise of the rounds, and even fall outside its
  // interval; the paired ratio is the estimate.
  double speedup_ratio = 0, speedup_low = 0, speedup_high = 0;
  double vs_native_ratio = 0, vs_native_low = 0, vs_native_high = 0;
  int compare_rounds = 0;
  bool compare_within_target = false;  // every interval within ±compare_target before the cap
  double accumulated_ms = 0;           // sum of the costs of all search frames at this camera
  // The race between the finalists (TuneOptions::finalists): how many distinct configurations
  // ran, its frames (untimed first frames included), and whether it chose another
  // configuration than the tuner's best.
  int race_candidates = 0;
  int race_frames = 0;
  bool race_changed_choice = false;
  std::string config;   // chosen configuration (backend and BVH, then work sizes if tuned)
  std::string backend;  // of the chosen configuration: "tuned" or "native"
  // "default" or "native" when the tuner's choice measured slower than that yardstick in the
  // comparison (keep_after_comparison) and the yardstick is kept instead; then `rejected` is
  // the tuner's choice and `rejected_vs_native` / `rejected_speedup` what it measured.
  std::string fallback;
  std::string rejected;
  double rejected_vs_native = 0, rejected_speedup = 0;
  bool converged = false;
  double speedup() const { return speedup_ratio; }
  double vs_native() const { return vs_native_ratio; }
};

struct TuneReport {
  std::vector<CameraTuneResult> cameras;
  int failed_builds = 0;
};

struct TuneProgress {
  int camera = 0, frame = 0;  // of this frame
  int frames_done = 0, frames_total = 0;
  double best_speedup = 0;  // default cost (one frame) / best cost seen so far at this camera
};

// The database namespace of a session: costs are only comparable at the same objective, image
// size, spp, path length, scheduler and search space, so samples of the space with the backend
// or with work sizes are stored apart from BVH-only ones, and wavefront ones apart from tile
// ones. The BVH-only space on tiles keeps the key it always had, so older databases stay valid.
std::string tuning_key(const TuneOptions& options);

// The search space of a session (make_backend_space or make_bvh_space, with work sizes when
// asked for), its defaults from `settings`.
tuner::Space make_tune_space(const TuneOptions& options, const RenderSettings& settings);

// Who races at a camera: the tuner's best (first, so that a win by anyone else "changes the
// choice"), its other finalists, and always both yardsticks, native Embree (medium, when in the
// space) and the default configuration, even when a variant of native (quality=low) is a finalist:
// otherwise a race among variants can choose one slower than either yardstick, and the cameras
// that exploit that choice inherit it (lost-empire: native low at 0.91-0.96 of native medium on
// five cameras, native chosen on three where the default was 1.08x faster). The search seeds
// (tuning_seeds) race too, after the finalists: a search measures each seed once, in its first
// simplex, and one unlucky frame drops a seed that is faster at the median (conference: the
// reinserted binary tree, 1.09x native over 12 interleaved rounds, measured once at 0.8x of the
// search's best and never again), and a camera that exploits a prediction measures no seed at
// all. The race drops duplicates.
std::vector<tuner::Config> race_entrants(const tuner::Space& space, const tuner::Config& best,
                                         const std::vector<tuner::Config>& finalists,
                                         bool native_in_space,
                                         const std::vector<tuner::Config>& seeds = {});

// What a camera keeps after the comparison, given the chosen configuration's ratios
// (`speedup`: default cost / chosen cost; `vs_native`: native cost / chosen cost, each a median
// with its 95 % interval) and `native_over_default` (native cost / default cost). The choice
// gives way when its whole interval against the default lies below 1, or (when native is in the
// space) when its median against native does: native is what the user would use instead, so a
// tuned tree is kept only where it measured at least as fast. Then the faster of the allowed
// yardsticks by median is kept, so that tuning never ends slower than native or measurably slower
// than what it started from.
enum class KeepAfterComparison { kChosen, kDefault, kNative };
KeepAfterComparison keep_after_comparison(const RatioInterval& speedup,
                                          const RatioInterval& vs_native,
                                          const RatioInterval& native_over_default,
                                          bool native_in_space);

// Runs the loop; `log` receives one line per camera, `on_frame` is called after every frame
// (both may be empty).
TuneReport run_tune_session(const TuneOptions& options,
                            const std::function<void(const std::string&)>& log = {},
                            const std::function<void(const TuneProgress&)>& on_frame = {});

}  // namespace tuneray
