// Per-pixel sample generators. The integrator asks for dimensions in order; `next4` fetches
// four dimensions in one call (the blue-noise sampler reads them with one 16-byte load).
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "math/rng.h"
#include "math/vec.h"

namespace tuneray {

class SamplerBank;

class Sampler {
 public:
  virtual ~Sampler() = default;
  // Positions the sampler at sample `index` of pixel (x, y); dimensions restart at 0.
  virtual void start_pixel_sample(uint32_t x, uint32_t y, uint32_t index) = 0;
  virtual float next1() = 0;
  virtual Vec2f next2() {
    float a = next1();
    return {a, next1()};
  }
  virtual std::array<float, 4> next4() {
    std::array<float, 4> r;
    for (auto& v : r) v = next1();
    return r;
  }
  virtual std::unique_ptr<Sampler> clone() const = 0;
  // A bank of copies of this sampler, one per path slot of a batch scheduler.
  virtual std::unique_ptr<SamplerBank> make_bank() const = 0;
};

// Which pixel sample a path slot draws: sample `index` of pixel (x, y).
struct PixelSampleId {
  uint32_t x = 0, y = 0, index = 0;
};

// One sampler per path slot for a wavefront scheduler, asked for whole waves of numbers at once:
// one virtual call per wave instead of one per quadruple, and the samplers lie side by side
// instead of behind a pointer each. Slot k gives exactly the numbers a lone sampler started at
// the same pixel sample would give.
class SamplerBank {
 public:
  virtual ~SamplerBank() = default;
  // Starts slots [first, first + ids.size()) at their pixel samples; number j of slot
  // first + i's first four (the camera sample) goes to first4[j][i].
  virtual void start(size_t first, std::span<const PixelSampleId> ids, float* const* first4) = 0;
  // For each listed slot slots[k], its next `quads` quadruples: number j of quadruple q goes to
  // planes[4 * q + j][positions[k]].
  virtual void next4(std::span<const uint32_t> slots, std::span<const uint32_t> positions,
                     int quads, float* const* planes) = 0;
};

// The bank of a concrete (final) sampler type: its calls are direct and inline.
template <class S>
class SamplerBankOf final : public SamplerBank {
 public:
  explicit SamplerBankOf(const S& prototype) : prototype_(prototype) {}
  void start(size_t first, std::span<const PixelSampleId> ids, float* const* first4) override {
    if (samplers_.size() < first + ids.size()) samplers_.resize(first + ids.size(), prototype_);
    size_t i = 0;
    // Samplers that read tables ask for a start's lines this many ids ahead.
    prefetch_starts(ids, 0, kStartPrefetchAhead);
    // Samplers that can seed four at once (their seeding is a chain of 64-bit multiplies).
    if constexpr (requires(S * s[4], const PixelSampleId* id, float* const* out, size_t at) {
                    S::start4(s, id, out, at);
                  }) {
      for (; i + 4 <= ids.size(); i += 4) {
        prefetch_starts(ids, i + kStartPrefetchAhead, 4);
        S* s[4];
        for (int j = 0; j < 4; ++j) s[j] = &samplers_[first + i + j];
        S::start4(s, &ids[i], first4, i);
      }
    }
    for (; i < ids.size(); ++i) {
      S& s = samplers_[first + i];
      s.start_pixel_sample(ids[i].x, ids[i].y, ids[i].index);
      const std::array<float, 4> u = s.S::next4();
      for (int j = 0; j < 4; ++j) first4[j][i] = u[j];
    }
  }
  void next4(std::span<const uint32_t> slots, std::span<const uint32_t> positions, int quads,
             float* const* planes) override {
    size_t k = 0;
    for (size_t j = 0; j < std::min(kPrefetchAhead, slots.size()); ++j) prefetch_next(slots[j]);
    // Four slots at a time whose numbers all come from their PCG generators (every PcgSampler;
    // a blue-noise sampler past its tables) step those generators in AVX2 lanes.
    for (; k + 4 <= slots.size(); k += 4) {
      for (size_t j = k + kPrefetchAhead; j < std::min(slots.size(), k + kPrefetchAhead + 4); ++j)
        prefetch_next(slots[j]);
      Pcg32* g[4];
      bool lanes = true;
      for (int j = 0; j < 4; ++j) {
        g[j] = samplers_[slots[k + j]].generator_for_next_draws();
        lanes = lanes && g[j];
      }
      if (!lanes) {
        for (int j = 0; j < 4; ++j) draw(k + j, slots, positions, quads, planes);
        continue;
      }
      Pcg32x4 x(g);
      // Four side by side (the usual case: most paths of a wave draw) take one store.
      const uint32_t p0 = positions[k];
      if (positions[k + 1] == p0 + 1 && positions[k + 2] == p0 + 2 && positions[k + 3] == p0 + 3) {
        for (int n = 0; n < 4 * quads; ++n) _mm_storeu_ps(planes[n] + p0, x.next_floats());
      } else {
        for (int n = 0; n < 4 * quads; ++n) {
          alignas(16) float u[4];
          _mm_store_ps(u, x.next_floats());
          for (int j = 0; j < 4; ++j) planes[n][positions[k + j]] = u[j];
        }
      }
      x.store(g);
    }
    for (; k < slots.size(); ++k) draw(k, slots, positions, quads, planes);
  }

