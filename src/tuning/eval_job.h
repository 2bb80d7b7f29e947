// A job of a study spread over MPI ranks: one (scene, objective, camera) — finish its search
// and re-measure some configurations live — and what the rank that ran it sends back. Both
// travel between ranks as JSON text.
#pragma once

#include <string>
#include <utility>
#include <vector>

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
  // measured on `done_hardware`; a rank of another machine starts afresh instead), and
  // re-measure its converged configuration unless `known` holds it.
  bool search = false;
  std::string done_hardware;
  std::vector<EvalFrame> done;
  std::vector<std::string> measure;  // AccelChoice texts to re-measure live at this camera
  std::vector<std::string> known;    // AccelChoice texts the live log holds at this camera
};

struct EvalJobResult {
  int scene = 0, objective = 0, camera = 0;
  std::string hardware;           // of the rank that measured
  std::vector<EvalFrame> frames;  // the whole search, `done` included (empty: no search)
  std::vector<std::pair<std::string, double>> live;  // (AccelChoice text, median ms)
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
