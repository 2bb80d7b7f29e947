#include <gtest/gtest.h>

#include <cmath>

#include "scene/builtins.h"
#include "view/fly_camera.h"

namespace tuneray {
namespace {

void expect_near(Vec3f a, Vec3f b, float tolerance) {
  EXPECT_NEAR(a.x, b.x, tolerance);
  EXPECT_NEAR(a.y, b.y, tolerance);
  EXPECT_NEAR(a.z, b.z, tolerance);
}

TEST(FlyCamera, KeepsTheViewItStartsFrom) {
  CameraDesc start = look_at("c", Vec3f(1, 2, 3), Vec3f(-2, 0.5f, -1), 50);
  start.lens_radius = 0.1f;
  FlyCamera fly(start, 1);
  CameraDesc d = fly.desc();
  expect_near(d.position, start.position, 0);
  expect_near(d.target, start.target, 1e-5f);
  expect_near(fly.forward(), normalize(start.target - start.position), 1e-6f);
  EXPECT_EQ(d.vfov_deg, 50);
  EXPECT_EQ(d.lens_radius, 0.1f);
}

TEST(FlyCamera, YawAndPitchOfAxisViews) {
  FlyCamera along_x(look_at("x", Vec3f(0), Vec3f(1, 0, 0), 45), 1);
  EXPECT_NEAR(along_x.yaw(), kPi / 2, 1e-6f);
  EXPECT_NEAR(along_x.pitch(), 0, 1e-6f);
  expect_near(along_x.right(), Vec3f(0, 0, 1), 1e-6f);
  FlyCamera down_45(look_at("d", Vec3f(0), Vec3f(0, -1, -1), 45), 1);
  EXPECT_NEAR(down_45.yaw(), 0, 1e-6f);
  EXPECT_NEAR(down_45.pitch(), -kPi / 4, 1e-6f);
}

TEST(FlyCamera, MovesBySpeedTimesTimeAlongItsAxes) {
  FlyCamera fly(look_at("c", Vec3f(0), Vec3f(0, 0, -1), 45), 2);
  FlyInput forward;
  forward.move = Vec3f(0, 0, 1);
  EXPECT_TRUE(fly.apply(forward, 0.5f));
  expect_near(fly.desc().position, Vec3f(0, 0, -1), 1e-6f);
  FlyInput right_up;
  right_up.move = Vec3f(1, 1, 0);
  fly.apply(right_up, 0.25f);
  expect_near(fly.desc().position, Vec3f(0.5f, 0.5f, -1), 1e-6f);
  // Moving does not turn: the target moves with the camera.
  expect_near(fly.desc().target, Vec3f(0.5f, 0.5f, -2), 1e-6f);
}

TEST(FlyCamera, TurnsByMouseMotionAndStopsShortOfVertical) {
  FlyCamera fly(look_at("c", Vec3f(0), Vec3f(0, 0, -1), 45), 1);
  FlyInput turn;
  turn.turn_right_px = 100;
  fly.apply(turn, 0.01f);
  EXPECT_NEAR(fly.yaw(), 100 * FlyCamera::kTurnPerPixel, 1e-6f);
  expect_near(fly.desc().position, Vec3f(0), 0);
  FlyInput up;
  up.turn_up_px = 1e6f;
  fly.apply(up, 0.01f);
  EXPECT_EQ(fly.pitch(), FlyCamera::kMaxPitch);
  // The view is still a valid camera: its direction is not parallel to up.
  EXPECT_GT(length(cross(fly.desc().target - fly.desc().position, fly.desc().up)), 0.01f);
}

TEST(FlyCamera, NoInputIsNoChange) {
  CameraDesc start = look_at("c", Vec3f(1, 1, 1), Vec3f(0), 45);
  FlyCamera fly(start, 3);
  EXPECT_FALSE(fly.apply(FlyInput{}, 1.0f));
  expect_near(fly.desc().position, start.position, 0);
}

TEST(FlyCamera, DefaultSpeedCrossesTheBoxInFourSeconds) {
  EXPECT_FLOAT_EQ(default_fly_speed(Vec3f(0), Vec3f(0, 3, 4)), 5.0f / 4.0f);
  // An empty or degenerate box still gives a usable speed.
  EXPECT_EQ(default_fly_speed(Vec3f(1), Vec3f(1)), 1.0f);
  EXPECT_EQ(default_fly_speed(Vec3f(kInf), Vec3f(-kInf)), 1.0f);
}

}  // namespace
}  // namespace tuneray