 private:
  static constexpr size_t kPrefetchAhead = 8;
  // A start is a few dozen cycles once its fallback is seeded lazily, shorter than a table
  // line's trip from L3, so its lines are asked for further ahead than a draw's.
  static constexpr size_t kStartPrefetchAhead = 32;
  // The lines a table-reading sampler's next draw or start needs (none for the others).
  [[gnu::always_inline]] void prefetch_next(uint32_t slot) const {
    if constexpr (requires(const S& s) { s.prefetch_next(); }) samplers_[slot].prefetch_next();
  }
  [[gnu::always_inline]] void prefetch_starts(std::span<const PixelSampleId> ids, size_t from,
                                              size_t count) const {
    if constexpr (requires(const S& s, uint32_t x) { s.prefetch_start(x, x); }) {
      for (size_t j = from; j < std::min(ids.size(), from + count); ++j)
        prototype_.prefetch_start(ids[j].x, ids[j].y);
    }
  }
  void draw(size_t k, std::span<const uint32_t> slots, std::span<const uint32_t> positions,
            int quads, float* const* planes) {
    S& s = samplers_[slots[k]];
    for (int q = 0; q < quads; ++q) {
      const std::array<float, 4> u = s.S::next4();
      for (int j = 0; j < 4; ++j) planes[4 * q + j][positions[k]] = u[j];
    }
  }

  S prototype_;
  std::vector<S> samplers_;
};

// Independent uniform samples from PCG32, seeded from (seed, pixel, sample index) so that any
// pixel sample can be regenerated independently of thread scheduling (determinism).
class PcgSampler final : public Sampler {
 public:
  explicit PcgSampler(uint64_t seed = 0) : seed_(seed) {}
  void start_pixel_sample(uint32_t x, uint32_t y, uint32_t index) override {
    rng_.seed(mix_seed(pixel_word(x, y) ^ pixel_key()), mix_seed(index + index_offset()));
  }
  // start_pixel_sample(ids[i]) of s[i] for four samplers of one seed, in AVX2 lanes (the
  // seeding is a chain of 64-bit multiplies per sampler).
  static void start4(PcgSampler* const s[4], const PixelSampleId* ids) {
    seeded4(s, ids).store(generators(s).data());
  }
  // start4, then next4() of s[i]: number j goes to first4[j][at + i].
  static void start4(PcgSampler* const s[4], const PixelSampleId* ids, float* const* first4,
                     size_t at) {
    Pcg32x4 x = seeded4(s, ids);
    for (int j = 0; j < 4; ++j) _mm_storeu_ps(first4[j] + at, x.next_floats());
    x.store(generators(s).data());
  }
  float next1() override { return rng_.next_float(); }
  // The same four numbers as four next1() calls, without a virtual call per number.
  std::array<float, 4> next4() override {
    std::array<float, 4> r;
    for (auto& v : r) v = rng_.next_float();
    return r;
  }
  std::unique_ptr<Sampler> clone() const override { return std::make_unique<PcgSampler>(*this); }
  std::unique_ptr<SamplerBank> make_bank() const override {
    return std::make_unique<SamplerBankOf<PcgSampler>>(*this);
  }
  // The generator every further number comes from (SamplerBankOf steps four side by side).
  Pcg32* generator_for_next_draws() { return &rng_; }

 private:
  // The seeding's inputs: the pixel as one word, mixed with a key of the seed; the sample index
  // offset by the seed.
  static uint64_t pixel_word(uint32_t x, uint32_t y) {
    return (static_cast<uint64_t>(y) << 32) | x;
  }
  uint64_t pixel_key() const { return mix_seed(seed_); }
  uint64_t index_offset() const { return 0x9e3779b9ULL * (seed_ + 1); }

  static std::array<Pcg32*, 4> generators(PcgSampler* const s[4]) {
    return {&s[0]->rng_, &s[1]->rng_, &s[2]->rng_, &s[3]->rng_};
  }
  // start_pixel_sample's seeding for four samplers of one seed, as four generators in lanes.
  static Pcg32x4 seeded4(PcgSampler* const s[4], const PixelSampleId* ids) {
    alignas(32) uint64_t pixel[4], index[4];
    for (int j = 0; j < 4; ++j) {
      pixel[j] = pixel_word(ids[j].x, ids[j].y);
      index[j] = ids[j].index;
    }
    const auto lanes = [](const uint64_t* v) {
      return _mm256_load_si256(reinterpret_cast<const __m256i*>(v));
    };
    const auto all = [](uint64_t v) { return _mm256_set1_epi64x(static_cast<long long>(v)); };
    return Pcg32x4::seeded(
        mix_seed_lanes(_mm256_xor_si256(lanes(pixel), all(s[0]->pixel_key()))),
        mix_seed_lanes(_mm256_add_epi64(lanes(index), all(s[0]->index_offset()))));
  }

  uint64_t seed_;
  Pcg32 rng_;
};

}  // namespace tuneray
