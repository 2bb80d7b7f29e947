// The predictors' part of the study (DESIGN §6): per repetition a random split of the cameras;
// a nearest-neighbour and a Greedy-GQ RBF predictor trained on the searches of the training
// cameras are asked for a configuration at each held-out camera. Only the configurations come
// from here: what they cost is measured in each camera's comparison (eval_comparison.h).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "tuner/config.h"
#include "tuner/indicators.h"
#include "tuner/space.h"
#include "tuning/eval_profile.h"
#include "tuning/eval_scene.h"

namespace tuneray {

// What the predictors learn from one camera's search.
struct CameraSearch {
  // Every search sample: tuner configuration text and cost in ms (a refused build counted at
  // the default configuration's cost).
  std::vector<std::pair<std::string, double>> samples;
  tuner::Config incumbent;  // the search's converged configuration
};

struct EvalPrediction {
  int repetition = 0;
  int camera = 0;         // a held-out camera of that repetition
  std::string predictor;  // "nn" or "rbf"
  std::string config;     // AccelChoice text
};

// The predictions of `p.repetitions` random splits of `scene`'s cameras, in repetition, then
// held-out camera order; `searches` has one entry per camera. Deterministic given the profile's
// seed and the searches.
std::vector<EvalPrediction> predict_held_out_cameras(const EvalProfile& p, const EvalScene& scene,
                                                     const tuner::Space& space,
                                                     const tuner::IndicatorSchema& schema,
                                                     const std::vector<CameraSearch>& searches);

}  // namespace tuneray
