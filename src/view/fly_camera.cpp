#include "view/fly_camera.h"

#include <algorithm>
#include <cmath>

namespace tuneray {

FlyCamera::FlyCamera(const CameraDesc& desc, float speed) : speed_(speed) {
  set_desc(desc);
}

void FlyCamera::set_desc(const CameraDesc& desc) {
  base_ = desc;
  position_ = desc.position;
  Vec3f to_target = desc.target - desc.position;
  float distance = length(to_target);
  // A camera whose target sits on its position has no direction: look down -z.
  Vec3f f = distance > 0 && std::isfinite(distance) ? to_target / distance : Vec3f(0, 0, -1);
  target_distance_ = distance > 0 && std::isfinite(distance) ? distance : 1.0f;
  yaw_ = std::atan2(f.x, -f.z);
  pitch_ = std::clamp(std::asin(std::clamp(f.y, -1.0f, 1.0f)), -kMaxPitch, kMaxPitch);
}

Vec3f FlyCamera::forward() const {
  float c = std::cos(pitch_);
  return {c * std::sin(yaw_), std::sin(pitch_), -c * std::cos(yaw_)};
}

Vec3f FlyCamera::right() const {
  return {std::cos(yaw_), 0, std::sin(yaw_)};
}

bool FlyCamera::apply(const FlyInput& input, float seconds) {
  const bool turns = input.turn_right_px != 0 || input.turn_up_px != 0;
  const bool moves = input.move.x != 0 || input.move.y != 0 || input.move.z != 0;
  if (turns) {
    yaw_ += input.turn_right_px * kTurnPerPixel;
    pitch_ = std::clamp(pitch_ + input.turn_up_px * kTurnPerPixel, -kMaxPitch, kMaxPitch);
  }
  if (moves) {
    const float step = speed_ * seconds;
    position_ +=
        (right() * input.move.x + Vec3f(0, 1, 0) * input.move.y + forward() * input.move.z) * step;
  }
  return turns || moves;
}

CameraDesc FlyCamera::desc() const {
  CameraDesc d = base_;
  d.position = position_;
  d.target = position_ + forward() * target_distance_;
  d.up = Vec3f(0, 1, 0);
  return d;
}

float default_fly_speed(Vec3f bounds_min, Vec3f bounds_max) {
  float diagonal = length(bounds_max - bounds_min);
  return std::isfinite(diagonal) && diagonal > 0 ? diagonal / 4.0f : 1.0f;
}

}  // namespace tuneray
