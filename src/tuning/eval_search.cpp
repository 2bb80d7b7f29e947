#include "tuning/eval_search.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <stdexcept>

#include "tuning/bvh_space.h"

namespace tuneray {

std::string eval_scene_name(const std::string& spec) {
  return std::filesystem::path(spec).stem().string();
}

std::string eval_run_key(const EvalProfile& p, const std::string& scene, Objective objective) {
  return fmt::format("{}/{}/{}x{}/{}spp/{}b/{}{}", scene, to_string(objective), p.width, p.height,
                     p.spp, p.max_bounces, p.wavefront ? "wavefront" : "tile",
                     p.synthetic_costs ? "/synthetic" : "");
}

std::string eval_tuning_key(const EvalProfile& p, const std::string& run_key, int camera) {
  return fmt::format("{}{}/{}/cam{}", p.native_in_space ? "eval+backend" : "eval",
                     p.seeded ? "+seeded" : "", run_key, camera);
}

tuner::Space eval_space(const EvalProfile& p) {
  return p.native_in_space ? make_backend_space() : make_bvh_space();
}

tuner::TunerOptions eval_tuner_options(const EvalProfile& p, Objective objective,
                                       const std::string& run_key, int camera) {
  tuner::TunerOptions options;
  if (p.seeded) options.search_seeds = tuning_seeds(eval_space(p), objective == Objective::kTotal);
  options.epsilon = 1.0;
  options.seed = p.seed + static_cast<uint64_t>(camera);
  options.search.max_iterations = p.iterations;
  options.tuning_key = eval_tuning_key(p, run_key, camera);
  return options;
}

bool yardstick_after_frame(const EvalProfile& p, int k) {
  if (p.yardsticks <= 0 || p.iterations <= 0 || k < 0 || k >= p.iterations) return false;
  const int n = std::min(p.yardsticks, p.iterations);
  // Frame k closes the j-th of n equal stretches of the search when floor((k+1) n / iterations)
  // steps up there.
  return (k + 1) * n / p.iterations > k * n / p.iterations;
}

namespace {

constexpr const char* kYardstickExtra = "yardstick_ms";

tuner::Extras frame_extras(const EvalFrame& frame) {
  tuner::Extras extras = {{"build_ms", frame.build_ms}, {"render_ms", frame.render_ms}};
  if (frame.yardstick_ms > 0) extras[kYardstickExtra] = frame.yardstick_ms;
  return extras;
}

void report_frame(tuner::HybridTuner& tuner, const tuner::Config& config, const EvalFrame& frame) {
  if (frame.ok)
    tuner.report(config, frame.cost_s, frame_extras(frame));
  else
    tuner.report_failure(config, frame_extras(frame));
}

}  // namespace

EvalFrame measure_search_frame(const EvalProfile& p, int k, tuner::HybridTuner& tuner,
                               const tuner::State& state, EvalCostSource& costs,
                               Objective objective, int camera) {
  const tuner::Config config = tuner.suggest(state);
  const FrameCost cost = costs.frame(to_accel_choice(config), camera);
  EvalFrame frame;
  frame.config = config.to_string();
  frame.ok = cost.ok;
  frame.cost_s = cost.ok ? cost.cost_ms(objective) / 1000.0 : 0.0;
  frame.build_ms = cost.build_ms;
  frame.render_ms = cost.render_ms;
  if (yardstick_after_frame(p, k)) {
    const FrameCost yardstick =
        costs.frame(to_accel_choice(tuner.space().default_config()), camera);
    if (!yardstick.ok)
      throw std::runtime_error(fmt::format("search {}: the default configuration was refused: {}",
                                           tuner.options().tuning_key, yardstick.error));
    frame.yardstick_ms = yardstick.cost_ms(objective);
  }
  report_frame(tuner, config, frame);
  return frame;
}

void replay_search_frame(tuner::HybridTuner& tuner, const tuner::State& state,
                         const EvalFrame& frame) {
  const tuner::Config config = tuner.suggest(state);
  if (config.to_string() != frame.config)
    throw std::runtime_error(fmt::format(
        "search {}: replaying a frame measured elsewhere, the tuner suggests {} where {} was "
        "measured (the search is not deterministic, or the ranks run different programs)",
        tuner.options().tuning_key, config.to_string(), frame.config));
  report_frame(tuner, config, frame);
}

EvalFrame stored_frame(const tuner::StoredSample& sample) {
  EvalFrame frame;
  frame.config = sample.config;
  frame.ok = std::isfinite(sample.cost);
  frame.cost_s = frame.ok ? sample.cost : 0.0;
  auto extra = [&](const char* name) {
    auto it = sample.extras.find(name);
    return it == sample.extras.end() ? 0.0 : it->second;
  };
  frame.build_ms = extra("build_ms");
  frame.render_ms = extra("render_ms");
  frame.yardstick_ms = extra(kYardstickExtra);
  return frame;
}

}  // namespace tuneray
