// Generates primary rays for a CameraDesc: pinhole, or thin lens when lens_radius > 0.
#pragma once

#include "math/ray.h"
#include "render/simd8.h"
#include "scene/camera.h"

namespace tuneray {

class Camera {
 public:
  Camera(const CameraDesc& desc, int width, int height);

  // film_xy: continuous pixel coordinates (x right, y down, [0,width) x [0,height));
  // lens: uniform sample for the aperture (ignored by a pinhole).
  Ray generate_ray(Vec2f film_xy, Vec2f lens) const;
  // generate_ray for eight film points and lens samples at once (ray spans [0, inf)).
  void generate_rays8(simd::F8 film_x, simd::F8 film_y, simd::F8 lens_u, simd::F8 lens_v,
                      simd::V8& org, simd::V8& dir) const;

  const CameraDesc& desc() const { return desc_; }

 private:
  CameraDesc desc_;
  int width_, height_;
  Vec3f origin_, forward_, right_, up_;
  float tan_half_fov_, aspect_, focus_distance_;
};

}  // namespace tuneray
