// Measures what the tuner optimises: one frame rendered with a given accelerator (our tuned BVH
// with a configuration, or native Embree with a build quality; optionally with other scheduler
// and work sizes) from a given camera. A backend's tree is rebuilt only when its configuration
// has no tree yet (progressive rendering) or for every frame (real-time rendering, objective
// `total`); a change of work sizes alone never rebuilds it. Both backends keep their last tree,
// so frames that alternate between native and tuned (the baselines of `tune`) do not rebuild
// either, and under objective `render` the tuned backend keeps the trees of its last few
// configurations too (TunedTreeCache), so that a comparison's rounds, one frame of each
// candidate in turn, render from the trees built once instead of rebuilding one per frame.
#pragma once

#include <optional>
#include <string>

#include "accel/bvh_config.h"
#include "accel/embree_native.h"
#include "accel/tuned_bvh.h"
#include "render/film.h"
#include "render/render_settings.h"
#include "render/sampler.h"
#include "render/tile_renderer.h"
#include "scene/scene.h"
#include "tuning/accel_choice.h"
#include "tuning/tree_cache.h"
#include "tuning/work_sizes.h"

namespace tuneray {

enum class Objective {
  kRender,  // render time of a frame (progressive rendering keeps the tree)
  kTotal,   // build + render time (real-time rendering rebuilds every frame)
};

Objective parse_objective(const std::string& text);  // "render" | "total"
const char* to_string(Objective objective);

// The settings of a measured frame: size, path length, seed and scheduler as given, every other
// setting at its default (what tune, eval and the render-level comparison all measure).
RenderSettings frame_settings(int width, int height, int max_bounces, uint64_t seed,
                              bool wavefront);

struct FrameCost {
  bool ok = true;  // false: the build was refused (error says why)
  bool rebuilt = false;
  double build_ms = 0;  // of the build done for this frame (0 when none)
  double render_ms = 0;
  std::string error;
  // Milliseconds the objective counts; +infinity for a failed build.
  double cost_ms(Objective objective) const;
};

class FrameBench {
 public:
  // Tuned trees kept under objective `render`, the one rendered with included. Enough for every
  // tuned candidate of a comparison (default, converged, best sample and the distinct
  // predictions: at most 7 in the standard study, 9 seen in the paper's, whose cameras are held
  // out 3 times on average); with more candidates than trees, least-recently-used eviction
  // under round-robin frames would rebuild at every frame. Bounded because a search tries a new
  // configuration nearly every frame, and trees are large: the default tree of bmw-m6 (0.8 M
  // triangles) takes 81 MiB, so 16 trees of the largest shared scene take 1-2 GiB (per
  // process: MPI ranks on one node each keep their own).
  static constexpr size_t kTunedTrees = 16;

  FrameBench(const Scene& scene, const RenderSettings& settings, uint32_t spp, Objective objective);

  // Renders one frame of `spp` samples per pixel with `choice` from `camera`, with the work
  // sizes of the settings given to the constructor, or with `work`. The integrator and its
  // lights are kept.
  FrameCost run(const AccelChoice& choice, const CameraDesc& camera);
  FrameCost run(const AccelChoice& choice, const WorkSizes& work, const CameraDesc& camera);
  // The tuned BVH with `config`.
  FrameCost run(const BvhConfig& config, const CameraDesc& camera) {
    return run(AccelChoice::tuned(config), camera);
  }
  FrameCost run(const BvhConfig& config, const WorkSizes& work, const CameraDesc& camera) {
    return run(AccelChoice::tuned(config), work, camera);
  }

  // The accelerator of the last frame (or of the last build attempt) and its last successful
  // build's statistics.
  const Accel& accel() const;
  const BuildStats& build_stats() const;
  Objective objective() const { return objective_; }
  const RenderSettings& settings() const { return settings_; }
  uint32_t spp() const { return spp_; }
  // The last frame's samples (lets tests compare schedulers; the tuner only needs the time).
  const Film& film() const { return film_; }

 private:
  // Builds the tree `choice` needs unless it is already there; false (with the error in `cost`)
  // when the backend refused.
  bool prepare(const AccelChoice& choice, FrameCost& cost);

  const Scene& scene_;
  RenderSettings settings_;
  uint32_t spp_;
  Objective objective_;
  TunedBvhAccel tuned_;
  EmbreeNativeAccel native_;
  std::optional<std::string> tuned_built_;  // AccelChoice text of the tree in tuned_
  std::optional<BvhQuality> native_built_;
  BuildStats tuned_stats_, native_stats_;
  TunedTreeCache kept_{kTunedTrees - 1};  // tuned_'s tree is the other one
  Backend current_ = Backend::kTuned;
  PcgSampler sampler_;
  // One renderer per backend: a renderer holds its accelerator by reference.
  TileRenderer tuned_renderer_, native_renderer_;
  Film film_;
  uint32_t frame_ = 0;
};

}  // namespace tuneray
