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

RenderSettings frame_settings(int width, int height, int max_bounces, uint64_t seed,
                              bool wavefront) {
  RenderSettings s;
  s.width = width;
  s.height = height;
  s.max_bounces = max_bounces;
  s.seed = seed;
  s.quality.wavefront = wavefront;
  return s;
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
      tuned_renderer_(scene, tuned_, scene.cameras.at(0), settings, sampler_),
      native_renderer_(scene, native_, scene.cameras.at(0), settings, sampler_),
      film_(settings.width, settings.height) {}

const Accel& FrameBench::accel() const {
  return current_ == Backend::kNative ? static_cast<const Accel&>(native_) : tuned_;
}

const BuildStats& FrameBench::build_stats() const {
  return current_ == Backend::kNative ? native_stats_ : tuned_stats_;
}

bool FrameBench::prepare(const AccelChoice& choice, FrameCost& cost) {
  current_ = choice.backend;
  const GeometryView geometry{scene_.positions.data(), scene_.positions.size(),
                              scene_.triangles.data(), scene_.triangles.size()};
  const bool every_frame = objective_ == Objective::kTotal;
  try {
    if (choice.is_native()) {
      if (native_built_ == choice.native_quality && !every_frame) return true;
      native_built_.reset();
      native_.set_options(choice.native_options());
      native_stats_ = native_.build(geometry);
      native_built_ = choice.native_quality;
      cost.build_ms = native_stats_.build_ms;
    } else {
      const std::string key = choice.to_string();
      if (!every_frame) {  // objective `total` measures a build in every frame: no cache there
        if (tuned_built_ == key) return true;
        if (kept_.take(key, tuned_built_, tuned_, tuned_stats_)) {
          tuned_built_ = key;
          return true;
        }
        if (tuned_built_) kept_.keep(*tuned_built_, tuned_, tuned_stats_);
      }
      tuned_built_.reset();
      tuned_.set_config(choice.bvh);
      tuned_stats_ = tuned_.build(geometry);
      tuned_built_ = key;
      cost.build_ms = tuned_stats_.build_ms;
    }
  } catch (const std::exception& e) {  // BuildError, or a configuration the backend rejects
    cost.ok = false;
    cost.error = e.what();
    return false;
  }
  cost.rebuilt = true;
  return true;
}

FrameCost FrameBench::run(const AccelChoice& choice, const CameraDesc& camera) {
  return run(choice, WorkSizes::of(settings_), camera);
}

FrameCost FrameBench::run(const AccelChoice& choice, const WorkSizes& work,
                          const CameraDesc& camera) {
  FrameCost cost;
  if (!prepare(choice, cost)) return cost;
  TileRenderer& renderer = choice.is_native() ? native_renderer_ : tuned_renderer_;
  // A fresh film each frame: the image is not the point, the time is. Sample indices advance
  // so frames are not identical.
  film_.clear();
  renderer.set_camera(camera);
  renderer.set_work_sizes(work.wavefront, work.tile_size, work.batch_size);
  PassStats pass = renderer.render_pass(film_, frame_ * spp_, spp_);
  ++frame_;
  cost.render_ms = pass.render_ms;
  return cost;
}

}  // namespace tuneray
