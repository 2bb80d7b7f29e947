#include "render/path_wave.h"

#include <bit>

namespace tuneray {

namespace {

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
    const int planes = with_cache ? kFloatPlanes : kCorePlanes;
    for (int k = 0; k < planes; ++k) {
      std::vector<float>& v = f[static_cast<size_t>(k)];
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
