#include "accel/ray_planes.h"

#include <immintrin.h>

#include "math/transpose8.h"

namespace tuneray {

void rays_from_planes(const RayPlanes& planes, std::span<Ray> out) {
  static_assert(sizeof(Ray) == 8 * sizeof(float));
  const auto& o = planes.org;
  const auto& d = planes.dir;
  size_t i = 0;
  for (; i + 8 <= planes.size; i += 8) {
    __m256 r[8] = {_mm256_loadu_ps(o[0] + i), _mm256_loadu_ps(o[1] + i), _mm256_loadu_ps(o[2] + i),
                   _mm256_setzero_ps(),       _mm256_loadu_ps(d[0] + i), _mm256_loadu_ps(d[1] + i),
                   _mm256_loadu_ps(d[2] + i), _mm256_set1_ps(kInf)};
    transpose8(r);
    float* dst = reinterpret_cast<float*>(out.data() + i);
    for (int k = 0; k < 8; ++k) _mm256_storeu_ps(dst + 8 * k, r[k]);
  }
  for (; i < planes.size; ++i) out[i] = planes.ray(i);
}

}  // namespace tuneray
