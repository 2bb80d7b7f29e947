#include "render/camera.h"

#include <cmath>

#include "render/sampling.h"

namespace tuneray {

Camera::Camera(const CameraDesc& desc, int width, int height)
    : desc_(desc), width_(width), height_(height) {
  origin_ = desc.position;
  Vec3f to_target = desc.target - desc.position;
  forward_ = length(to_target) > 0 ? normalize(to_target) : Vec3f(0, 0, -1);
  Vec3f up_hint = desc.up;
  if (length(cross(forward_, up_hint)) < 1e-6f)  // looking along up: pick another up
    up_hint = std::abs(forward_.y) < 0.9f ? Vec3f(0, 1, 0) : Vec3f(0, 0, 1);
  right_ = normalize(cross(forward_, up_hint));
  up_ = cross(right_, forward_);
  tan_half_fov_ = std::tan(desc.vfov_deg * 0.5f * kPi / 180.0f);
  aspect_ = static_cast<float>(width) / static_cast<float>(height);
  focus_distance_ = desc.focus_distance > 0 ? desc.focus_distance : length(to_target);
  if (!(focus_distance_ > 0)) focus_distance_ = 1.0f;
}

Ray Camera::generate_ray(Vec2f film_xy, Vec2f lens) const {
  float sx = (2.0f * film_xy.x / width_ - 1.0f) * tan_half_fov_ * aspect_;
  float sy = (1.0f - 2.0f * film_xy.y / height_) * tan_half_fov_;
  Vec3f dir = forward_ + right_ * sx + up_ * sy;
  Ray ray;
  ray.org = origin_;
  if (desc_.lens_radius > 0) {
    // Thin lens: the point on the plane of focus stays fixed; the origin moves on the aperture.
    Vec3f focus_point = origin_ + dir * focus_distance_;
    Vec2f d = sample_concentric_disk(lens) * desc_.lens_radius;
    ray.org = origin_ + right_ * d.x + up_ * d.y;
    dir = focus_point - ray.org;
  }
  ray.dir = normalize(dir);
  return ray;
}

void Camera::generate_rays8(simd::F8 film_x, simd::F8 film_y, simd::F8 lens_u, simd::F8 lens_v,
                            simd::V8& org, simd::V8& dir) const {
  using simd::F8;
  using simd::V8;
  if (desc_.lens_radius > 0) {
    // The thin lens, lane by lane.
    alignas(32) float ox[simd::kLanes], oy[simd::kLanes], oz[simd::kLanes];
    alignas(32) float dx[simd::kLanes], dy[simd::kLanes], dz[simd::kLanes];
    for (int i = 0; i < simd::kLanes; ++i) {
      const Ray r = generate_ray({film_x[i], film_y[i]}, {lens_u[i], lens_v[i]});
      ox[i] = r.org.x, oy[i] = r.org.y, oz[i] = r.org.z;
      dx[i] = r.dir.x, dy[i] = r.dir.y, dz[i] = r.dir.z;
    }
    org = V8(F8::load(ox), F8::load(oy), F8::load(oz));
    dir = V8(F8::load(dx), F8::load(dy), F8::load(dz));
    return;
  }
  const F8 sx = (2.0f * film_x / static_cast<float>(width_) - 1.0f) * tan_half_fov_ * aspect_;
  const F8 sy = (1.0f - 2.0f * film_y / static_cast<float>(height_)) * tan_half_fov_;
  const V8 d = V8(forward_) + V8(right_) * sx + V8(up_) * sy;
  org = V8(origin_);
  dir = d * (1.0f / length(d));
}

}  // namespace tuneray
