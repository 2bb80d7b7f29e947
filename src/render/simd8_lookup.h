// Lane-wise lookups in the small tables of shading (a value per light, per material), eight
// lanes at once. A table of at most 16 entries is read with one or two register permutes
// instead of an AVX2 gather, which is microcoded: on this project's AMD Zen 3 machine the
// light sample spent half its time in its gathers (docs/bvh.md, twenty-third session), and
// most scenes have few lights or materials. Larger tables are gathered.
#pragma once

#include <immintrin.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "render/simd8.h"

namespace tuneray::simd {

// The storage a table of `entries` values needs for lookup(): a whole number of registers
// (at least one), so the permutes' loads stay inside it.
inline constexpr size_t lookup_table_size(size_t entries) {
  return std::max<size_t>(kLanes, (entries + kLanes - 1) / kLanes * kLanes);
}

// Pads `table` with zeros to lookup_table_size(table.size()).
template <class T>
void pad_for_lookup(std::vector<T>& table) {
  table.resize(lookup_table_size(table.size()), T{});
}

// Lane i gets table[index[i]]; `entries` is the table's size before padding and every index
// lies below it.
inline F8 lookup(const std::vector<float>& table, size_t entries, I8 index) {
  const float* t = table.data();
  if (entries <= kLanes) return F8(_mm256_permutevar8x32_ps(_mm256_loadu_ps(t), index.v));
  if (entries <= 2 * kLanes) {
    const __m256 low = _mm256_permutevar8x32_ps(_mm256_loadu_ps(t), index.v);
    const __m256 high = _mm256_permutevar8x32_ps(_mm256_loadu_ps(t + kLanes), index.v);
    // Index bit 3 (entries 8-15) moved to the sign bit that blendv reads.
    const __m256 upper = _mm256_castsi256_ps(_mm256_slli_epi32(index.v, 28));
    return F8(_mm256_blendv_ps(low, high, upper));
  }
  return F8(_mm256_i32gather_ps(t, index.v, 4));
}

inline I8 lookup(const std::vector<int32_t>& table, size_t entries, I8 index) {
  const int32_t* t = table.data();
  const auto row = [t](size_t at) {
    return _mm256_loadu_si256(reinterpret_cast<const __m256i*>(t + at));
  };
  if (entries <= kLanes) return I8(_mm256_permutevar8x32_epi32(row(0), index.v));
  if (entries <= 2 * kLanes) {
    const __m256 low = _mm256_castsi256_ps(_mm256_permutevar8x32_epi32(row(0), index.v));
    const __m256 high = _mm256_castsi256_ps(_mm256_permutevar8x32_epi32(row(kLanes), index.v));
    const __m256 upper = _mm256_castsi256_ps(_mm256_slli_epi32(index.v, 28));
    return I8(_mm256_castps_si256(_mm256_blendv_ps(low, high, upper)));
  }
  return I8(_mm256_i32gather_epi32(t, index.v, 4));
}

}  // namespace tuneray::simd
