// A job of a study spread over MPI ranks: one (scene, objective, camera) — finish its search, or
// measure its comparison — and what the rank that ran it sends back. Both travel between ranks
// as JSON text.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "tuning/eval_comparison.h"
#include "tuning/eval_costs.h"
#include "tuning/eval_profile.h"
#include "tuning/eval_scene.h"
#include "tuning/eval_search.h"

namespace tuneray {

struct EvalJob {
  int scene = 0;      // index into the profile's scenes
  int objective = 0;  // index into the profile's objectives
  int camera = 0;
  // The search is incomplete: finish it, continuing from the frames the database holds (`done`,
  // measured on `done_hardware`; a rank of another machine starts afresh instead).
  bool search = false;
  std::string done_hardware;
  std::vector<EvalFrame> done;
  // The configurations (AccelChoice texts) of the camera's comparison, in measuring order;
  // empty: none to measure.
  std::vector<std::string> compare;
};

struct EvalJobResult {
  int scene = 0, objective = 0, camera = 0;
  std::string hardware;                      // of the rank that measured
  std::vector<EvalFrame> frames;             // the whole search, `done` included (empty: no search)
  std::optional<EvalComparison> comparison;  // every round of it
};

std::string to_json(const EvalJob& job);
std::string to_json(const EvalJobResult& result);
// Throw std::runtime_error on malformed text.
EvalJob parse_eval_job(const std::string& text);
EvalJobResult parse_eval_job_result(const std::string& text);

// Runs `job` on `scene` (profile `p`) with `costs` (of the job's scene and objective), on a
// machine of signature `hardware`. Opens no database: the search runs in memory.
EvalJobResult run_eval_job(const EvalProfile& p, const EvalScene& scene, EvalCostSource& costs,
                           const EvalJob& job, const std::string& hardware);

}  // namespace tuneray
