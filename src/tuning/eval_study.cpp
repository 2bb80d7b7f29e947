#include "tuning/eval_study.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>

#include "tuner/hardware_signature.h"
#include "tuner/hybrid_tuner.h"
#include "tuning/bvh_space.h"
#include "tuning/comparison_log.h"
#include "tuning/eval_comparison.h"
#include "tuning/eval_costs.h"
#include "tuning/eval_metrics.h"
#include "tuning/eval_predictions.h"
#include "tuning/eval_scene.h"
#include "tuning/eval_search.h"
#include "tuning/stats.h"
#include "tuning/tuner_state.h"

namespace tuneray {

namespace {

namespace fs = std::filesystem;

// What the study keeps of one camera's search, read back from the database.
struct SearchOutcome {
  CameraSearch search;      // what the predictors learn from
  std::string best_sample;  // AccelChoice text of the lowest sample: a candidate, never a cost
  // The default configuration in the search's window: the median of its frames there (the
  // yardsticks and the search's own frames of it; every search starts there) and how many;
  // 0 if none.
  double default_ms = 0;
  int default_frames = 0;
};

// Every cost (ms) of the default configuration measured in the search's window.
std::vector<double> default_costs_in_search(const std::vector<tuner::StoredSample>& samples,
                                            const std::string& default_config) {
  std::vector<double> at_default;
  for (const tuner::StoredSample& s : samples) {
    if (std::isfinite(s.cost) && s.config == default_config) at_default.push_back(s.cost * 1000.0);
    const double yardstick = stored_frame(s).yardstick_ms;
    if (yardstick > 0) at_default.push_back(yardstick);
  }
  return at_default;
}

// A refused build counts as a frame rendered with the default tree, at the cost the search
// itself measured for the default configuration, so the searches need nothing measured outside
// them. Should that be missing, the search's worst frame stands in for it.
double refused_frame_cost(const std::vector<tuner::StoredSample>& samples, double default_ms) {
  if (default_ms > 0) return default_ms;
  double worst = 0;
  for (const tuner::StoredSample& s : samples)
    if (std::isfinite(s.cost)) worst = std::max(worst, s.cost * 1000.0);
  return worst;
}

SearchOutcome search_outcome(const std::vector<tuner::StoredSample>& samples,
                             const tuner::Space& space, tuner::Config incumbent) {
  SearchOutcome o;
  const std::vector<double> at_default =
      default_costs_in_search(samples, space.default_config().to_string());
  o.default_ms = median(at_default);
  o.default_frames = static_cast<int>(at_default.size());
  const double refused_ms = refused_frame_cost(samples, o.default_ms);
  double best_ms = kNever;
  o.best_sample = to_accel_choice(space.default_config()).to_string();
  for (const tuner::StoredSample& s : samples) {
    const double ms = std::isfinite(s.cost) ? s.cost * 1000.0 : refused_ms;
    o.search.samples.emplace_back(s.config, ms);
    if (std::isfinite(s.cost) && ms < best_ms) {
      best_ms = ms;
      o.best_sample = to_accel_choice(space.parse(s.config)).to_string();
    }
  }
  o.search.incumbent = std::move(incumbent);
  return o;
}

// The camera's costs and ratios, all from its comparison.
void add_comparison(CameraRecord& r, const EvalComparison& c, const std::string& default_config) {
  const std::string native_config = AccelChoice::native().to_string();
  r.default_ms = c.cost_ms(default_config);
  if (r.search_default_ms > 0) r.search_window_load = r.search_default_ms / r.default_ms;
  r.search_calibrated = r.search_default_frames >= kMinYardstickFrames && r.search_window_load > 0;
  r.native_ms = c.cost_ms(native_config);
  r.converged_ms = c.cost_ms(r.converged_config);
  r.best_config = c.fastest();
  r.best_ms = c.cost_ms(r.best_config);
  r.search_speedup = c.ratio(default_config, r.converged_config);
  r.native_speedup = c.ratio(native_config, r.converged_config);
  r.candidates = static_cast<int>(c.configs.size());
  r.rounds = c.rounds();
  r.within_target = c.within_target;
}

// The prediction's figures of merit (DESIGN §6) against the search and its camera's comparison.
PredictionRecord prediction_record(const EvalProfile& p, const CameraRecord& r,
                                   const EvalComparison& c, const EvalPrediction& prediction) {
  PredictionRecord pr;
  pr.scene = r.scene;
  pr.objective = r.objective;
  pr.repetition = prediction.repetition;
  pr.camera = prediction.camera;
  pr.predictor = prediction.predictor;
  pr.config = prediction.config;
  pr.predicted_ms = c.cost_ms(pr.config);
  const std::vector<double> search_ms = r.search_ms_in_comparison_window();
  pr.search_total_ms = accumulated_search_time(search_ms, r.converged_ms, p.iterations);
  pr.speedup = prediction_speedup(search_ms, r.converged_ms, pr.predicted_ms, p.iterations);
  pr.overhead_reduction =
      overhead_reduction(search_ms, r.converged_ms, pr.predicted_ms, r.best_ms, p.iterations);
  pr.roofline = c.ratio(r.best_config, pr.config);
  pr.native_speedup = c.ratio(AccelChoice::native().to_string(), pr.config);
  pr.break_even = break_even_frame(search_ms, r.converged_ms, pr.predicted_ms);
  return pr;
}

std::string comparison_line(const CameraRecord& r, const EvalProfile& p) {
  auto interval = [](const RatioInterval& x) {
    return fmt::format("{:.3f}x [{:.3f}, {:.3f}]", x.ratio, x.low, x.high);
  };
  return fmt::format(
      "{:<14} {:<6} camera {:>3}: {} configurations compared in {} rounds ({}): default {:8.2f} "
      "ms, native {:8.2f} ms, converged {:8.2f} ms ({} default, {} native), best known {:8.2f} "
      "ms; the search's window {:.2f}x as loaded{}",
      r.scene, r.objective, r.camera, r.candidates, r.rounds,
      r.within_target ? fmt::format("within ±{:g} %", 100 * p.compare_target) : "cap reached",
      r.default_ms, r.native_ms, r.converged_ms, interval(r.search_speedup),
      interval(r.native_speedup), r.best_ms, r.search_window_load,
      r.search_calibrated ? " (calibrated)" : "");
}

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

std::string eval_comparisons_path(const EvalPaths& paths) {
  return (fs::path(paths.out_dir) / "comparisons.tsv").string();
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
  const std::string default_config = to_accel_choice(space.default_config()).to_string();
  const tuner::IndicatorSchema schema = make_indicator_schema();

  for (size_t si = 0; si < p.scenes.size(); ++si) {
    const std::unique_ptr<EvalScene> scene = load_eval_scene(p, p.scenes[si]);
    const std::string& name = scene->name;

    for (size_t oi = 0; oi < p.objectives.size(); ++oi) {
      const Objective objective = p.objectives[oi];
      const std::string run_key = eval_run_key(p, name, objective);
      std::unique_ptr<EvalCostSource> costs;
      if (!o.plan)
        costs =
            o.make_costs ? o.make_costs(*scene, objective) : make_eval_costs(p, *scene, objective);

      // 1. A full search at every camera, each from the default configuration.
      const size_t n_cameras = scene->cameras.size();
      std::vector<CameraRecord> records(n_cameras);
      std::vector<SearchOutcome> searches(n_cameras);
      bool searched_all = true;
      for (size_t ci = 0; ci < n_cameras; ++ci) {
        const int camera = static_cast<int>(ci);
        tuner::TunerOptions options = eval_tuner_options(p, objective, run_key, camera);
        options.db_path = db_path;
        const SearchSource source =
            search_source(db, options.tuning_key, hardware, o.mix_signatures, p.iterations);
        options.hardware = source.hardware;
        if (o.plan && source.samples < static_cast<size_t>(p.iterations)) {
          // Left to another rank, which needs what is stored.
          EvalJob& job = o.plan->job(static_cast<int>(si), static_cast<int>(oi), camera);
          job.search = true;
          job.done_hardware = source.hardware;
          if (source.samples > 0)
            if (auto id = db.find_signature(options.tuning_key, source.hardware))
              for (const tuner::StoredSample& s : db.samples(*id))
                job.done.push_back(stored_frame(s));
          searched_all = false;
          continue;
        }
        tuner::HybridTuner tuner(space, schema, options);
        const int64_t signature = tuner.signature_id();
        const size_t done = tuner.database()->samples(signature).size();
        for (size_t k = done; k < static_cast<size_t>(p.iterations); ++k)
          measure_search_frame(p, static_cast<int>(k), tuner, scene->states[ci], *costs, objective,
                               camera);
        const tuner::Config incumbent = tuner.best(scene->states[ci]);
        SearchOutcome& search = searches[ci];
        search = search_outcome(tuner.database()->samples(signature), space, incumbent);
        CameraRecord& r = records[ci];
        r.scene = name;
        r.objective = to_string(objective);
        r.camera = camera;
        for (const auto& [config, ms] : search.search.samples) r.search_ms.push_back(ms);
        r.search_ms.resize(std::min(r.search_ms.size(), static_cast<size_t>(p.iterations)));
        r.search_default_ms = search.default_ms;
        r.search_default_frames = search.default_frames;
        if (auto summary = tuner.summary(scene->states[ci])) r.converged = summary->converged;
        r.converged_config = to_accel_choice(incumbent).to_string();
        if (log)
          log(fmt::format("{:<14} {:<6} camera {:>3}: search {:3} frames, {} {}", name, r.objective,
                          camera, r.search_ms.size(), r.converged ? "converged to" : "stopped at",
                          r.converged_config));
      }
      // The predictors need every camera's search.
      if (!searched_all) continue;

      // 2. Predictors trained on random splits, asked for the held-out cameras.
      std::vector<CameraSearch> learned;
      for (const SearchOutcome& s : searches) learned.push_back(s.search);
      const std::vector<EvalPrediction> predictions =
          predict_held_out_cameras(p, *scene, space, schema, learned);
      std::vector<std::vector<std::string>> predicted(n_cameras);
      for (const EvalPrediction& pr : predictions)
        predicted[static_cast<size_t>(pr.camera)].push_back(pr.config);

      // 3. One comparison per camera of everything the report compares there.
      ComparisonLog comparison_log(eval_comparisons_path(paths), run_key);
      std::vector<EvalComparison> comparisons(n_cameras);
      bool compared_all = true;
      for (size_t ci = 0; ci < n_cameras; ++ci) {
        const int camera = static_cast<int>(ci);
        CameraRecord& r = records[ci];
        const std::vector<std::string> configs = comparison_configs(
            default_config, r.converged_config, searches[ci].best_sample, predicted[ci]);
        if (auto stored = comparison_log.find(camera, configs)) {
          comparisons[ci] = *stored;
        } else if (o.plan) {
          o.plan->job(static_cast<int>(si), static_cast<int>(oi), camera).compare = configs;
          compared_all = false;
          continue;
        } else {
          comparisons[ci] = comparison_log.add(
              camera,
              measure_comparison(*costs, objective, camera, configs, comparison_options(p)));
        }
        add_comparison(r, comparisons[ci], default_config);
        if (log) log(comparison_line(r, p));
      }
      if (!compared_all) continue;

      // 4. The predictions' figures of merit.
      results.cameras.insert(results.cameras.end(), records.begin(), records.end());
      for (const EvalPrediction& pr : predictions) {
        const size_t ci = static_cast<size_t>(pr.camera);
        results.predictions.push_back(prediction_record(p, records[ci], comparisons[ci], pr));
      }
    }
  }
  return results;
}

}  // namespace tuneray
