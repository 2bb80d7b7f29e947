// One scene of the study as every rank sees it: the scene, its cameras along the path and each
// camera's indicators as a tuner state. Deterministic, so the ranks that measure and the rank
// that stores agree on every state.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "scene/camera.h"
#include "scene/scene.h"
#include "tuner/indicators.h"
#include "tuning/eval_costs.h"
#include "tuning/eval_profile.h"

namespace tuneray {

struct EvalScene {
  std::string name;  // eval_scene_name(spec)
  Scene scene;
  std::vector<CameraDesc> cameras;
  std::vector<tuner::State> states;
  std::vector<std::vector<double>> normalised;  // states normalised by the indicator schema
};

// Loads scene `spec` of profile `p` (throws what load_scene throws). Heap-allocated because
// cost sources keep references to its scene and cameras.
std::unique_ptr<EvalScene> load_eval_scene(const EvalProfile& p, const std::string& spec);

// Where the frame costs of `scene` under `objective` come from: rendered and timed, or the
// profile's synthetic costs. `scene` must outlive the source.
std::unique_ptr<EvalCostSource> make_eval_costs(const EvalProfile& p, const EvalScene& scene,
                                                Objective objective);

}  // namespace tuneray
