#include "tuning/frame_bench.h"

#include <limits>
#include <stdexcept>

namespace tuneray {

Objective parse_objective(const std::string& text) {
  if (text == "render") return Objective::kRender;
  if (text == "total") return Objective::kTotal;
  throw std::invalid_argument("bad objective '" + text + "': expected render or total");
}

const char* to_string(Objective objective) {
  return objective == Objective::kRender ? "render" : "total";
}

double FrameCost::cost_ms(Objective objective) const {
  if (!ok) return std::numeric_limits<double>::infinity();
  return objective == Objective::kRender ? render_ms : build_ms + render_ms;
}

FrameBench::FrameBench(const Scene& scene, const RenderSettings& settings, uint32_t spp,
                       Objective objective)
    : scene_(scene),
      settings_(settings),
      spp_(spp),
      objective_(objective),
      sampler_(settings.seed),
      renderer_(scene, accel_, scene.cameras.at(0), settings, sampler_),
      film_(settings.width, settings.height) {}

FrameCost FrameBench::run(const BvhConfig& config, const CameraDesc& camera) {
  return run(config, WorkSizes::of(settings_), camera);
}

FrameCost FrameBench::run(const BvhConfig& config, const WorkSizes& work,
                          const CameraDesc& camera) {
  FrameCost cost;
  if (!built_ || !(*built_ == config) || objective_ == Objective::kTotal) {
    built_.reset();
    try {
      accel_.set_config(config);
      build_stats_ = accel_.build({scene_.positions.data(), scene_.positions.size(),
                                   scene_.triangles.data(), scene_.triangles.size()});
    } catch (const std::exception& e) {  // BuildError, or a configuration the backend rejects
      cost.ok = false;
      cost.error = e.what();
      return cost;
    }
    built_ = config;
    cost.rebuilt = true;
    cost.build_ms = build_stats_.build_ms;
  }
  // A fresh film each frame: the image is not the point, the time is. Sample indices advance
  // so frames are not identical.
  film_.clear();
  renderer_.set_camera(camera);
  renderer_.set_work_sizes(work.wavefront, work.tile_size, work.batch_size);
  PassStats pass = renderer_.render_pass(film_, frame_ * spp_, spp_);
  ++frame_;
  cost.render_ms = pass.render_ms;
  return cost;
}

}  // namespace tuneray
