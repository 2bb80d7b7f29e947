#include "tuning/tune_session.h"

#include <fmt/core.h>

#include <algorithm>
#include <stdexcept>

#include "scene/camera_spline.h"
#include "scene/indicators.h"
#include "scene/load.h"
#include "tuner/hybrid_tuner.h"
#include "tuning/bvh_space.h"
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

std::vector<CameraDesc> camera_positions(const Scene& scene, int path_index, int count) {
  if (path_index < 0 ||
      (path_index > 0 && path_index >= static_cast<int>(scene.camera_paths.size())))
    throw std::invalid_argument("bad camera path " + std::to_string(path_index) +
                                ": the scene has " + std::to_string(scene.camera_paths.size()));
  CameraPath path =
      scene.camera_paths.empty() ? automatic_camera_path(scene) : scene.camera_paths[path_index];
  return sample_camera_path(path, count);
}

std::string tuning_key(const TuneOptions& o) {
  return fmt::format("{}/{}/{}x{}/{}spp/{}b", o.work_sizes ? "bvh+work" : "bvh",
                     to_string(o.objective), o.width, o.height, o.spp, o.max_bounces);
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
  std::vector<CameraDesc> cameras = camera_positions(scene, o.camera_path, o.cameras);
  SceneIndicators scene_indicators = compute_scene_indicators(scene);

  tuner::TunerOptions options;
  options.epsilon = o.epsilon;
  options.predictor = parse_predictor(o.predictor);
  options.seed = o.seed;
  options.search.max_iterations = o.iterations;
  options.db_path = o.db_path;
  options.tuning_key = tuning_key(o);

  RenderSettings settings;
  settings.width = o.width;
  settings.height = o.height;
  settings.max_bounces = o.max_bounces;
  settings.seed = o.seed;
  // The BVH is tuned on the tile scheduler, one ray at a time as in the study we reproduce
  // (DESIGN 6), whatever the render default: it keeps tuning keys and databases comparable.
  // --work-sizes lets the tuner choose the scheduler.
  settings.quality.wavefront = false;
  tuner::Space space = o.work_sizes ? make_render_space(settings) : make_bvh_space();
  tuner::HybridTuner tuner(space, make_indicator_schema(), options);
  // Without --work-sizes every frame keeps the settings' scheduler and sizes.
  auto work_of = [&](const tuner::Config& c) {
    return o.work_sizes ? to_work_sizes(c) : WorkSizes::of(settings);
  };

  FrameBench bench(scene, settings, o.spp, o.objective);
  const BvhConfig default_config;
  const WorkSizes default_work = work_of(space.default_config());
  // Warm-up: threads, caches, page faults (not counted).
  bench.run(default_config, default_work, cameras[0]);

  TuneReport report;
  TuneProgress progress;
  progress.frames_total = o.iterations * static_cast<int>(cameras.size());
  auto measure_median = [&](const BvhConfig& config, const WorkSizes& work,
                            const CameraDesc& camera) {
    std::vector<double> ms;
    for (int k = 0; k < o.baseline_repeats; ++k)
      ms.push_back(bench.run(config, work, camera).cost_ms(o.objective));
    return median(ms);
  };
  for (size_t ci = 0; ci < cameras.size(); ++ci) {
    tuner::State state = to_tuner_state(compute_indicators(scene_indicators, cameras[ci]));
    CameraTuneResult r;
    r.camera = static_cast<int>(ci);
    // The baseline is measured outside the tuner: it is the yardstick, not a tuning decision.
    r.default_ms = measure_median(default_config, default_work, cameras[ci]);
    double best_ms = r.default_ms;
    for (int it = 0; it < o.iterations; ++it) {
      tuner::Config c = tuner.suggest(state);
      if (it == 0) r.mode = tuner.mode() == tuner::TunerMode::kSearch ? "search" : "exploit";
      FrameCost cost = bench.run(to_bvh_config(c), work_of(c), cameras[ci]);
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
        progress.best_speedup = best_ms > 0 ? r.default_ms / best_ms : 0.0;
        on_frame(progress);
      }
    }
    const tuner::Config best = tuner.best(state);
    const BvhConfig chosen = to_bvh_config(best);
    const WorkSizes chosen_work = work_of(best);
    r.chosen_ms = measure_median(chosen, chosen_work, cameras[ci]);
    r.config = chosen.to_string();
    if (o.work_sizes) r.config += "," + chosen_work.to_string();
    if (auto s = tuner.summary(state)) r.converged = s->converged;
    if (log)
      log(fmt::format(
          "camera {:>3} {:<8} default {:8.2f} ms  chosen {:8.2f} ms  speedup {:5.2f}  {}", r.camera,
          r.mode, r.default_ms, r.chosen_ms, r.speedup(), r.config));
    report.cameras.push_back(r);
  }
  return report;
}

}  // namespace tuneray
