// The base sequence: for each dimension pair, the (0,2)-sequence whose first coordinate is the
// van der Corput sequence and second the second Sobol dimension (generator matrix: Pascal's
// triangle mod 2), randomised per pair so that pairs do not repeat each other:
// - the sample index is multiplied by a random unit upper-triangular matrix over its bits
//   (Faure-Tezuka scrambling): every prefix of 2^k indices maps onto itself, so each prefix of
//   the sequence is the same point set, visited in a different order per pair;
// - each coordinate is multiplied by a random unit lower-triangular matrix over its digits
//   (Matousek's linear scrambling), which keeps every elementary interval's count.
// Both are linear over GF(2), so XOR keys on index and value keep the net properties too.
#include "render/blue_noise.h"

#include <bit>
#include <stdexcept>
#include <string>

#include "math/rng.h"

namespace tuneray {

namespace {

using namespace blue_noise;

constexpr int kIndexBits = 8;  // kSamples = 2^8
static_assert(kSamples == 1u << kIndexBits);

uint32_t parity(uint32_t x) {
  return static_cast<uint32_t>(std::popcount(x) & 1);
}

// Column c of the generator matrices, as the 32-bit value index bit c contributes.
uint32_t van_der_corput_column(int c) {
  return 1u << (31 - c);
}
uint32_t sobol2_column(int c) {
  // Row r (digit 2^-(r+1)) of column c is binomial(c, r) mod 2 = ((r & c) == r).
  uint32_t v = 0;
  for (int r = 0; r <= c; ++r)
    if ((r & c) == r) v |= 1u << (31 - r);
  return v;
}

// Random unit upper-triangular matrix over index bits: bit j of the result is bit j of the
// index XOR a random subset of the higher bits.
struct IndexScramble {
  uint32_t higher_mask[kIndexBits];
  uint32_t apply(uint32_t i) const {
    uint32_t out = 0;
    for (int j = 0; j < kIndexBits; ++j) out |= (((i >> j) & 1u) ^ parity(i & higher_mask[j])) << j;
    return out;
  }
};

// Random unit lower-triangular matrix over digits (most significant first): each digit is
// XORed with a random subset of the more significant digits.
struct DigitScramble {
  uint32_t higher_mask[32];
  uint32_t apply(uint32_t v) const {
    uint32_t out = 0;
    for (int b = 0; b < 32; ++b) out |= (((v >> b) & 1u) ^ parity(v & higher_mask[b])) << b;
    return out;
  }
};

uint32_t mask_above(int bit, int bits) {
  return bit + 1 >= bits ? 0u : (~0u << (bit + 1)) & (bits == 32 ? ~0u : (1u << bits) - 1);
}

}  // namespace

BlueNoiseTables::BlueNoiseTables(std::span<const uint16_t> origin)
    : base_(kSamples), keys_(kTilePixels) {
  if (origin.size() != static_cast<size_t>(kQuadruples) * kTilePixels)
    throw std::invalid_argument("blue-noise origin table has " + std::to_string(origin.size()) +
                                " entries, expected " + std::to_string(kQuadruples * kTilePixels));
  // Fixed seed: the base sequence is part of the table format (the keys were optimised for it).
  Pcg32 rng(0x62'6c'75'65'6e'6f'69'73ULL, 17);
  for (int pair = 0; pair < kDims / 2; ++pair) {
    IndexScramble index_scramble;
    for (int j = 0; j < kIndexBits; ++j)
      index_scramble.higher_mask[j] = rng.next_u32() & mask_above(j, kIndexBits);
    DigitScramble digits[2];
    for (DigitScramble& d : digits)
      for (int b = 0; b < 32; ++b) d.higher_mask[b] = rng.next_u32() & mask_above(b, 32);
    for (uint32_t i = 0; i < kSamples; ++i) {
      uint32_t j = index_scramble.apply(i);
      uint32_t x = 0, y = 0;
      for (int c = 0; c < kIndexBits; ++c)
        if ((j >> c) & 1u) {
          x ^= van_der_corput_column(c);
          y ^= sobol2_column(c);
        }
      base_[i].v[2 * pair] = digits[0].apply(x);
      base_[i].v[2 * pair + 1] = digits[1].apply(y);
    }
  }
  for (int q = 0; q < kQuadruples; ++q)
    for (int p = 0; p < kTilePixels; ++p) {
      uint16_t o = origin[static_cast<size_t>(q) * kTilePixels + p];
      if (o >= kTilePixels)
        throw std::invalid_argument("blue-noise origin table: entry " + std::to_string(o) +
                                    " out of range");
      random_keys(o, q, keys_[p].scramble[q], keys_[p].rank.k[q]);
    }
}

void BlueNoiseTables::random_keys(uint32_t origin, int q, Keys4& scramble, uint32_t& rank) {
  Pcg32 rng(mix_seed((static_cast<uint64_t>(q) << 32) | origin), 0x4b657973);
  for (uint32_t& k : scramble.k) k = rng.next_u32();
  rank = rng.next_u32() & (kSamples - 1);
}

const BlueNoiseTables& BlueNoiseTables::optimized() {
  static const BlueNoiseTables tables(kOptimizedOrigin);
  return tables;
}

}  // namespace tuneray
