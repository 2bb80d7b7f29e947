#include "accel/ray_sample.h"

#include <immintrin.h>

#include <cmath>

namespace tuneray::bvh {

namespace {

// A direction component of 0 would make its inverse infinite and (box plane - origin) * inverse
// NaN where the origin lies on the plane; a tiny stand-in keeps every slab distance a number.
float safe_inverse(float d) {
  constexpr float kTiny = 1e-30f;
  if (std::fabs(d) < kTiny) d = std::copysign(kTiny, d);
  return 1.0f / d;
}

}  // namespace

void RaySample::add(const Ray& ray, float length) {
  if (std::isnan(length)) return;  // fmin would take the other operand
  length = std::fmin(length, ray.tfar);
  if (!is_finite(ray.org) || !is_finite(ray.dir) || !std::isfinite(length) || !(length >= 0.0f) ||
      (ray.dir.x == 0.0f && ray.dir.y == 0.0f && ray.dir.z == 0.0f))
    return;
  if (size_ % 8 == 0) {
    for (auto* plane : {&ox_, &oy_, &oz_, &ix_, &iy_, &iz_}) plane->resize(size_ + 8, 0.0f);
    length_.resize(size_ + 8, -1.0f);
  }
  ox_[size_] = ray.org.x, oy_[size_] = ray.org.y, oz_[size_] = ray.org.z;
  ix_[size_] = safe_inverse(ray.dir.x);
  iy_[size_] = safe_inverse(ray.dir.y);
  iz_[size_] = safe_inverse(ray.dir.z);
  length_[size_] = length;
  ++size_;
}

float RaySample::visit_share(const BBox& box) const {
  if (size_ == 0 || box.empty()) return 0.0f;
  const __m256 lo[3] = {_mm256_set1_ps(box.lo.x), _mm256_set1_ps(box.lo.y),
                        _mm256_set1_ps(box.lo.z)};
  const __m256 hi[3] = {_mm256_set1_ps(box.hi.x), _mm256_set1_ps(box.hi.y),
                        _mm256_set1_ps(box.hi.z)};
  const float* org[3] = {ox_.data(), oy_.data(), oz_.data()};
  const float* inv[3] = {ix_.data(), iy_.data(), iz_.data()};
  size_t count = 0;
  for (size_t i = 0; i < length_.size(); i += 8) {
    __m256 enter = _mm256_setzero_ps();
    __m256 leave = _mm256_loadu_ps(length_.data() + i);
    for (int a = 0; a < 3; ++a) {
      const __m256 o = _mm256_loadu_ps(org[a] + i), d = _mm256_loadu_ps(inv[a] + i);
      const __m256 t0 = _mm256_mul_ps(_mm256_sub_ps(lo[a], o), d);
      const __m256 t1 = _mm256_mul_ps(_mm256_sub_ps(hi[a], o), d);
      enter = _mm256_max_ps(enter, _mm256_min_ps(t0, t1));
      leave = _mm256_min_ps(leave, _mm256_max_ps(t0, t1));
    }
    const int through = _mm256_movemask_ps(_mm256_cmp_ps(enter, leave, _CMP_LE_OQ));
    count += static_cast<size_t>(__builtin_popcount(static_cast<unsigned>(through)));
  }
  return static_cast<float>(count) / static_cast<float>(size_);
}

BoxMeasure::BoxMeasure(const RaySample* rays, float ray_weight, const BBox& scene) {
  const float area = scene.surface_area();
  if (!rays || rays->empty() || !(ray_weight > 0.0f) || !(area > 0.0f)) return;
  rays_ = rays;
  ray_weight_ = ray_weight > 1.0f ? 1.0f : ray_weight;
  area_weight_ = (1.0f - ray_weight_) / area;
}

}  // namespace tuneray::bvh
