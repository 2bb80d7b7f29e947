// Eight float lanes in one AVX2 register, for shading eight paths at once (render/shade8.h).
// Comparisons give masks in the same register type; `select(m, a, b)` takes a where m is set.
// Every operation works lane by lane, so a path's result never depends on which other paths
// share its register: the schedulers may group paths as they like and still agree bit for bit.
#pragma once

#include <immintrin.h>

#include <cstdint>

#include "math/vec.h"

namespace tuneray::simd {

inline constexpr int kLanes = 8;

struct M8 {
  __m256 v;
  M8() = default;
  explicit M8(__m256 x) : v(x) {}
  // From the low 8 bits of `bits` (bit i = lane i).
  static M8 from_bits(uint32_t bits) {
    const __m256i lane_bit = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
    const __m256i set = _mm256_and_si256(_mm256_set1_epi32(static_cast<int>(bits)), lane_bit);
    return M8(_mm256_castsi256_ps(_mm256_cmpeq_epi32(set, lane_bit)));
  }
  static M8 all() { return M8(_mm256_castsi256_ps(_mm256_set1_epi32(-1))); }
  static M8 none() { return M8(_mm256_setzero_ps()); }
  uint32_t bits() const { return static_cast<uint32_t>(_mm256_movemask_ps(v)); }
  bool any() const { return bits() != 0; }
  M8 operator&(M8 o) const { return M8(_mm256_and_ps(v, o.v)); }
  M8 operator|(M8 o) const { return M8(_mm256_or_ps(v, o.v)); }
  M8 operator!() const { return M8(_mm256_xor_ps(v, all().v)); }
  M8& operator&=(M8 o) { return *this = *this & o; }
  M8& operator|=(M8 o) { return *this = *this | o; }
  // This mask without the lanes of `o`.
  M8 and_not(M8 o) const { return M8(_mm256_andnot_ps(o.v, v)); }
};

struct F8 {
  __m256 v;
  F8() = default;
  F8(float s) : v(_mm256_set1_ps(s)) {}  // NOLINT: broadcasting constants reads naturally
  explicit F8(__m256 x) : v(x) {}
  static F8 load(const float* p) { return F8(_mm256_loadu_ps(p)); }
  void store(float* p) const { _mm256_storeu_ps(p, v); }
  float operator[](int i) const {
    alignas(32) float a[kLanes];
    _mm256_store_ps(a, v);
    return a[i];
  }

  F8 operator-() const { return F8(_mm256_xor_ps(v, _mm256_set1_ps(-0.0f))); }
  F8 operator+(F8 o) const { return F8(_mm256_add_ps(v, o.v)); }
  F8 operator-(F8 o) const { return F8(_mm256_sub_ps(v, o.v)); }
  F8 operator*(F8 o) const { return F8(_mm256_mul_ps(v, o.v)); }
  F8 operator/(F8 o) const { return F8(_mm256_div_ps(v, o.v)); }
  F8& operator+=(F8 o) { return *this = *this + o; }
  F8& operator-=(F8 o) { return *this = *this - o; }
  F8& operator*=(F8 o) { return *this = *this * o; }

