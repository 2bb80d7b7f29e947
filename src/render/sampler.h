// Per-pixel sample generators. The integrator asks for dimensions in order; `next4` fetches
// four dimensions in one call (the blue-noise sampler reads them with one 16-byte load).
#pragma once

#include <array>
#include <cstdint>
#include <memory>

#include "math/rng.h"
#include "math/vec.h"

namespace tuneray {

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
};

// Independent uniform samples from PCG32, seeded from (seed, pixel, sample index) so that any
// pixel sample can be regenerated independently of thread scheduling (determinism).
class PcgSampler final : public Sampler {
 public:
  explicit PcgSampler(uint64_t seed = 0) : seed_(seed) {}
  void start_pixel_sample(uint32_t x, uint32_t y, uint32_t index) override {
    uint64_t pixel = (static_cast<uint64_t>(y) << 32) | x;
    rng_.seed(mix_seed(pixel ^ mix_seed(seed_)), mix_seed(index + 0x9e3779b9ULL * (seed_ + 1)));
  }
  float next1() override { return rng_.next_float(); }
  // The same four numbers as four next1() calls, without a virtual call per number.
  std::array<float, 4> next4() override {
    std::array<float, 4> r;
    for (auto& v : r) v = rng_.next_float();
    return r;
  }
  std::unique_ptr<Sampler> clone() const override { return std::make_unique<PcgSampler>(*this); }

 private:
  uint64_t seed_;
  Pcg32 rng_;
};

}  // namespace tuneray
