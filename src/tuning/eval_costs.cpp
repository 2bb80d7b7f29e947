#include "tuning/eval_costs.h"

#include <fmt/core.h>

#include <cmath>
#include <cstdint>

namespace tuneray {

namespace {

class MeasuredCosts : public EvalCostSource {
 public:
  MeasuredCosts(const Scene& scene, const RenderSettings& settings, uint32_t spp,
                Objective objective, const std::vector<CameraDesc>& cameras)
      : bench_(scene, settings, spp, objective), cameras_(cameras) {
    // The first frames of each backend pay for page faults and cold caches.
    bench_.run(AccelChoice::native(), cameras_.at(0));
    bench_.run(AccelChoice::tuned(BvhConfig{}), cameras_.at(0));
  }

  FrameCost frame(const AccelChoice& choice, int camera_index) override {
    return bench_.run(choice, cameras_.at(static_cast<size_t>(camera_index)));
  }

 private:
  FrameBench bench_;
  const std::vector<CameraDesc>& cameras_;
};

class SyntheticCosts : public EvalCostSource {
 public:
  SyntheticCosts(std::string scene, Objective objective)
      : scene_(std::move(scene)), objective_(objective) {}

  FrameCost frame(const AccelChoice& choice, int camera_index) override {
    return synthetic_frame_cost(scene_, objective_, camera_index, choice);
  }

 private:
  std::string scene_;
  Objective objective_;
};

// FNV-1a: fixed by its definition, so the costs are the same on every machine and build.
uint64_t hash_text(const std::string& text) {
  uint64_t h = 14695981039346656037ull;
  for (unsigned char c : text) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return h;
}

// A number in [0, 1) drawn from `text`.
double unit(const std::string& text) {
  return static_cast<double>(hash_text(text) >> 11) * 0x1p-53;
}

double quality_factor(BvhQuality quality, double low, double medium, double high) {
  switch (quality) {
    case BvhQuality::kLow:
      return low;
    case BvhQuality::kMedium:
      return medium;
    case BvhQuality::kHigh:
      return high;
  }
  return medium;
}

}  // namespace

std::unique_ptr<EvalCostSource> make_measured_costs(const Scene& scene,
                                                    const RenderSettings& settings, uint32_t spp,
                                                    Objective objective,
                                                    const std::vector<CameraDesc>& cameras) {
  return std::make_unique<MeasuredCosts>(scene, settings, spp, objective, cameras);
}

std::unique_ptr<EvalCostSource> make_synthetic_costs(std::string scene, Objective objective) {
  return std::make_unique<SyntheticCosts>(std::move(scene), objective);
}

FrameCost synthetic_frame_cost(const std::string& scene, Objective objective, int camera,
                               const AccelChoice& choice) {
  const std::string where = fmt::format("{}/{}", scene, camera);
  const double base_ms = 1.0 + 4.0 * unit(scene) + 2.0 * unit(where);
  // The camera moves the optimum of the branching factor and of the leaf size.
  const double best_log_branching = 1.0 + 2.0 * unit(where + "/branching");
  const double best_log_leaf = 1.0 + 3.0 * unit(where + "/leaf");
  const double ripple = 0.03 * unit(where + "/" + choice.to_string());
  FrameCost cost;
  double build_factor = 1.0;
  double render_factor = 1.0;
  if (choice.is_native()) {
    build_factor = quality_factor(choice.native_quality, 0.4, 0.8, 2.0);
    render_factor =
        1.0 + quality_factor(choice.native_quality, 0.4, 0.15, 0.1) + 0.1 * unit(where + "/native");
  } else {
    const BvhConfig& b = choice.bvh;
    build_factor = quality_factor(b.quality, 0.5, 1.0, 2.5) * (b.compact ? 1.2 : 1.0);
    render_factor = 1.0 + quality_factor(b.quality, 0.5, 0.1, 0.0) +
                    0.15 * std::abs(std::log2(b.branching) - best_log_branching) +
                    0.08 * std::abs(std::log2(b.max_leaf) - best_log_leaf) +
                    0.05 * std::abs(std::log(b.cost_ratio())) + (b.robust ? 0.05 : 0.0) +
                    (b.is_static ? -0.02 : 0.0) + 0.002 * std::abs(b.max_depth - 32);
  }
  cost.rebuilt = objective == Objective::kTotal;
  cost.build_ms = cost.rebuilt ? 0.3 * base_ms * build_factor : 0.0;
  cost.render_ms = base_ms * (render_factor + ripple);
  return cost;
}

}  // namespace tuneray