  // Ordered comparisons: false where either side is NaN (as in scalar C++), except !=.
  M8 operator<(F8 o) const { return M8(_mm256_cmp_ps(v, o.v, _CMP_LT_OQ)); }
  M8 operator<=(F8 o) const { return M8(_mm256_cmp_ps(v, o.v, _CMP_LE_OQ)); }
  M8 operator>(F8 o) const { return M8(_mm256_cmp_ps(v, o.v, _CMP_GT_OQ)); }
  M8 operator>=(F8 o) const { return M8(_mm256_cmp_ps(v, o.v, _CMP_GE_OQ)); }
  M8 operator==(F8 o) const { return M8(_mm256_cmp_ps(v, o.v, _CMP_EQ_OQ)); }
  M8 operator!=(F8 o) const { return M8(_mm256_cmp_ps(v, o.v, _CMP_NEQ_UQ)); }
};

inline F8 operator+(float a, F8 b) {
  return F8(a) + b;
}
inline F8 operator-(float a, F8 b) {
  return F8(a) - b;
}
inline F8 operator*(float a, F8 b) {
  return F8(a) * b;
}
inline F8 operator/(float a, F8 b) {
  return F8(a) / b;
}

inline F8 select(M8 m, F8 a, F8 b) {
  return F8(_mm256_blendv_ps(b.v, a.v, m.v));
}
inline M8 select(M8 m, M8 a, M8 b) {
  return M8(_mm256_blendv_ps(b.v, a.v, m.v));
}
inline F8 sqrt(F8 a) {
  return F8(_mm256_sqrt_ps(a.v));
}
inline F8 abs(F8 a) {
  return F8(_mm256_andnot_ps(_mm256_set1_ps(-0.0f), a.v));
}
// min/max as std::min/std::max of scalar code: the first argument when the comparison fails
// (e.g. on NaN), so a guard written with them behaves as in the scalar code.
inline F8 min(F8 a, F8 b) {
  return select(b < a, b, a);
}
inline F8 max(F8 a, F8 b) {
  return select(a < b, b, a);
}
inline F8 fma(F8 a, F8 b, F8 c) {
  return F8(_mm256_fmadd_ps(a.v, b.v, c.v));
}
inline F8 copysign(F8 magnitude, F8 sign) {
  const __m256 s = _mm256_set1_ps(-0.0f);
  return F8(_mm256_or_ps(_mm256_andnot_ps(s, magnitude.v), _mm256_and_ps(s, sign.v)));
}
// Lanes that are neither inf nor NaN.
inline M8 is_finite(F8 a) {
  return abs(a) <= F8(3.40282347e38f);
}
// Clears the lanes outside m (to +0).
inline F8 keep(M8 m, F8 a) {
  return F8(_mm256_and_ps(m.v, a.v));
}

// Three lanes-of-floats: eight 3-vectors (positions, directions, colours).
struct V8 {
  F8 x, y, z;
  V8() = default;
  V8(F8 x_, F8 y_, F8 z_) : x(x_), y(y_), z(z_) {}
  explicit V8(F8 s) : x(s), y(s), z(s) {}
  explicit V8(Vec3f v) : x(v.x), y(v.y), z(v.z) {}
  V8 operator-() const { return {-x, -y, -z}; }
  V8 operator+(const V8& o) const { return {x + o.x, y + o.y, z + o.z}; }
  V8 operator-(const V8& o) const { return {x - o.x, y - o.y, z - o.z}; }
  V8 operator*(const V8& o) const { return {x * o.x, y * o.y, z * o.z}; }
  V8 operator*(F8 s) const { return {x * s, y * s, z * s}; }
  V8 operator/(F8 s) const { return {x / s, y / s, z / s}; }
  V8& operator+=(const V8& o) { return *this = *this + o; }
  V8& operator*=(const V8& o) { return *this = *this * o; }
  V8& operator*=(F8 s) { return *this = *this * s; }
  // Lane i as a scalar vector.
  Vec3f lane(int i) const { return {x[i], y[i], z[i]}; }
};

inline F8 dot(const V8& a, const V8& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
inline V8 cross(const V8& a, const V8& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline F8 length(const V8& v) {
  return sqrt(dot(v, v));
}
inline V8 normalize(const V8& v) {
  return v / length(v);
}
inline V8 select(M8 m, const V8& a, const V8& b) {
  return {select(m, a.x, b.x), select(m, a.y, b.y), select(m, a.z, b.z)};
}
inline V8 keep(M8 m, const V8& a) {
  return {keep(m, a.x), keep(m, a.y), keep(m, a.z)};
}
inline F8 max_component(const V8& v) {
  return max(v.x, max(v.y, v.z));
}
inline M8 is_finite(const V8& v) {
  return is_finite(v.x) & is_finite(v.y) & is_finite(v.z);
}

// Eight 32-bit integers.
struct I8 {
  __m256i v;
  I8() = default;
  I8(int32_t s) : v(_mm256_set1_epi32(s)) {}  // NOLINT: as F8
  explicit I8(__m256i x) : v(x) {}
  static I8 load(const int32_t* p) {
    return I8(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(p)));
  }
  void store(int32_t* p) const { _mm256_storeu_si256(reinterpret_cast<__m256i*>(p), v); }
  I8 operator+(I8 o) const { return I8(_mm256_add_epi32(v, o.v)); }
  M8 operator==(I8 o) const { return M8(_mm256_castsi256_ps(_mm256_cmpeq_epi32(v, o.v))); }
  M8 operator>(I8 o) const { return M8(_mm256_castsi256_ps(_mm256_cmpgt_epi32(v, o.v))); }
  M8 operator>=(I8 o) const { return !(o > *this); }
  M8 operator<(I8 o) const { return o > *this; }
};
inline I8 select(M8 m, I8 a, I8 b) {
  return I8(_mm256_castps_si256(
      _mm256_blendv_ps(_mm256_castsi256_ps(b.v), _mm256_castsi256_ps(a.v), m.v)));
}

// sin and cos of 2 pi u for u in [0, 1): reduced to [-pi/4, pi/4] around the nearest quarter
// turn, where the series of sampling.h (sin_quarter, cos_quarter) hold to float precision.
inline void sincos_turn(F8 u, F8& s, F8& c) {
  const F8 t = u * 4.0f;
  const F8 k = F8(_mm256_round_ps(t.v, _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC));
  const F8 r = (t - k) * (kPi / 2);
  const F8 r2 = r * r;
  const F8 sr = r * (1.0f - r2 * (1.0f / 6) *
                                (1.0f - r2 * (1.0f / 20) *
                                            (1.0f - r2 * (1.0f / 42) * (1.0f - r2 * (1.0f / 72)))));
  const F8 cr =
      1.0f - r2 * 0.5f *
                 (1.0f - r2 * (1.0f / 12) *
                             (1.0f - r2 * (1.0f / 30) *
                                         (1.0f - r2 * (1.0f / 56) * (1.0f - r2 * (1.0f / 90)))));
  const __m256i q = _mm256_and_si256(_mm256_cvtps_epi32(k.v), _mm256_set1_epi32(3));
  const M8 odd(_mm256_castsi256_ps(
      _mm256_cmpeq_epi32(_mm256_and_si256(q, _mm256_set1_epi32(1)), _mm256_set1_epi32(1))));
  const M8 sin_negative(_mm256_castsi256_ps(_mm256_cmpgt_epi32(q, _mm256_set1_epi32(1))));
  const M8 cos_negative(_mm256_castsi256_ps(_mm256_cmpeq_epi32(
      _mm256_and_si256(_mm256_add_epi32(q, _mm256_set1_epi32(1)), _mm256_set1_epi32(2)),
      _mm256_set1_epi32(2))));
  s = select(odd, cr, sr);
  c = select(odd, sr, cr);
  s = select(sin_negative, -s, s);
  c = select(cos_negative, -c, c);
}

// Loads lane i from `values[i]` (eight scalars gathered by the caller's loop).
inline F8 from_lanes(const float (&values)[kLanes]) {
  return F8::load(values);
}

}  // namespace tuneray::simd
