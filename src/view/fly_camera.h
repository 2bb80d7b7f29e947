// The viewer's free-flying camera: a position, a heading (yaw) and a pitch, moved by WASD keys
// and turned by the mouse. It starts from, and turns back into, a scene CameraDesc, so a flight
// can begin at a scene camera or a path's keyframe and be recorded as keyframes.
#pragma once

#include "math/vec.h"
#include "scene/camera.h"

namespace tuneray {

// How far the camera is asked to move in one frame, in its own frame of reference (x right,
// y world up, z forward), each component in [-1, 1]; scaled by speed and time.
struct FlyInput {
  Vec3f move{0, 0, 0};
  float turn_right_px = 0;  // mouse motion in pixels
  float turn_up_px = 0;
};

class FlyCamera {
 public:
  // `desc` gives the view (its up vector is replaced by world y: a flying camera does not
  // roll); `speed` is in scene units per second.
  FlyCamera(const CameraDesc& desc, float speed);

  // Moves and turns; returns true when the view changed.
  bool apply(const FlyInput& input, float seconds);

  // Unit vector the camera looks along.
  Vec3f forward() const;
  Vec3f right() const;
  // The camera as a scene camera: the target in front at the starting focus distance, so a
  // thin lens keeps its focus.
  CameraDesc desc() const;
  void set_desc(const CameraDesc& desc);

  float yaw() const { return yaw_; }
  float pitch() const { return pitch_; }

  // Radians the view turns per pixel of mouse motion.
  static constexpr float kTurnPerPixel = 0.003f;
  // The pitch stops short of straight up or down, where yaw would be undefined.
  static constexpr float kMaxPitch = 1.55f;

 private:
  CameraDesc base_;  // fov, lens and name of the camera it started from
  Vec3f position_;
  float yaw_ = 0, pitch_ = 0;  // yaw 0 looks along -z, positive yaw turns right
  float target_distance_ = 1;
  float speed_;
};

// A flying speed that crosses the scene in about four seconds (from its bounding box diagonal).
float default_fly_speed(Vec3f bounds_min, Vec3f bounds_max);

}  // namespace tuneray
