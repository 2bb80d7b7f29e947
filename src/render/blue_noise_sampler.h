// Blue-noise screen-space sampler (Heitz, Belcour, Ostromoukhov, Coeurjolly, Iehl 2019): each
// pixel draws from the same scrambled (0,2)-sequences, permuted and XOR-scrambled by per-pixel
// keys that were optimised so that neighbouring pixels' errors differ (blue_noise.h). The keys
// tile the image every 128 pixels; the seed offsets the tile.
//
// Falls back to the PCG sampler (same seeding as PcgSampler) for dimensions >= 16 and for
// sample indices >= 256, where the tables end: those samples are white noise, still unbiased.
// Inside the tables the fallback is seeded only when a path first draws past them: most paths
// of an open scene end before (bmw-m6: 88 % of camera rays reach the sky), and the seeding's
// chain of 64-bit multiplies made the start 6.5 % of such a frame's samples at 256 spp (4.9 %
// seeded lazily).
#pragma once

#include <immintrin.h>

#include "render/blue_noise.h"
#include "render/render_settings.h"
#include "render/sampler.h"

namespace tuneray {

class BlueNoiseSampler final : public Sampler {
 public:
  explicit BlueNoiseSampler(uint64_t seed = 0,
                            const BlueNoiseTables& tables = BlueNoiseTables::optimized());
  void start_pixel_sample(uint32_t x, uint32_t y, uint32_t index) override;
  // start_pixel_sample(ids[i]) and next4() of s[i] for four samplers of one seed and tables
  // (their fallbacks seeded in AVX2 lanes): number j goes to first4[j][at + i].
  static void start4(BlueNoiseSampler* const s[4], const PixelSampleId* ids, float* const* first4,
                     size_t at) {
    PcgSampler* fallbacks[4];
    bool any_past_tables = false;
    for (int i = 0; i < 4; ++i) {
      s[i]->start_tables(ids[i].x, ids[i].y, ids[i].index);
      fallbacks[i] = &s[i]->fallback_;
      any_past_tables = any_past_tables || !s[i]->in_table_;
    }
    if (any_past_tables) {
      PcgSampler::start4(fallbacks, ids);
      for (int i = 0; i < 4; ++i) s[i]->fallback_seeded_ = true;
    }
    for (int i = 0; i < 4; ++i) {
      const std::array<float, 4> u = s[i]->next4();
      for (int j = 0; j < 4; ++j) first4[j][at + i] = u[j];
    }
  }
  float next1() override;
  // Inline: the wavefront's sampler bank calls it for every path at every bounce.
  std::array<float, 4> next4() override {
    // Beyond the tables (from the second bounce's BSDF sample on, and every sample from the
    // 257th) the numbers are the fallback's: drawn from it directly, they are what four next1()
    // calls would return after four virtual calls and tests.
    if (!in_table_ || dim_ >= blue_noise::kDims) return seeded_fallback().next4();
    if (dim_ % 4 != 0 || dim_ + 4 > blue_noise::kDims) return Sampler::next4();
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
  std::unique_ptr<Sampler> clone() const override {
    return std::make_unique<BlueNoiseSampler>(*this);
  }
  std::unique_ptr<SamplerBank> make_bank() const override {
    return std::make_unique<SamplerBankOf<BlueNoiseSampler>>(*this);
  }
  // Ask for what the next next4() reads from the tables (the pixel's keys, 80 bytes that may
  // span two lines of a 1.3 MB table, so often not in the nearer caches) ahead of it:
  // SamplerBankOf calls these a few slots early. Always inlined, as Film::prefetch.
  [[gnu::always_inline]] void prefetch_next() const {
    if (in_table_ && dim_ < blue_noise::kDims) prefetch_keys(keys_);
  }
  [[gnu::always_inline]] void prefetch_start(uint32_t x, uint32_t y) const {
    prefetch_keys(&keys_at(x, y));
  }
  // Past its tables every further number comes from the PCG fallback; before, none does.
  Pcg32* generator_for_next_draws() {
    return !in_table_ || dim_ >= blue_noise::kDims ? seeded_fallback().generator_for_next_draws()
                                                   : nullptr;
  }

 private:
  // The keys of pixel (x, y): the tile shifted by the seed's offset.
  const PixelKeys& keys_at(uint32_t x, uint32_t y) const {
    return tables_->keys((x + offset_x_) % blue_noise::kTileSize,
                         (y + offset_y_) % blue_noise::kTileSize);
  }
  [[gnu::always_inline]] static void prefetch_keys(const PixelKeys* keys) {
    __builtin_prefetch(keys);
    __builtin_prefetch(reinterpret_cast<const char*>(keys) + sizeof(PixelKeys) - 1);
  }
  // start_pixel_sample but for the fallback's seeding.
  void start_tables(uint32_t x, uint32_t y, uint32_t index) {
    keys_ = &keys_at(x, y);
    x_ = x;
    y_ = y;
    index_ = index;
    dim_ = 0;
    in_table_ = index < blue_noise::kSamples;
    fallback_seeded_ = false;
  }
  // The fallback, seeded for the current pixel sample on its first use.
  PcgSampler& seeded_fallback() {
    if (!fallback_seeded_) {
      fallback_.start_pixel_sample(x_, y_, index_);
      fallback_seeded_ = true;
    }
    return fallback_;
  }

  const BlueNoiseTables* tables_;
  uint32_t offset_x_, offset_y_;
  const PixelKeys* keys_ = nullptr;
  uint32_t x_ = 0, y_ = 0, index_ = 0;
  int dim_ = 0;
  bool in_table_ = false;  // index < kSamples
  bool fallback_seeded_ = false;
  PcgSampler fallback_;
};

// The sampler a render uses (RenderSettings::quality.sampler).
std::unique_ptr<Sampler> make_sampler(SamplerKind kind, uint64_t seed);

}  // namespace tuneray
