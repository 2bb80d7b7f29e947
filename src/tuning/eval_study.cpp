#include "tuning/eval_study.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <numeric>
#include <set>
#include <sstream>

#include "scene/camera_spline.h"
#include "scene/indicators.h"
#include "scene/load.h"
#include "tuner/greedy_gq.h"
#include "tuner/hybrid_tuner.h"
#include "tuner/nearest_neighbour.h"
#include "tuner/rng.h"
#include "tuning/bvh_space.h"
#include "tuning/cost_log.h"
#include "tuning/eval_costs.h"
#include "tuning/eval_metrics.h"
#include "tuning/stats.h"
#include "tuning/tuner_state.h"

namespace tuneray {

std::vector<CameraDesc> camera_positions(const Scene& scene, int path_index, int count);

namespace {

namespace fs = std::filesystem;

std::string scene_key(const std::string& spec) {
  return fs::path(spec).stem().string();
}

// Live re-measurements: the median of `repeats` frames per (camera, configuration), kept in a
// CSV beside the report so that an interrupted study does not measure them again.
class LiveCosts {
 public:
  LiveCosts(std::string path, std::string prefix)
      : log_(std::move(path), prefix), prefix_(prefix) {}

  double get(EvalCostSource& costs, Objective objective, int camera_index,
             const AccelChoice& config, int repeats) {
    std::string key = fmt::format("{}\t{}\t{}", prefix_, camera_index, config.to_string());
    if (auto known = log_.find(key)) return *known;
    std::vector<double> ms;
    for (int r = 0; r < repeats; ++r)
      ms.push_back(costs.frame(config, camera_index).cost_ms(objective));
    return log_.add(key, median(ms));
  }

  // Best (lowest) measured cost and its configuration for one camera.
  std::pair<double, std::string> best(int camera_index) const {
    std::string head = fmt::format("{}\t{}\t", prefix_, camera_index);
    std::pair<double, std::string> b{kNever, ""};
    for (const auto& [key, ms] : log_.entries())
      if (key.compare(0, head.size(), head) == 0 && ms < b.first) b = {ms, key.substr(head.size())};
    return b;
  }

