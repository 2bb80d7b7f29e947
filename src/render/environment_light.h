// The environment as a light: a constant colour or an equirectangular map, importance sampled
// by luminance x sin(theta). Convention: +y is up; v = theta / pi (row 0 = straight up);
// u = (atan2(x, -z) + pi) / (2 pi), so the centre of the image is the direction -z.
#pragma once

#include "image/image.h"
#include "math/vec.h"
#include "render/sampling.h"
#include "scene/scene.h"

namespace tuneray {

struct EnvironmentSample {
  Vec3f wi;
  Color radiance{0.0f};
  float pdf = 0;  // solid angle
};

class EnvironmentLight {
 public:
  EnvironmentLight() = default;
  explicit EnvironmentLight(const Environment& env);

  bool active() const { return active_; }
  Color eval(Vec3f dir) const;
  EnvironmentSample sample(Vec2f u) const;
  float pdf(Vec3f dir) const;
  // Average radiance, for the light-selection weight.
  float mean_luminance() const { return mean_luminance_; }

  static Vec2f direction_to_uv(Vec3f dir);
  static Vec3f uv_to_direction(Vec2f uv);

 private:
  bool active_ = false;
  Color constant_{0.0f};
  const Image* map_ = nullptr;
  float scale_ = 1.0f;
  Distribution2D distribution_;
  float mean_luminance_ = 0;
};

}  // namespace tuneray
