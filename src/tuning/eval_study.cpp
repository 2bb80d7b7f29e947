#include "tuning/eval_study.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <numeric>
#include <set>
#include <sstream>

#include "tuner/greedy_gq.h"
#include "tuner/hardware_signature.h"
#include "tuner/hybrid_tuner.h"
#include "tuner/nearest_neighbour.h"
#include "tuner/rng.h"
#include "tuning/bvh_space.h"
#include "tuning/cost_log.h"
#include "tuning/eval_costs.h"
#include "tuning/eval_metrics.h"
#include "tuning/eval_scene.h"
#include "tuning/eval_search.h"
#include "tuning/stats.h"
#include "tuning/tuner_state.h"

namespace tuneray {

namespace {

namespace fs = std::filesystem;

// Live re-measurements: the median of `repeats` frames per (camera, configuration), kept in a
// CSV beside the report so that an interrupted study does not measure them again. In a plan
// (MPI coordinator), a missing one is listed as work and reads as NaN.
class LiveCosts {
 public:
  LiveCosts(std::string path, std::string prefix, EvalPlan* plan, int scene, int objective)
      : log_(std::move(path), prefix),
        prefix_(prefix),
        plan_(plan),
        scene_(scene),
        objective_(objective) {}

  double get(EvalCostSource* costs, Objective objective, int camera_index,
             const AccelChoice& config, int repeats) {
    const std::string text = config.to_string();
    if (auto known = log_.find(eval_live_key(prefix_, camera_index, text))) return *known;
    if (plan_) {
      std::vector<std::string>& measure = plan_->job(scene_, objective_, camera_index).measure;
      if (std::find(measure.begin(), measure.end(), text) == measure.end()) measure.push_back(text);
      return std::numeric_limits<double>::quiet_NaN();
    }
    return log_.add(eval_live_key(prefix_, camera_index, text),
                    measure_live_ms(*costs, objective, camera_index, config, repeats));
  }

