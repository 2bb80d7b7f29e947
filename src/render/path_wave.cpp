#include "render/path_wave.h"

#include <bit>

namespace tuneray {

namespace {

// The 8x8 transpose of rows r[0..7] (each eight floats) in place.
void transpose8(__m256 (&r)[8]) {
  const __m256 t0 = _mm256_unpacklo_ps(r[0], r[1]), t1 = _mm256_unpackhi_ps(r[0], r[1]);
  const __m256 t2 = _mm256_unpacklo_ps(r[2], r[3]), t3 = _mm256_unpackhi_ps(r[2], r[3]);
  const __m256 t4 = _mm256_unpacklo_ps(r[4], r[5]), t5 = _mm256_unpackhi_ps(r[4], r[5]);
  const __m256 t6 = _mm256_unpacklo_ps(r[6], r[7]), t7 = _mm256_unpackhi_ps(r[6], r[7]);
  const __m256 s0 = _mm256_shuffle_ps(t0, t2, 0x44), s1 = _mm256_shuffle_ps(t0, t2, 0xEE);
  const __m256 s2 = _mm256_shuffle_ps(t1, t3, 0x44), s3 = _mm256_shuffle_ps(t1, t3, 0xEE);
  const __m256 s4 = _mm256_shuffle_ps(t4, t6, 0x44), s5 = _mm256_shuffle_ps(t4, t6, 0xEE);
  const __m256 s6 = _mm256_shuffle_ps(t5, t7, 0x44), s7 = _mm256_shuffle_ps(t5, t7, 0xEE);
  r[0] = _mm256_permute2f128_ps(s0, s4, 0x20);
  r[1] = _mm256_permute2f128_ps(s1, s5, 0x20);
  r[2] = _mm256_permute2f128_ps(s2, s6, 0x20);
  r[3] = _mm256_permute2f128_ps(s3, s7, 0x20);
  r[4] = _mm256_permute2f128_ps(s0, s4, 0x31);
  r[5] = _mm256_permute2f128_ps(s1, s5, 0x31);
  r[6] = _mm256_permute2f128_ps(s2, s6, 0x31);
  r[7] = _mm256_permute2f128_ps(s3, s7, 0x31);
}

// For each 8-bit mask, the positions of its set bits first: a permutation that packs the kept
// lanes of a register to its front.
struct LeftPack {
  alignas(32) int32_t index[256][8];
  LeftPack() {
    for (int m = 0; m < 256; ++m) {
      int k = 0;
      for (int i = 0; i < 8; ++i)
        if (m & (1 << i)) index[m][k++] = i;
      while (k < 8) index[m][k++] = 0;
    }
  }
};
const LeftPack kLeftPack;

}  // namespace

void PathWave::rays(std::span<Ray> out) const {
  static_assert(sizeof(Ray) == 8 * sizeof(float));
  const float* o[3] = {plane(kOrgX), plane(kOrgY), plane(kOrgZ)};
  const float* d[3] = {plane(kDirX), plane(kDirY), plane(kDirZ)};
  size_t i = 0;
  for (; i + 8 <= size; i += 8) {
    __m256 r[8] = {_mm256_loadu_ps(o[0] + i), _mm256_loadu_ps(o[1] + i), _mm256_loadu_ps(o[2] + i),
                   _mm256_setzero_ps(),       _mm256_loadu_ps(d[0] + i), _mm256_loadu_ps(d[1] + i),
                   _mm256_loadu_ps(d[2] + i), _mm256_set1_ps(kInf)};
    transpose8(r);
    float* dst = reinterpret_cast<float*>(out.data() + i);
    for (int k = 0; k < 8; ++k) _mm256_storeu_ps(dst + 8 * k, r[k]);
  }
  for (; i < size; ++i) out[i] = ray(i);
}

void PathWave::compact(std::span<const uint8_t> alive) {
  size_t kept = 0;
  for (size_t g = 0; g * 8 < size; ++g) {
    const size_t i = g * 8;
    uint32_t mask = alive[g];
    if (i + 8 > size) mask &= (1u << (size - i)) - 1;
    if (mask == 0xff && kept == i) {
      kept += 8;
      continue;
    }
    // Loads before stores: the packed group lands at kept <= i, over lanes already read.
    const __m256i perm = _mm256_load_si256(reinterpret_cast<const __m256i*>(kLeftPack.index[mask]));
    for (auto& v : f) {
      const __m256 x = _mm256_permutevar8x32_ps(_mm256_loadu_ps(v.data() + i), perm);
      _mm256_storeu_ps(v.data() + kept, x);
    }
    for (std::vector<int32_t>* v : {&depth, &flags}) {
      const __m256i x = _mm256_permutevar8x32_epi32(
          _mm256_loadu_si256(reinterpret_cast<const __m256i*>(v->data() + i)), perm);
      _mm256_storeu_si256(reinterpret_cast<__m256i*>(v->data() + kept), x);
    }
    const __m256i x = _mm256_permutevar8x32_epi32(
        _mm256_loadu_si256(reinterpret_cast<const __m256i*>(slot.data() + i)), perm);
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(slot.data() + kept), x);
    kept += static_cast<size_t>(std::popcount(mask));
  }
  size = kept;
}

}  // namespace tuneray
