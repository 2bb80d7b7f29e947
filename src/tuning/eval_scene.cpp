#include "tuning/eval_scene.h"

#include "scene/camera_spline.h"
#include "scene/indicators.h"
#include "scene/load.h"
#include "tuning/eval_search.h"
#include "tuning/tuner_state.h"

namespace tuneray {

std::unique_ptr<EvalScene> load_eval_scene(const EvalProfile& p, const std::string& spec) {
  LoadOptions load_options;
  load_options.scenes_dir = p.scenes_dir;
  auto s = std::make_unique<EvalScene>();
  s->name = eval_scene_name(spec);
  s->scene = load_scene(spec, load_options);
  s->cameras = cameras_along_path(s->scene, 0, p.cameras);
  const tuner::IndicatorSchema schema = make_indicator_schema();
  SceneIndicators si = compute_scene_indicators(s->scene);
  for (const CameraDesc& c : s->cameras) {
    s->states.push_back(to_tuner_state(compute_indicators(si, c)));
    s->normalised.push_back(schema.normalise(s->states.back()));
  }
  return s;
}

std::unique_ptr<EvalCostSource> make_eval_costs(const EvalProfile& p, const EvalScene& scene,
                                                Objective objective) {
  if (p.synthetic_costs) return make_synthetic_costs(scene.name, objective);
  return make_measured_costs(scene.scene,
                             frame_settings(p.width, p.height, p.max_bounces, p.seed, p.wavefront),
                             p.spp, objective, scene.cameras);
}

}  // namespace tuneray
