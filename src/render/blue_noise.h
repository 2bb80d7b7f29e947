// Tables of the blue-noise sampler (docs/quality.md, "Blue-noise sampler"): a base sequence of
// 256 samples in 16 dimensions, and per-pixel keys over a 128x128 tile that permute (rank) and
// XOR-scramble it so that neighbouring pixels' errors are decorrelated (Heitz et al. 2019).
//
// Dimensions come in quadruples (4 x 4 = 16); the scrambling keys of a quadruple are one
// aligned 16-byte load, and so are a pixel's four ranking keys (one per quadruple). Each
// quadruple's dimension pairs (0,1) and (2,3) are (0,2)-sequences, and a ranking key XORs the
// sample index, which maps every aligned block of 2^k indices onto another such block, so a
// pixel's first 2^k samples stay stratified in every elementary interval of each pair.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace tuneray {

struct alignas(16) Keys4 {
  uint32_t k[4];
};

namespace blue_noise {
constexpr int kTileSize = 128;
constexpr int kTilePixels = kTileSize * kTileSize;
constexpr int kQuadruples = 4;
constexpr int kDims = 4 * kQuadruples;
constexpr uint32_t kSamples = 256;
}  // namespace blue_noise

// One pixel's keys: scramble[q] XORs the four values of quadruple q; rank.k[q] XORs the
// sample index of quadruple q (< kSamples).
struct alignas(16) PixelKeys {
  Keys4 scramble[blue_noise::kQuadruples];
  Keys4 rank;
};

class BlueNoiseTables {
 public:
  // The tables of the committed generator output (data/blue_noise_keys.u16), built once.
  static const BlueNoiseTables& optimized();

  // Tables where pixel p of quadruple q gets the random keys first drawn for pixel
  // origin[q * kTilePixels + p] (the generator optimises this permutation). The identity
  // gives white-noise keys. Throws std::invalid_argument on a wrong size or out-of-range entry.
  explicit BlueNoiseTables(std::span<const uint16_t> origin);

  const PixelKeys& keys(uint32_t tile_x, uint32_t tile_y) const {
    return keys_[tile_y * blue_noise::kTileSize + tile_x];
  }
  // The 16 dimensions of base sample `index` (< kSamples), as 32-bit fixed point.
  const uint32_t* base(uint32_t index) const { return base_[index].v; }

  // Dimension `dim` of sample `index` of the pixel with `keys`, fixed point (no fallback:
  // index < kSamples, dim < kDims).
  static uint32_t value_bits(const BlueNoiseTables& t, const PixelKeys& keys, uint32_t index,
                             int dim) {
    int q = dim / 4;
    return t.base(index ^ keys.rank.k[q])[dim] ^ keys.scramble[q].k[dim % 4];
  }

  // The unoptimised random keys of origin pixel `origin` for quadruple `q`: four scrambling
  // keys and a ranking key.
  static void random_keys(uint32_t origin, int q, Keys4& scramble, uint32_t& rank);

 private:
  struct alignas(64) Row {
    uint32_t v[blue_noise::kDims];
  };
  std::vector<Row> base_;
  std::vector<PixelKeys> keys_;
};

inline float bits_to_unit_float(uint32_t bits) {
  return static_cast<float>(bits >> 8) * 0x1p-24f;
}

namespace blue_noise {
// The generator's output (data/blue_noise_keys.u16, embedded by the build): the origin
// permutation, kQuadruples * kTilePixels entries.
extern const uint16_t kOptimizedOrigin[kQuadruples * kTilePixels];
}  // namespace blue_noise

}  // namespace tuneray
