// PCG32 (O'Neill 2014): small state, good statistical quality, fast. Used by samplers and tools.
#pragma once

#include <immintrin.h>

#include <cstdint>

namespace tuneray {

class Pcg32 {
 public:
  Pcg32() { seed(0x853c49e6748fea9bULL, 0xda3e39cb94b95bdbULL); }
  Pcg32(uint64_t state, uint64_t stream = 0xda3e39cb94b95bdbULL) { seed(state, stream); }

  void seed(uint64_t state, uint64_t stream) {
    state_ = 0;
    inc_ = (stream << 1u) | 1u;
    next_u32();
    state_ += state;
    next_u32();
  }

  uint32_t next_u32() {
    uint64_t old = state_;
    state_ = old * kMultiplier + inc_;
    uint32_t xorshifted = static_cast<uint32_t>(((old >> 18u) ^ old) >> 27u);
    uint32_t rot = static_cast<uint32_t>(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((-rot) & 31));
  }

  // Uniform in [0, 1): 24 random mantissa bits, so 1.0f is never returned.
  float next_float() { return static_cast<float>(next_u32() >> 8) * 0x1p-24f; }

  // The generator's state, for stepping several generators side by side (Pcg32x4).
  uint64_t state() const { return state_; }
  uint64_t increment() const { return inc_; }
  void set_state_and_increment(uint64_t state, uint64_t increment) {
    state_ = state;
    inc_ = increment;
  }

  static constexpr uint64_t kMultiplier = 6364136223846793005ULL;

 private:
  uint64_t state_ = 0, inc_ = 1;
};

// a * b mod 2^64 in each 64-bit lane (AVX2 has no 64-bit multiply: three 32-bit products).
inline __m256i mul64_lanes(__m256i a, uint64_t b) {
  const __m256i b_lo = _mm256_set1_epi64x(static_cast<long long>(b & 0xffffffffu));
  const __m256i b_hi = _mm256_set1_epi64x(static_cast<long long>(b >> 32));
  const __m256i low = _mm256_mul_epu32(a, b_lo);
  const __m256i cross =
      _mm256_add_epi64(_mm256_mul_epu32(_mm256_srli_epi64(a, 32), b_lo), _mm256_mul_epu32(a, b_hi));
  return _mm256_add_epi64(low, _mm256_slli_epi64(cross, 32));
}

// Four Pcg32 generators stepped in AVX2 lanes: next_floats() gives what next_float() of each
// would give, bit for bit (AVX2 has no 64-bit multiply; the product is assembled from three
// 32-bit ones, exact mod 2^64).
class Pcg32x4 {
 public:
  Pcg32x4(const Pcg32* const g[4])
      : state_(_mm256_setr_epi64x(
            static_cast<long long>(g[0]->state()), static_cast<long long>(g[1]->state()),
            static_cast<long long>(g[2]->state()), static_cast<long long>(g[3]->state()))),
        inc_(_mm256_setr_epi64x(
            static_cast<long long>(g[0]->increment()), static_cast<long long>(g[1]->increment()),
            static_cast<long long>(g[2]->increment()), static_cast<long long>(g[3]->increment()))) {
  }

  // Four generators seeded as Pcg32::seed(state[i], stream[i]) would seed them.
  static Pcg32x4 seeded(__m256i state, __m256i stream) {
    const __m256i inc = _mm256_or_si256(_mm256_slli_epi64(stream, 1), _mm256_set1_epi64x(1));
    // seed(): from 0, one step gives inc; plus the state, another step.
    const __m256i first = _mm256_add_epi64(inc, state);
    return Pcg32x4(_mm256_add_epi64(mul64_lanes(first, Pcg32::kMultiplier), inc), inc);
  }

  // The next number of each generator, lane i of the result from generator i.
  __m128 next_floats() {
    const __m256i old = state_;
    state_ = _mm256_add_epi64(mul64_lanes(old, Pcg32::kMultiplier), inc_);
    // The output permutation on each lane's low 32 bits: xorshift, then a rotation by old >> 59.
    const __m256i x = _mm256_srli_epi64(_mm256_xor_si256(_mm256_srli_epi64(old, 18), old), 27);
    const __m256i rot = _mm256_srli_epi64(old, 59);
    const __m256i left =
        _mm256_and_si256(_mm256_sub_epi32(_mm256_setzero_si256(), rot), _mm256_set1_epi32(31));
    const __m256i out = _mm256_or_si256(_mm256_srlv_epi32(x, rot), _mm256_sllv_epi32(x, left));
    const __m128i packed = _mm256_castsi256_si128(
        _mm256_permutevar8x32_epi32(out, _mm256_setr_epi32(0, 2, 4, 6, 0, 2, 4, 6)));
    return _mm_mul_ps(_mm_cvtepi32_ps(_mm_srli_epi32(packed, 8)), _mm_set1_ps(0x1p-24f));
  }

  // Writes the states (and increments) into four generators: those they came from, or after
  // seeded() the ones to be seeded.
  void store(Pcg32* const g[4]) const {
    alignas(32) uint64_t s[4], inc[4];
    _mm256_store_si256(reinterpret_cast<__m256i*>(s), state_);
    _mm256_store_si256(reinterpret_cast<__m256i*>(inc), inc_);
    for (int i = 0; i < 4; ++i) g[i]->set_state_and_increment(s[i], inc[i]);
  }

 private:
  Pcg32x4(__m256i state, __m256i inc) : state_(state), inc_(inc) {}

  __m256i state_, inc_;
};

// Mixes integers into a well-distributed 64-bit seed (SplitMix64 finaliser).
inline uint64_t mix_seed(uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

// mix_seed of each 64-bit lane, bit for bit.
inline __m256i mix_seed_lanes(__m256i x) {
  x = _mm256_add_epi64(x, _mm256_set1_epi64x(static_cast<long long>(0x9e3779b97f4a7c15ULL)));
  x = mul64_lanes(_mm256_xor_si256(x, _mm256_srli_epi64(x, 30)), 0xbf58476d1ce4e5b9ULL);
  x = mul64_lanes(_mm256_xor_si256(x, _mm256_srli_epi64(x, 27)), 0x94d049bb133111ebULL);
  return _mm256_xor_si256(x, _mm256_srli_epi64(x, 31));
}

}  // namespace tuneray