 private:
  CostLog log_;
  std::string prefix_;
};

struct SceneData {
  std::vector<CameraDesc> cameras;
  std::vector<tuner::State> states;
  std::vector<std::vector<double>> normalised;
  // Per camera: every search sample (config text, cost in ms; failures already replaced).
  std::vector<std::vector<std::pair<std::string, double>>> samples;
  std::vector<tuner::Config> incumbents;  // per camera, the search's converged configuration
};

}  // namespace

EvalResults run_eval_study(const EvalProfile& p, const EvalPaths& paths,
                           const std::function<void(const std::string&)>& log) {
  fs::create_directories(paths.out_dir);
  std::string db_path =
      paths.db_path.empty() ? (fs::path(paths.out_dir) / "eval.db").string() : paths.db_path;
  EvalResults results;
  results.profile = p;
  const tuner::Space space = p.native_in_space ? make_backend_space() : make_bvh_space();
  const tuner::IndicatorSchema schema = make_indicator_schema();

  for (const std::string& spec : p.scenes) {
    LoadOptions load_options;
    load_options.scenes_dir = p.scenes_dir;
    Scene scene = load_scene(spec, load_options);
    const std::string name = scene_key(spec);
    SceneData data;
    data.cameras = camera_positions(scene, 0, p.cameras);
    SceneIndicators si = compute_scene_indicators(scene);
    for (const CameraDesc& c : data.cameras) {
      data.states.push_back(to_tuner_state(compute_indicators(si, c)));
      data.normalised.push_back(schema.normalise(data.states.back()));
    }

    for (Objective objective : p.objectives) {
      const std::string obj = to_string(objective);
      // The scheduler is part of the key: costs on tiles and on waves do not compare.
      // So are synthetic costs: they must never mix with measured ones.
      const std::string run_key = fmt::format(
          "{}/{}/{}x{}/{}spp/{}b/{}{}", name, obj, p.width, p.height, p.spp, p.max_bounces,
          p.wavefront ? "wavefront" : "tile", p.synthetic_costs ? "/synthetic" : "");
      RenderSettings settings;
      settings.width = p.width;
      settings.height = p.height;
      settings.max_bounces = p.max_bounces;
      settings.seed = p.seed;
      settings.quality.wavefront = p.wavefront;
      std::unique_ptr<EvalCostSource> costs =
          p.synthetic_costs ? make_synthetic_costs(name, objective)
                            : make_measured_costs(scene, settings, p.spp, objective, data.cameras);
      const AccelChoice default_choice = AccelChoice::tuned(BvhConfig{});
      const AccelChoice native_choice = AccelChoice::native();
      LiveCosts live((fs::path(paths.out_dir) / "live_costs.tsv").string(), run_key);

      // 1. A full search at every camera, each from the default configuration.
      std::vector<CameraRecord> records(data.cameras.size());
      data.samples.assign(data.cameras.size(), {});
      data.incumbents.assign(data.cameras.size(), space.default_config());
      for (size_t ci = 0; ci < data.cameras.size(); ++ci) {
        tuner::TunerOptions options;
        options.epsilon = 1.0;
        options.seed = p.seed + ci;
        options.search.max_iterations = p.iterations;
        options.db_path = db_path;
        // The space is part of the key: the database refuses one key with two spaces.
        options.tuning_key =
            fmt::format("{}/{}/cam{}", p.native_in_space ? "eval+backend" : "eval", run_key, ci);
        tuner::HybridTuner tuner(space, schema, options);
        int64_t signature = tuner.signature_id();
        size_t done = tuner.database()->samples(signature).size();
        for (size_t k = done; k < static_cast<size_t>(p.iterations); ++k) {
          tuner::Config c = tuner.suggest(data.states[ci]);
          FrameCost cost = costs->frame(to_accel_choice(c), static_cast<int>(ci));
          tuner::Extras extras = {{"build_ms", cost.build_ms}, {"render_ms", cost.render_ms}};
          if (cost.ok)
            tuner.report(c, cost.cost_ms(objective) / 1000.0, extras);
          else
            tuner.report_failure(c, extras);
        }
        CameraRecord& r = records[ci];
        r.scene = name;
        r.objective = obj;
        r.camera = static_cast<int>(ci);
        r.default_ms = live.get(*costs, objective, r.camera, default_choice, p.measure_repeats);
        r.native_ms = live.get(*costs, objective, r.camera, native_choice, p.measure_repeats);
        for (const tuner::StoredSample& s : tuner.database()->samples(signature)) {
          // A refused build is counted as a frame rendered with the default tree.
          double ms = std::isfinite(s.cost) ? s.cost * 1000.0 : r.default_ms;
          r.search_ms.push_back(ms);
          data.samples[ci].emplace_back(s.config, ms);
        }
        r.search_ms.resize(std::min(r.search_ms.size(), static_cast<size_t>(p.iterations)));
        tuner::Config incumbent = tuner.best(data.states[ci]);
        data.incumbents[ci] = incumbent;
        if (auto summary = tuner.summary(data.states[ci])) r.converged = summary->converged;
        r.converged_config = to_accel_choice(incumbent).to_string();
        r.converged_ms =
            live.get(*costs, objective, r.camera, to_accel_choice(incumbent), p.measure_repeats);
        if (log)
          log(fmt::format(
              "{:<14} {:<6} camera {:>3}: search {:3} frames, default {:8.2f} ms, native {:8.2f} "
              "ms, converged {:8.2f} ms ({:.3f}x default, {:.3f}x native)",
              name, obj, ci, r.search_ms.size(), r.default_ms, r.native_ms, r.converged_ms,
              r.search_speedup(), r.native_speedup()));
      }

      // 2. Predictors trained on a random split, judged on the held-out cameras.
      const size_t n = data.cameras.size();
      const size_t n_train = std::clamp<size_t>(
          static_cast<size_t>(std::lround(p.train_fraction * n)), 1, n > 1 ? n - 1 : 1);
      std::vector<PredictionRecord> predictions;
      for (int rep = 0; rep < p.repetitions && n > 1; ++rep) {
        tuner::Rng rng(p.seed * 7919 + static_cast<uint64_t>(rep));
        std::vector<size_t> order(n);
        std::iota(order.begin(), order.end(), 0);
        for (size_t i = n - 1; i > 0; --i) std::swap(order[i], order[rng.next_u64() % (i + 1)]);

        tuner::NearestNeighbourPredictor nn;
        tuner::GreedyGqPredictor gq(schema.size(), space.size(), tuner::GreedyGqOptions{},
                                    p.seed + static_cast<uint64_t>(rep));
        double worst = 0;
        for (size_t t = 0; t < n_train; ++t)
          for (const auto& [config, ms] : data.samples[order[t]]) worst = std::max(worst, ms);
        std::vector<tuner::Config> candidates;
        std::vector<std::vector<double>> candidate_points;
        std::set<std::string> seen;
        for (size_t t = 0; t < n_train; ++t) {
          size_t ci = order[t];
          const tuner::Config& best = data.incumbents[ci];
          nn.set_best(static_cast<int64_t>(ci), data.normalised[ci], best);
          for (const auto& [config, ms] : data.samples[ci])
            gq.train(data.normalised[ci], space.encode(space.parse(config)),
                     tuner::GreedyGqPredictor::reward(tuner::RewardKind::kNegLog, ms / 1000.0,
                                                      worst / 1000.0));
          if (seen.insert(best.to_string()).second) {
            candidates.push_back(best);
            candidate_points.push_back(space.encode(best));
          }
        }
        for (size_t v = n_train; v < n; ++v) {
          size_t ci = order[v];
          std::vector<std::pair<std::string, tuner::Config>> picks;
          if (auto pred = nn.predict(data.normalised[ci])) picks.emplace_back("nn", pred->config);
          if (auto idx = gq.best_candidate(data.normalised[ci], candidate_points))
            picks.emplace_back("rbf", candidates[*idx]);
          for (const auto& [predictor, config] : picks) {
            PredictionRecord pr;
            pr.scene = name;
            pr.objective = obj;
            pr.repetition = rep;
            pr.camera = static_cast<int>(ci);
            pr.predictor = predictor;
            AccelChoice choice = to_accel_choice(config);
            pr.config = choice.to_string();
            pr.predicted_ms = live.get(*costs, objective, pr.camera, choice, p.measure_repeats);
            predictions.push_back(pr);
          }
        }
      }

      // 3. Best known per camera (over everything measured live), then the figures of merit.
      for (CameraRecord& r : records) {
        auto [best_ms, best_config] = live.best(r.camera);
        r.best_ms = best_ms;
        r.best_config = best_config;
      }
      for (PredictionRecord& pr : predictions) {
        const CameraRecord& r = records[pr.camera];
        pr.search_total_ms = accumulated_search_time(r.search_ms, r.converged_ms, p.iterations);
        pr.speedup = prediction_speedup(r.search_ms, r.converged_ms, pr.predicted_ms, p.iterations);
        pr.overhead_reduction = overhead_reduction(r.search_ms, r.converged_ms, pr.predicted_ms,
                                                   r.best_ms, p.iterations);
        pr.roofline = roofline_fraction(pr.predicted_ms, r.best_ms);
        pr.native_speedup = pr.predicted_ms > 0 ? r.native_ms / pr.predicted_ms : 0.0;
        pr.break_even = break_even_frame(r.search_ms, r.converged_ms, pr.predicted_ms);
      }
      results.cameras.insert(results.cameras.end(), records.begin(), records.end());
      results.predictions.insert(results.predictions.end(), predictions.begin(), predictions.end());
    }
  }
  return results;
}

}  // namespace tuneray
