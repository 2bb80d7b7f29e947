#include "tuning/tune_session.h"

#include <fmt/core.h>

#include <algorithm>
#include <stdexcept>
#include <utility>

#include "scene/camera_spline.h"
#include "scene/indicators.h"
#include "scene/load.h"
#include "tuner/hybrid_tuner.h"
#include "tuning/bvh_space.h"
#include "tuning/eval_comparison.h"
#include "tuning/render_space.h"
#include "tuning/stats.h"
#include "tuning/tuner_state.h"

namespace tuneray {

tuner::PredictorKind parse_predictor(const std::string& text) {
  if (text == "nn") return tuner::PredictorKind::kNearestNeighbour;
  if (text == "rbf") return tuner::PredictorKind::kRbf;
  if (text == "both") return tuner::PredictorKind::kBoth;
  throw std::invalid_argument("bad predictor '" + text + "': expected nn, rbf or both");
}

std::string tuning_key(const TuneOptions& o) {
  std::string key = fmt::format("{}{}/{}/{}x{}/{}spp/{}b", o.native_in_space ? "backend+" : "",
                                o.work_sizes ? "bvh+work" : "bvh", to_string(o.objective), o.width,
                                o.height, o.spp, o.max_bounces);
  // Tiles were the only scheduler before the key named it: no suffix means tiles.
  return o.wavefront ? key + "/wavefront" : key;
}

tuner::Space make_tune_space(const TuneOptions& o, const RenderSettings& settings) {
  tuner::Space base = o.native_in_space ? make_backend_space() : make_bvh_space();
  return o.work_sizes ? make_render_space(settings, std::move(base)) : base;
}

std::vector<tuner::Config> race_entrants(const tuner::Space& space, const tuner::Config& best,
                                         const std::vector<tuner::Config>& finalists,
                                         bool native_in_space,
                                         const std::vector<tuner::Config>& seeds) {
  std::vector<tuner::Config> entrants{best};
  entrants.insert(entrants.end(), finalists.begin(), finalists.end());
  entrants.insert(entrants.end(), seeds.begin(), seeds.end());
  if (native_in_space) entrants.push_back(to_tuner_config(space, AccelChoice::native()));
  entrants.push_back(space.default_config());
  return entrants;
}

KeepAfterComparison keep_after_comparison(const RatioInterval& speedup,
                                          const RatioInterval& vs_native,
                                          const RatioInterval& native_over_default,
                                          bool native_in_space) {
  const bool slower_than_default = speedup.high < 1.0;
  // Native is what the user would render with instead, so the tuned backend has to show that it
  // wins: measured slower by its median, the choice gives way even where the interval still
  // reaches 1 (bmw-m6, forty-fifth session: four cameras kept trees at 0.977-0.992 of native).
  const bool slower_than_native = native_in_space && vs_native.ratio < 1.0;
  if (!slower_than_default && !slower_than_native) return KeepAfterComparison::kChosen;
  if (native_in_space && native_over_default.ratio < 1.0) return KeepAfterComparison::kNative;
  return KeepAfterComparison::kDefault;
}

TuneReport run_tune_session(const TuneOptions& o,
                            const std::function<void(const std::string&)>& log,
                            const std::function<void(const TuneProgress&)>& on_frame) {
  if (o.iterations < 1 || o.cameras < 1 || o.spp < 1 || o.baseline_repeats < 1)
    throw std::invalid_argument("iterations, cameras, spp and repeats must be >= 1");
  if (!(o.epsilon >= 0 && o.epsilon <= 1)) throw std::invalid_argument("epsilon must be in [0, 1]");
  LoadOptions load_options;
  load_options.scenes_dir = o.scenes_dir;
  Scene scene = load_scene(o.scene, load_options);
  std::vector<CameraDesc> cameras = cameras_along_path(scene, o.camera_path, o.cameras);
  SceneIndicators scene_indicators = compute_scene_indicators(scene);

  tuner::TunerOptions options;
  options.epsilon = o.epsilon;
  options.predictor = parse_predictor(o.predictor);
  options.seed = o.seed;
  options.search.max_iterations = o.iterations;
  options.db_path = o.db_path;
  options.tuning_key = tuning_key(o);

  const RenderSettings settings =
      frame_settings(o.width, o.height, o.max_bounces, o.seed, o.wavefront);
  const tuner::Space space = make_tune_space(o, settings);
  options.search_seeds = tuning_seeds(space, o.objective == Objective::kTotal);
  tuner::HybridTuner tuner(space, make_indicator_schema(), options);
  // Without --work-sizes every frame keeps the settings' scheduler and sizes.
  auto work_of = [&](const tuner::Config& c) {
    return o.work_sizes ? to_work_sizes(c) : WorkSizes::of(settings);
  };

  FrameBench bench(scene, settings, o.spp, o.objective);
  const AccelChoice default_choice = to_accel_choice(space.default_config());
  const AccelChoice native_choice = AccelChoice::native();
  const WorkSizes default_work = work_of(space.default_config());
  // Warm-up: threads, caches, page faults, both backends' first trees (not counted).
  bench.run(native_choice, default_work, cameras[0]);
  bench.run(default_choice, default_work, cameras[0]);

  TuneReport report;
  TuneProgress progress;
  progress.frames_total = o.iterations * static_cast<int>(cameras.size());
  // The yardsticks and the chosen configuration in one comparison, eval's protocol
  // (eval_comparison.h): interleaved rounds, so that a drift of the shared machine's load hits
  // all of them alike. Identical candidates (the chosen configuration may be the default or
  // native itself) are one configuration measured once: compared with itself it reports
  // exactly 1, not the machine's noise.
  using Candidate = std::pair<AccelChoice, WorkSizes>;
  InterleavedOptions compare_options;
  compare_options.min_rounds = std::max(2, o.baseline_repeats);
  compare_options.max_rounds = std::max(compare_options.min_rounds, o.compare_max_rounds);
  compare_options.target_half_width = o.compare_target;
  compare_options.every_pair = true;
  auto name_of = [](const Candidate& c) {
    return c.first.to_string() + "," + c.second.to_string();
  };
  // measure_comparison over `distinct` candidates (their names in `names`) at `camera`.
  auto measure = [&](const std::vector<std::string>& names, const std::vector<Candidate>& distinct,
                     const CameraDesc& camera, const std::string& what,
                     const InterleavedOptions& options) {
    return measure_comparison(
        names, o.objective,
        [&](size_t i) { return bench.run(distinct[i].first, distinct[i].second, camera); }, what,
        options);
  };
  // Fills the yardsticks of `r` from candidates {default, native, chosen}; returns which of
  // the three the camera keeps (keep_after_comparison) and fills `r`'s ratios for that one.
  auto compare = [&](const std::vector<Candidate>& candidates, const CameraDesc& camera,
                     CameraTuneResult& r) -> size_t {
    std::vector<std::string> names, configs;
    std::vector<Candidate> measured;
    for (const Candidate& c : candidates) {
      names.push_back(name_of(c));
      if (std::find(configs.begin(), configs.end(), names.back()) != configs.end()) continue;
      configs.push_back(names.back());
      measured.push_back(c);
    }
    const EvalComparison c = measure(configs, measured, camera,
                                     fmt::format("tune, camera {}", r.camera), compare_options);
    size_t kept = 2;
    switch (keep_after_comparison(c.ratio(names[0], names[2]), c.ratio(names[1], names[2]),
                                  c.ratio(names[1], names[0]), o.native_in_space)) {
      case KeepAfterComparison::kChosen:
        break;
      case KeepAfterComparison::kDefault:
        kept = 0;
        r.fallback = "default";
        break;
      case KeepAfterComparison::kNative:
        kept = 1;
        r.fallback = "native";
        break;
    }
    if (kept != 2) {
      r.rejected_speedup = c.ratio(names[0], names[2]).ratio;
      r.rejected_vs_native = c.ratio(names[1], names[2]).ratio;
    }
    r.default_ms = c.cost_ms(names[0]);
    r.native_ms = c.cost_ms(names[1]);
    r.chosen_ms = c.cost_ms(names[kept]);
    const RatioInterval speedup = c.ratio(names[0], names[kept]);
    const RatioInterval vs_native = c.ratio(names[1], names[kept]);
    r.speedup_ratio = speedup.ratio;
    r.speedup_low = speedup.low;
    r.speedup_high = speedup.high;
    r.vs_native_ratio = vs_native.ratio;
    r.vs_native_low = vs_native.low;
    r.vs_native_high = vs_native.high;
    r.compare_rounds = c.rounds();
    r.compare_within_target = c.within_target;
    return kept;
  };
  InterleavedOptions race_options;
  race_options.min_rounds = race_options.max_rounds = std::max(1, o.race_rounds);
  // The fastest of `finalists` (the first is the tuner's best) by their median in interleaved
  // rounds; frames and the decision go into `r`. Every timed round is reported to the tuner, as
  // every measurement is: native's frames in the race teach the predictors where it wins, so the
  // next camera's prediction is native and needs no race.
  auto race = [&](const std::vector<tuner::Config>& finalists, const CameraDesc& camera,
                  CameraTuneResult& r) -> tuner::Config {
    std::vector<std::string> names;
    std::vector<tuner::Config> distinct;
    std::vector<Candidate> candidates;
    for (const tuner::Config& c : finalists) {
      const Candidate candidate{to_accel_choice(c), work_of(c)};
      const std::string name = name_of(candidate);
      if (std::find(names.begin(), names.end(), name) != names.end()) continue;
      names.push_back(name);
      distinct.push_back(c);
      candidates.push_back(candidate);
    }
    r.race_candidates = static_cast<int>(distinct.size());
    if (distinct.size() < 2) return distinct.front();
    const EvalComparison c =
        measure(names, candidates, camera,
                fmt::format("tune's race of finalists, camera {}", r.camera), race_options);
    r.race_frames = static_cast<int>(distinct.size()) * (c.rounds() + 1);
    for (size_t i = 0; i < c.configs.size(); ++i) {
      const auto at = std::find(names.begin(), names.end(), c.configs[i]) - names.begin();
      for (double ms : c.costs[i]) tuner.report(distinct[at], ms / 1000.0, {{"race", 1.0}});
    }
    const size_t winner =
        static_cast<size_t>(std::find(names.begin(), names.end(), c.fastest()) - names.begin());
    r.race_changed_choice = winner != 0;
    return distinct[winner];
  };
  for (size_t ci = 0; ci < cameras.size(); ++ci) {
    tuner::State state = to_tuner_state(compute_indicators(scene_indicators, cameras[ci]));
    CameraTuneResult r;
    r.camera = static_cast<int>(ci);
    // One frame of the default for the progress bar's running speedup only: the yardsticks
    // are measured after the search, beside the chosen configuration.
    const double reference_ms =
        bench.run(default_choice, default_work, cameras[ci]).cost_ms(o.objective);
    double best_ms = reference_ms;
    for (int it = 0; it < o.iterations; ++it) {
      tuner::Config c = tuner.suggest(state);
      if (it == 0) r.mode = tuner.mode() == tuner::TunerMode::kSearch ? "search" : "exploit";
      FrameCost cost = bench.run(to_accel_choice(c), work_of(c), cameras[ci]);
      tuner::Extras extras = {{"build_ms", cost.build_ms}, {"render_ms", cost.render_ms}};
      if (cost.ok) {
        tuner.report(c, cost.cost_ms(o.objective) / 1000.0, extras);
        r.accumulated_ms += cost.cost_ms(o.objective);
        best_ms = std::min(best_ms, cost.cost_ms(o.objective));
      } else {
        tuner.report_failure(c, extras);
        ++report.failed_builds;
      }
      ++r.frames;
      if (on_frame) {
        progress.camera = r.camera;
        progress.frame = it;
        ++progress.frames_done;
        progress.best_speedup = best_ms > 0 ? reference_ms / best_ms : 0.0;
        on_frame(progress);
      }
    }
    tuner::Config best = tuner.best(state);
    if (o.finalists > 0) {
      const std::vector<tuner::Config> finalists =
          race_entrants(space, best, tuner.finalists(state, static_cast<size_t>(o.finalists)),
                        o.native_in_space, options.search_seeds);
      best = race(finalists, cameras[ci], r);
    }
    const Candidate chosen_candidate{to_accel_choice(best), work_of(best)};
    // The baselines are measured outside the tuner: they are yardsticks, not tuning decisions.
    // The race's rounds are not reused: the winner of a race is again biased towards its lucky
    // rounds, so its speed is measured anew.
    const std::vector<Candidate> compared{
        {default_choice, default_work}, {native_choice, default_work}, chosen_candidate};
    const size_t kept = compare(compared, cameras[ci], r);
    auto describe = [&](const Candidate& c) {
      return o.work_sizes ? c.first.to_string() + "," + c.second.to_string() : c.first.to_string();
    };
    if (kept != 2) r.rejected = describe(chosen_candidate);
    r.config = describe(compared[kept]);
    r.backend = to_string(compared[kept].first.backend);
    if (auto s = tuner.summary(state)) r.converged = s->converged;
    if (log)
      log(fmt::format(
              "camera {:>3} {:<8} default {:8.2f} ms  native {:8.2f} ms  chosen {:8.2f} ms  "
              "speedup {:5.2f} [{:.2f}, {:.2f}]  vs native {:5.2f} [{:.2f}, {:.2f}]  {} rounds  "
              "{}{}",
              r.camera, r.mode, r.default_ms, r.native_ms, r.chosen_ms, r.speedup(), r.speedup_low,
              r.speedup_high, r.vs_native(), r.vs_native_low, r.vs_native_high, r.compare_rounds,
              r.config,
              r.race_frames > 0 ? fmt::format("  (race of {}{})", r.race_candidates,
                                              r.race_changed_choice ? ", changed the choice" : "")
                                : "") +
          (r.fallback.empty()
               ? ""
               : fmt::format("  (kept {}: the tuner's {} measured {:.2f} vs native, {:.2f} over "
                             "the default)",
                             r.fallback, r.rejected, r.rejected_vs_native, r.rejected_speedup)));
    report.cameras.push_back(r);
  }
  return report;
}

}  // namespace tuneray
