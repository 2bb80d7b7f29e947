// Where the study's frame costs come from. Normally each frame is rendered and timed. For tests
// of resume and reproducibility (`eval --synthetic-costs`) a made-up cost, a deterministic
// function of (scene, objective, camera, configuration), replaces every measurement: nothing is
// rendered, and two runs, or a run killed and resumed any number of times, must then write
// byte-identical reports. Synthetic figures say nothing about the renderer.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "render/render_settings.h"
#include "scene/camera.h"
#include "scene/scene.h"
#include "tuning/accel_choice.h"
#include "tuning/frame_bench.h"

namespace tuneray {

class EvalCostSource {
 public:
  virtual ~EvalCostSource() = default;
  // The cost of one frame seen from camera `camera_index` with the accelerator `choice`.
  virtual FrameCost frame(const AccelChoice& choice, int camera_index) = 0;
};

// Renders and times frames with a FrameBench (after a warm-up frame of each backend, which is
// not counted). `scene` and `cameras` must outlive the source.
std::unique_ptr<EvalCostSource> make_measured_costs(const Scene& scene,
                                                    const RenderSettings& settings, uint32_t spp,
                                                    Objective objective,
                                                    const std::vector<CameraDesc>& cameras);

// Synthetic costs of one scene and objective (see synthetic_frame_cost).
std::unique_ptr<EvalCostSource> make_synthetic_costs(std::string scene, Objective objective);

// A smooth landscape over the BVH parameters whose optimum moves with the camera (so that the
// predictors have something to learn), plus a small hashed ripple per configuration; native
// Embree costs a camera-dependent constant per build quality. Always succeeds, always > 0, and
// depends only on its arguments (a 64-bit FNV-1a hash of their text, no clock, no state).
FrameCost synthetic_frame_cost(const std::string& scene, Objective objective, int camera,
                               const AccelChoice& choice);

}  // namespace tuneray
