// The evaluation study (DESIGN §6): per scene and objective, a full search at every camera of a
// path (recorded in the tuning database, so an interrupted study resumes), then the predictors
// trained on a random 80 % of the cameras and asked for the other 20 %, repeated, and at every
// camera one interleaved comparison of everything the report compares there (the default,
// native Embree, the search's result and best sample, each prediction), stored whole so that
// an interrupted study resumes without mixing time windows.
#pragma once

#include <array>
#include <functional>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "tuning/eval_job.h"
#include "tuning/eval_profile.h"
#include "tuning/eval_records.h"
#include "tuning/eval_scene.h"

namespace tuneray {

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
  // When set, nothing is measured: every search the database lacks and every comparison the
  // comparison log lacks is added here instead, and the results hold only what was complete
  // (all of it when the plan stays empty).
  EvalPlan* plan = nullptr;
  // Where frame costs come from (empty: make_eval_costs). Tests put noise they control here.
  std::function<std::unique_ptr<EvalCostSource>(const EvalScene&, Objective)> make_costs;
};

// Runs (or resumes) the study. `log` receives progress lines.
EvalResults run_eval_study(const EvalProfile& profile, const EvalPaths& paths,
                           const std::function<void(const std::string&)>& log,
                           const EvalStudyOptions& options = {});

// The tuning database the study uses (paths.db_path, or eval.db in the output folder) and the
// log of finished comparisons (comparison_log.h).
std::string eval_db_path(const EvalPaths& paths);
std::string eval_comparisons_path(const EvalPaths& paths);

// The refusal of a study whose ranks run on several kinds of machine, one line per machine.
std::string mixed_machines_message(const std::vector<std::string>& machines);

// Throws EvalSignatureError unless `mix` or every sample of the study in `db_path` was measured
// on the only machine of `hardware`.
void check_eval_signatures(const EvalProfile& p, const std::string& db_path,
                           const std::vector<std::string>& hardware, bool mix);

}  // namespace tuneray
