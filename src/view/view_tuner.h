// Online tuning inside the viewer (`view --tune --db F`): the hybrid tuner of `tune`, with its
// database, tuning key, search space and objectives, choosing the accelerator frame by frame
// while the window shows the result. Every frame runs the tuner's suggestion for the current
// camera's state (searching or exploiting as the tuner decides) and is reported to it, except
// two once the camera has stood still for a few frames: one with the default configuration and
// one with native Embree, the yardsticks of `tune`'s speedups (not reported to the tuner, as in
// `tune`). Flying never waits for them. The cost of a frame is its render time per sample per
// pixel, which is what `tune` measures with its 1-spp frames at the same size (plus the build under
// `total`).
#pragma once

#include <optional>
#include <string>

#include "accel/embree_native.h"
#include "accel/tuned_bvh.h"
#include "render/frame_budget.h"
#include "scene/indicators.h"
#include "scene/scene.h"
#include "tuner/hybrid_tuner.h"
#include "tuning/accel_choice.h"
#include "tuning/frame_bench.h"

namespace tuneray {

struct ViewTuneOptions {
  std::string db_path = "tuning.db";
  Objective objective = Objective::kRender;
  double epsilon = 0.1;
  uint64_t seed = 1;
};

struct ViewTuneStatus {
  std::string mode;    // "default", "native" (the yardstick frames), "search" or "exploit"
  std::string config;  // of the frame last rendered
  double default_ms = 0, native_ms = 0, current_ms = 0;  // costs per spp at this camera
  double speedup() const { return current_ms > 0 ? default_ms / current_ms : 0; }
  double vs_native() const { return current_ms > 0 ? native_ms / current_ms : 0; }
};

class ViewTuner {
 public:
  // `settings`: the viewer's (size, bounces, scheduler), which choose the tuning key.
  ViewTuner(const Scene& scene, const RenderSettings& settings, const ViewTuneOptions& options);

  // A new camera: a new tuner state and new yardsticks.
  void set_camera(const CameraDesc& camera);
  // Builds, if it is not built yet, the accelerator of the next frame and returns it. A
  // configuration the backend refuses is reported as a failure and the default is used.
  const Accel& next_accel();
  // The frame rendered with next_accel()'s accelerator.
  void report(const FrameResult& frame);

  const ViewTuneStatus& status() const { return status_; }
  const std::string& tuning_key() const { return key_; }
  int failed_builds() const { return failed_builds_; }

 private:
  enum class Phase { kDefault, kNative, kTuner };
  // Frames after a camera change before the yardsticks are measured.
  static constexpr int kYardstickFrame = 8;
  Phase phase() const;
  // Builds `choice` unless built; false when the backend refused it.
  bool prepare(const AccelChoice& choice);
  const Accel& accel_of(const AccelChoice& choice) const;

  const Scene& scene_;
  SceneIndicators scene_indicators_;
  ViewTuneOptions options_;
  std::string key_;
  std::optional<tuner::HybridTuner> tuner_;
  tuner::State state_;
  int frames_since_change_ = 0;
  std::optional<tuner::Config> pending_;  // the tuner's configuration of the next frame
  AccelChoice current_;
  TunedBvhAccel tuned_;
  EmbreeNativeAccel native_;
  std::optional<BvhConfig> tuned_built_;
  std::optional<BvhQuality> native_built_;
  double tuned_build_ms_ = 0, native_build_ms_ = 0, frame_build_ms_ = 0;
  ViewTuneStatus status_;
  int failed_builds_ = 0;
};

}  // namespace tuneray