  // Configurations measured at one camera.
  std::vector<std::string> known(int camera_index) const {
    std::vector<std::string> configs;
    const std::string head = fmt::format("{}\t{}\t", prefix_, camera_index);
    for (const auto& [key, ms] : log_.entries())
      if (key.compare(0, head.size(), head) == 0) configs.push_back(key.substr(head.size()));
    return configs;
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
  EvalPlan* plan_;
  int scene_, objective_;
};

struct SceneData {
  // Per camera: every search sample (config text, cost in ms; failures already replaced).
  std::vector<std::vector<std::pair<std::string, double>>> samples;
  std::vector<tuner::Config> incumbents;  // per camera, the search's converged configuration
};

std::vector<std::string> unique_hardware(const std::vector<std::string>& hardware) {
  std::vector<std::string> unique;
  for (const std::string& h : hardware)
    if (std::find(unique.begin(), unique.end(), h) == unique.end()) unique.push_back(h);
  if (unique.empty()) unique.push_back(tuner::hardware_signature());
  return unique;
}

// The machine whose samples a camera's search uses. Unmixed: the one measuring machine. Mixed:
// a complete search of any machine (a measuring one first), else the measuring machine with the
// most samples, else the first measuring machine.
struct SearchSource {
  std::string hardware;
  size_t samples = 0;
};
SearchSource search_source(tuner::TuningDb& db, const std::string& key,
                           const std::vector<std::string>& hardware, bool mix, int iterations) {
  if (!mix) {
    for (const auto& row : db.hardware_with_samples(key))
      if (row.hardware == hardware.front()) return {row.hardware, static_cast<size_t>(row.samples)};
    return {hardware.front(), 0};
  }
  const auto rows = db.hardware_with_samples(key);
  auto measuring = [&](const std::string& h) {
    return std::find(hardware.begin(), hardware.end(), h) != hardware.end();
  };
  std::optional<SearchSource> complete, partial;
  for (const auto& row : rows) {
    SearchSource s{row.hardware, static_cast<size_t>(row.samples)};
    if (row.samples >= iterations) {
      if (!complete || (measuring(row.hardware) && !measuring(complete->hardware))) complete = s;
    } else if (measuring(row.hardware) &&
               (!partial || row.samples > static_cast<int64_t>(partial->samples))) {
      partial = s;
    }
  }
  if (complete) return *complete;
  if (partial) return *partial;
  return {hardware.front(), 0};
}

}  // namespace

EvalJob& EvalPlan::job(int scene, int objective, int camera) {
  const std::array<int, 3> key{scene, objective, camera};
  auto it = index_.find(key);
  if (it != index_.end()) return jobs[it->second];
  index_[key] = jobs.size();
  EvalJob& j = jobs.emplace_back();
  j.scene = scene;
  j.objective = objective;
  j.camera = camera;
  return j;
}

std::string eval_db_path(const EvalPaths& paths) {
  return paths.db_path.empty() ? (fs::path(paths.out_dir) / "eval.db").string() : paths.db_path;
}

std::string eval_live_costs_path(const EvalPaths& paths) {
  return (fs::path(paths.out_dir) / "live_costs.tsv").string();
}

std::string eval_live_key(const std::string& run_key, int camera, const std::string& config) {
  return fmt::format("{}\t{}\t{}", run_key, camera, config);
}

std::string mixed_machines_message(const std::vector<std::string>& machines) {
  std::string text = "the ranks run on machines of different kinds:";
  for (const std::string& m : machines) text += "\n  " + m;
  return text +
         "\nthe study would compare costs measured on different hardware; run on one kind, or "
         "pass --mix-signatures to accept it";
}

void check_eval_signatures(const EvalProfile& p, const std::string& db_path,
                           const std::vector<std::string>& hardware, bool mix) {
  if (mix) return;
  const std::vector<std::string> measuring = unique_hardware(hardware);
  if (measuring.size() > 1) throw EvalSignatureError(mixed_machines_message(measuring));
  if (!fs::exists(db_path)) return;
  tuner::TuningDb db(db_path);
  std::map<std::string, int64_t> foreign;  // hardware -> samples
  for (const std::string& spec : p.scenes)
    for (Objective objective : p.objectives) {
      const std::string run_key = eval_run_key(p, eval_scene_name(spec), objective);
      for (int ci = 0; ci < p.cameras; ++ci)
        for (const auto& row : db.hardware_with_samples(eval_tuning_key(p, run_key, ci)))
          if (row.hardware != measuring.front()) foreign[row.hardware] += row.samples;
    }
  if (foreign.empty()) return;
  std::string list;
  for (const auto& [h, n] : foreign) list += fmt::format("\n  {} ({} samples)", h, n);
  throw EvalSignatureError(fmt::format(
      "{} holds samples of this study measured on another machine:{}\nthis run measures on\n  "
      "{}\nmixing them would compare costs of different hardware; use another --out or --db, or "
      "pass --mix-signatures to accept it",
      db_path, list, measuring.front()));
}

EvalResults run_eval_study(const EvalProfile& p, const EvalPaths& paths,
                           const std::function<void(const std::string&)>& log,
                           const EvalStudyOptions& o) {
  fs::create_directories(paths.out_dir);
  const std::string db_path = eval_db_path(paths);
  const std::vector<std::string> hardware = unique_hardware(o.hardware);
  check_eval_signatures(p, db_path, hardware, o.mix_signatures);
  tuner::TuningDb db(db_path);
  EvalResults results;
  results.profile = p;
  const tuner::Space space = eval_space(p);
  const tuner::IndicatorSchema schema = make_indicator_schema();

  for (size_t si = 0; si < p.scenes.size(); ++si) {
    const std::unique_ptr<EvalScene> scene = load_eval_scene(p, p.scenes[si]);
    const std::string& name = scene->name;
    SceneData data;

    for (size_t oi = 0; oi < p.objectives.size(); ++oi) {
      const Objective objective = p.objectives[oi];
      const std::string obj = to_string(objective);
      const std::string run_key = eval_run_key(p, name, objective);
      std::unique_ptr<EvalCostSource> costs;
      if (!o.plan) costs = make_eval_costs(p, *scene, objective);
      const AccelChoice default_choice = AccelChoice::tuned(BvhConfig{});
      const AccelChoice native_choice = AccelChoice::native();
      LiveCosts live(eval_live_costs_path(paths), run_key, o.plan, static_cast<int>(si),
                     static_cast<int>(oi));

      // 1. A full search at every camera, each from the default configuration.
      const size_t n_cameras = scene->cameras.size();
      std::vector<CameraRecord> records(n_cameras);
      data.samples.assign(n_cameras, {});
      data.incumbents.assign(n_cameras, space.default_config());
      bool searched_all = true;
      for (size_t ci = 0; ci < n_cameras; ++ci) {
        const int camera = static_cast<int>(ci);
        tuner::TunerOptions options = eval_tuner_options(p, run_key, camera);
        options.db_path = db_path;
        const SearchSource source =
            search_source(db, options.tuning_key, hardware, o.mix_signatures, p.iterations);
        options.hardware = source.hardware;
        if (o.plan && source.samples < static_cast<size_t>(p.iterations)) {
          // Left to another rank, which needs what is stored and what the live log holds.
          EvalJob& job = o.plan->job(static_cast<int>(si), static_cast<int>(oi), camera);
          job.search = true;
          job.done_hardware = source.hardware;
          if (source.samples > 0)
            if (auto id = db.find_signature(options.tuning_key, source.hardware))
              for (const tuner::StoredSample& s : db.samples(*id))
                job.done.push_back(stored_frame(s));
          live.get(nullptr, objective, camera, default_choice, p.measure_repeats);
          live.get(nullptr, objective, camera, native_choice, p.measure_repeats);
          job.known = live.known(camera);
          searched_all = false;
          continue;
        }
        tuner::HybridTuner tuner(space, schema, options);
        int64_t signature = tuner.signature_id();
        size_t done = tuner.database()->samples(signature).size();
        for (size_t k = done; k < static_cast<size_t>(p.iterations); ++k)
          measure_search_frame(tuner, scene->states[ci], *costs, objective, camera);
        CameraRecord& r = records[ci];
        r.scene = name;
        r.objective = obj;
        r.camera = camera;
        r.default_ms =
            live.get(costs.get(), objective, r.camera, default_choice, p.measure_repeats);
        r.native_ms = live.get(costs.get(), objective, r.camera, native_choice, p.measure_repeats);
        for (const tuner::StoredSample& s : tuner.database()->samples(signature)) {
          // A refused build is counted as a frame rendered with the default tree.
          double ms = std::isfinite(s.cost) ? s.cost * 1000.0 : r.default_ms;
          r.search_ms.push_back(ms);
          data.samples[ci].emplace_back(s.config, ms);
        }
        r.search_ms.resize(std::min(r.search_ms.size(), static_cast<size_t>(p.iterations)));
        tuner::Config incumbent = tuner.best(scene->states[ci]);
        data.incumbents[ci] = incumbent;
        if (auto summary = tuner.summary(scene->states[ci])) r.converged = summary->converged;
        r.converged_config = to_accel_choice(incumbent).to_string();
        r.converged_ms = live.get(costs.get(), objective, r.camera, to_accel_choice(incumbent),
                                  p.measure_repeats);
        if (log)
          log(fmt::format(
              "{:<14} {:<6} camera {:>3}: search {:3} frames, default {:8.2f} ms, native {:8.2f} "
              "ms, converged {:8.2f} ms ({:.3f}x default, {:.3f}x native)",
              name, obj, ci, r.search_ms.size(), r.default_ms, r.native_ms, r.converged_ms,
              r.search_speedup(), r.native_speedup()));
      }
      // The predictors need every camera's search.
      if (!searched_all) continue;

      // 2. Predictors trained on a random split, judged on the held-out cameras.
      const size_t n = n_cameras;
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
          nn.set_best(static_cast<int64_t>(ci), scene->normalised[ci], best);
          for (const auto& [config, ms] : data.samples[ci])
            gq.train(scene->normalised[ci], space.encode(space.parse(config)),
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
          if (auto pred = nn.predict(scene->normalised[ci])) picks.emplace_back("nn", pred->config);
          if (auto idx = gq.best_candidate(scene->normalised[ci], candidate_points))
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
            pr.predicted_ms =
                live.get(costs.get(), objective, pr.camera, choice, p.measure_repeats);
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
