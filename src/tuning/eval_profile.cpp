#include "tuning/eval_profile.h"

#include <stdexcept>

namespace tuneray {

EvalProfile eval_profile(const std::string& name, const std::vector<std::string>& shared_scenes) {
  EvalProfile p;
  p.name = name;
  if (name == "quick") {
    p.scenes = {"cornell", "voxels"};
    p.cameras = 6;
    p.iterations = 12;
    p.width = 96;
    p.height = 54;
    p.repetitions = 3;
    p.yardsticks = 3;
  } else if (name == "standard") {
    p.scenes = shared_scenes;
    p.cameras = 10;
    p.iterations = 30;
    p.yardsticks = 6;
    p.width = 256;
    p.height = 144;
    p.repetitions = 15;
  } else if (name == "paper") {
    p.scenes = shared_scenes;
  } else {
    throw std::invalid_argument("unknown profile '" + name + "' (quick, standard or paper)");
  }
  return p;
}

}  // namespace tuneray
