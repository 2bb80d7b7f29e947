// Blue-noise screen-space sampler (Heitz, Belcour, Ostromoukhov, Coeurjolly, Iehl 2019): each
// pixel draws from the same scrambled (0,2)-sequences, permuted and XOR-scrambled by per-pixel
// keys that were optimised so that neighbouring pixels' errors differ (blue_noise.h). The keys
// tile the image every 128 pixels; the seed offsets the tile.
//
// Falls back to the PCG sampler (same seeding as PcgSampler) for dimensions >= 16 and for
// sample indices >= 256, where the tables end: those samples are white noise, still unbiased.
#pragma once

#include "render/blue_noise.h"
#include "render/render_settings.h"
#include "render/sampler.h"

namespace tuneray {

class BlueNoiseSampler final : public Sampler {
 public:
  explicit BlueNoiseSampler(uint64_t seed = 0,
                            const BlueNoiseTables& tables = BlueNoiseTables::optimized());
  void start_pixel_sample(uint32_t x, uint32_t y, uint32_t index) override;
  float next1() override;
  std::array<float, 4> next4() override;
  std::unique_ptr<Sampler> clone() const override {
    return std::make_unique<BlueNoiseSampler>(*this);
  }
  std::unique_ptr<SamplerBank> make_bank() const override {
    return std::make_unique<SamplerBankOf<BlueNoiseSampler>>(*this);
  }

 private:
  const BlueNoiseTables* tables_;
  uint32_t offset_x_, offset_y_;
  const PixelKeys* keys_ = nullptr;
  uint32_t index_ = 0;
  int dim_ = 0;
  bool in_table_ = false;  // index < kSamples
  PcgSampler fallback_;
};

// The sampler a render uses (RenderSettings::quality.sampler).
std::unique_ptr<Sampler> make_sampler(SamplerKind kind, uint64_t seed);

}  // namespace tuneray
