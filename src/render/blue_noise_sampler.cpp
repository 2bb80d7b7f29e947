#include "render/blue_noise_sampler.h"

#include <immintrin.h>

namespace tuneray {

using namespace blue_noise;

BlueNoiseSampler::BlueNoiseSampler(uint64_t seed, const BlueNoiseTables& tables)
    : tables_(&tables), fallback_(seed) {
  // Seed 0 is the tile as optimised; other seeds see it shifted (independent-looking noise).
  uint64_t h = seed == 0 ? 0 : mix_seed(seed);
  offset_x_ = static_cast<uint32_t>(h) % kTileSize;
  offset_y_ = static_cast<uint32_t>(h >> 32) % kTileSize;
}

void BlueNoiseSampler::start_pixel_sample(uint32_t x, uint32_t y, uint32_t index) {
  keys_ = &tables_->keys((x + offset_x_) % kTileSize, (y + offset_y_) % kTileSize);
  index_ = index;
  dim_ = 0;
  in_table_ = index < kSamples;
  fallback_.start_pixel_sample(x, y, index);
}

float BlueNoiseSampler::next1() {
  if (!in_table_ || dim_ >= kDims) return fallback_.next1();
  return bits_to_unit_float(BlueNoiseTables::value_bits(*tables_, *keys_, index_, dim_++));
}

std::array<float, 4> BlueNoiseSampler::next4() {
  // Beyond the tables (from the second bounce's BSDF sample on, and every sample from the 257th)
  // the numbers are the fallback's: drawn from it directly, they are what four next1() calls
  // would return after four virtual calls and tests.
  if (!in_table_ || dim_ >= kDims) return fallback_.next4();
  if (dim_ % 4 != 0 || dim_ + 4 > kDims) return Sampler::next4();
  const int q = dim_ / 4;
  dim_ += 4;
  // One aligned 16-byte load for the quadruple's base values and one for its scrambling keys.
  const uint32_t* row = tables_->base(index_ ^ keys_->rank.k[q]) + 4 * q;
  __m128i bits =
      _mm_xor_si128(_mm_load_si128(reinterpret_cast<const __m128i*>(row)),
                    _mm_load_si128(reinterpret_cast<const __m128i*>(keys_->scramble[q].k)));
  __m128 u = _mm_mul_ps(_mm_cvtepi32_ps(_mm_srli_epi32(bits, 8)), _mm_set1_ps(0x1p-24f));
  std::array<float, 4> out;
  _mm_storeu_ps(out.data(), u);
  return out;
}

std::unique_ptr<Sampler> make_sampler(SamplerKind kind, uint64_t seed) {
  if (kind == SamplerKind::kBlueNoise) return std::make_unique<BlueNoiseSampler>(seed);
  return std::make_unique<PcgSampler>(seed);
}

}  // namespace tuneray
