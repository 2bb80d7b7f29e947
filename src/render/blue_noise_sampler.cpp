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
  start_tables(x, y, index);
  if (!in_table_) seeded_fallback();
}

float BlueNoiseSampler::next1() {
  if (!in_table_ || dim_ >= kDims) return seeded_fallback().next1();
  return bits_to_unit_float(BlueNoiseTables::value_bits(*tables_, *keys_, index_, dim_++));
}

std::unique_ptr<Sampler> make_sampler(SamplerKind kind, uint64_t seed) {
  if (kind == SamplerKind::kBlueNoise) return std::make_unique<BlueNoiseSampler>(seed);
  return std::make_unique<PcgSampler>(seed);
}

}  // namespace tuneray
