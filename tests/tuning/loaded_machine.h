// Synthetic frame costs (tuning/eval_costs.h) as a machine whose load changes would give them,
// deterministically: the test of a comparison protocol needs noise it controls. At each camera
// the first `search_frames` frames are the camera's search and pass scaled by `search_load` (and
// one, made lucky on purpose, by its factor too); every later frame belongs to the camera's
// comparison and is scaled by the load of its round. A round ends where a configuration comes again
// (a comparison's warm-up and each of its rounds measure every candidate once), so a load change
// hits every candidate of a round alike, as a change between two rounds would.
#pragma once

#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "tuning/eval_costs.h"

namespace tuneray::testing {

struct MachineLoad {
  int search_frames = 0;             // per camera, yardstick frames included
  double search_load = 1;            // every search frame costs this many times its cost
  std::vector<double> load = {1.0};  // by comparison round (round 0 = the warm-up), cycled
  int lucky_frame = -1;              // this search frame at each camera costs...
  double lucky_factor = 1;           // ...this fraction of its cost
  // The comparison of this camera fails with std::runtime_error at its frame `fail_at` (from
  // 0); the frames before it cost 1 + 0.37 k times theirs, k = the configuration's order of
  // first appearance, so a result that used any of them would show it.
  int fail_camera = -1;
  int fail_at = -1;
};

class LoadedMachine : public EvalCostSource {
 public:
  LoadedMachine(std::string scene, Objective objective, MachineLoad load)
      : scene_(std::move(scene)), objective_(objective), load_(std::move(load)) {}

  FrameCost frame(const AccelChoice& choice, int camera) override {
    FrameCost cost = synthetic_frame_cost(scene_, objective_, camera, choice);
    Window& w = windows_[camera];
    if (w.search_frames < load_.search_frames) {
      if (w.search_frames++ == load_.lucky_frame) scale(cost, load_.lucky_factor);
      scale(cost, load_.search_load);
      return cost;
    }
    const std::string config = choice.to_string();
    if (w.in_round.count(config)) {
      w.in_round.clear();
      ++w.round;
    }
    w.in_round.insert(config);
    if (camera == load_.fail_camera) {
      if (w.frames == load_.fail_at) throw std::runtime_error("the machine went down");
      w.order.emplace(config, static_cast<int>(w.order.size()));
      scale(cost, 1 + 0.37 * w.order.at(config));
    }
    ++w.frames;
    scale(cost, load_.load[static_cast<size_t>(w.round) % load_.load.size()]);
    return cost;
  }

 private:
  struct Window {
    int search_frames = 0, frames = 0, round = 0;
    std::set<std::string> in_round;
    std::map<std::string, int> order;
  };

  static void scale(FrameCost& cost, double factor) {
    cost.build_ms *= factor;
    cost.render_ms *= factor;
  }

  std::string scene_;
  Objective objective_;
  MachineLoad load_;
  std::map<int, Window> windows_;
};

}  // namespace tuneray::testing
