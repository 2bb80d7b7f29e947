// Measures what the tuner optimises: one frame rendered with a given BVH configuration (and
// optionally scheduler and work sizes) from a given camera. The BVH is rebuilt only when its
// configuration changes (progressive rendering) or for every frame (real-time rendering,
// objective `total`); a change of work sizes alone never rebuilds it.
#pragma once

#include <optional>
#include <string>

#include "accel/bvh_config.h"
#include "accel/tuned_bvh.h"
#include "render/film.h"
#include "render/render_settings.h"
#include "render/sampler.h"
#include "render/tile_renderer.h"
#include "scene/scene.h"
#include "tuning/work_sizes.h"

namespace tuneray {

enum class Objective {
  kRender,  // render time of a frame (progressive rendering keeps the tree)
  kTotal,   // build + render time (real-time rendering rebuilds every frame)
};

Objective parse_objective(const std::string& text);  // "render" | "total"
const char* to_string(Objective objective);

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
  FrameBench(const Scene& scene, const RenderSettings& settings, uint32_t spp, Objective objective);

  // Renders one frame of `spp` samples per pixel with `config` from `camera`, with the work
  // sizes of the settings given to the constructor.
  FrameCost run(const BvhConfig& config, const CameraDesc& camera);
  // The same with other work sizes. The integrator and its lights are kept.
  FrameCost run(const BvhConfig& config, const WorkSizes& work, const CameraDesc& camera);
  // The last successful build's statistics.
  const BuildStats& build_stats() const { return build_stats_; }
  Objective objective() const { return objective_; }
  const RenderSettings& settings() const { return settings_; }
  uint32_t spp() const { return spp_; }
  // The last frame's samples (lets tests compare schedulers; the tuner only needs the time).
  const Film& film() const { return film_; }

 private:
  const Scene& scene_;
  RenderSettings settings_;
  uint32_t spp_;
  Objective objective_;
  TunedBvhAccel accel_;
  std::optional<BvhConfig> built_;
  BuildStats build_stats_;
  PcgSampler sampler_;
  TileRenderer renderer_;
  Film film_;
  uint32_t frame_ = 0;
};

}  // namespace tuneray
