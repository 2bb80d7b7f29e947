// The evaluation study (DESIGN §6): per scene and objective, a full search at every camera of a
// path (recorded in the tuning database, so an interrupted study resumes), then the predictors
// trained on a random 80 % of the cameras and judged on the other 20 %, repeated.
#pragma once

#include <array>
#include <functional>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "tuning/eval_job.h"
#include "tuning/eval_profile.h"

namespace tuneray {

// One camera's search and its side-by-side re-measurements.
struct CameraRecord {
  std::string scene;
  std::string objective;
  int camera = 0;
  std::vector<double> search_ms;  // cost of every search frame, in order
  std::string converged_config;   // the search's incumbent
  bool converged = false;
  double default_ms = 0;  // live medians, measured the same way for every configuration
  double converged_ms = 0;
  double native_ms = 0;  // native Embree, medium quality (`render --accel native`)
  double best_ms = 0;    // best of every configuration measured live at this camera
  std::string best_config;
  double search_speedup() const { return converged_ms > 0 ? default_ms / converged_ms : 0.0; }
  double native_speedup() const { return converged_ms > 0 ? native_ms / converged_ms : 0.0; }
};

// One predictor's choice for one validation camera in one repetition.
struct PredictionRecord {
  std::string scene;
  std::string objective;
  int repetition = 0;
  int camera = 0;
  std::string predictor;  // "nn" or "rbf"
  std::string config;
  double predicted_ms = 0;
  double search_total_ms = 0;  // accumulated time of the search's frames
  double speedup = 0;          // over the search, accumulated over the search's frame count
  double native_speedup = 0;   // native Embree's live cost / predicted_ms
  double overhead_reduction = 0;
  double roofline = 0;
  double break_even = 0;  // frames; infinity = never
};

struct EvalResults {
  EvalProfile profile;
  std::vector<CameraRecord> cameras;
  std::vector<PredictionRecord> predictions;
};

struct EvalPaths {
  std::string out_dir;  // report, CSV, plots
  std::string db_path;  // tuning database (search data); default out_dir/eval.db
};

// What a study still lacks, as jobs for other ranks (one per camera).
struct EvalPlan {
  std::vector<EvalJob> jobs;
  EvalJob& job(int scene, int objective, int camera);

 private:
  std::map<std::array<int, 3>, size_t> index_;
};

// The study found samples of another machine, or ranks of several machines, and was not told
// to mix them.
class EvalSignatureError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct EvalStudyOptions {
  // Hardware signatures of the ranks that measure, first = preferred (empty: this machine's).
  std::vector<std::string> hardware;
  // Accept samples of several signatures: a complete search of another machine is then used as
  // it is, an incomplete one is restarted on a measuring machine. Otherwise the study refuses.
  bool mix_signatures = false;
  // When set, nothing is measured: every search the database lacks and every live cost the log
  // lacks is added here instead, and the results hold only what was complete (all of it when
  // the plan stays empty).
  EvalPlan* plan = nullptr;
};

// Runs (or resumes) the study. `log` receives progress lines.
EvalResults run_eval_study(const EvalProfile& profile, const EvalPaths& paths,
                           const std::function<void(const std::string&)>& log,
                           const EvalStudyOptions& options = {});

// The tuning database the study uses (paths.db_path, or eval.db in the output folder) and the
// live cost log.
std::string eval_db_path(const EvalPaths& paths);
std::string eval_live_costs_path(const EvalPaths& paths);
// Key of a live cost in the log.
std::string eval_live_key(const std::string& run_key, int camera, const std::string& config);

// The refusal of a study whose ranks run on several kinds of machine, one line per machine.
std::string mixed_machines_message(const std::vector<std::string>& machines);

// Throws EvalSignatureError unless `mix` or every sample of the study in `db_path` was measured
// on the only machine of `hardware`.
void check_eval_signatures(const EvalProfile& p, const std::string& db_path,
                           const std::vector<std::string>& hardware, bool mix);

}  // namespace tuneray
