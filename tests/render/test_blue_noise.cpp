// The blue-noise sampler: its tables keep each pixel's samples stratified, its optimised keys
// push the per-pixel error to high frequencies (the generator's claim), and renders with it
// converge to the PCG image.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "accel/embree_native.h"
#include "image/metrics.h"
#include "math/rng.h"
#include "render/blue_noise.h"
#include "render/blue_noise_error.h"
#include "render/blue_noise_sampler.h"
#include "render/film.h"
#include "render/tile_renderer.h"
#include "render_helpers.h"
#include "scene/load.h"

namespace tuneray {
namespace {

using namespace blue_noise;

std::vector<uint16_t> identity_origin() {
  std::vector<uint16_t> o(static_cast<size_t>(kQuadruples) * kTilePixels);
  for (size_t i = 0; i < o.size(); ++i) o[i] = static_cast<uint16_t>(i % kTilePixels);
  return o;
}

// For 2^k samples, every elementary interval [i/2^a, (i+1)/2^a) x [j/2^b, (j+1)/2^b) with
// a + b = k of each pair of each quadruple holds exactly one of a pixel's first 2^k samples.
TEST(BlueNoise, EachPixelsSamplesAreA02Sequence) {
  const BlueNoiseTables& t = BlueNoiseTables::optimized();
  Pcg32 rng(3, 4);
  for (int trial = 0; trial < 24; ++trial) {
    const PixelKeys& keys = t.keys(rng.next_u32() % kTileSize, rng.next_u32() % kTileSize);
    for (int dim = 0; dim < kDims; dim += 2)
      for (int k = 0; k <= 8; ++k) {
        uint32_t n = 1u << k;
        for (int a = 0; a <= k; ++a) {
          std::vector<int> cells(n, 0);
          for (uint32_t i = 0; i < n; ++i) {
            uint32_t x = BlueNoiseTables::value_bits(t, keys, i, dim);
            uint32_t y = BlueNoiseTables::value_bits(t, keys, i, dim + 1);
            uint32_t cx = a == 0 ? 0 : x >> (32 - a), cy = k - a == 0 ? 0 : y >> (32 - (k - a));
            ++cells[(cy << a) | cx];
          }
          for (uint32_t c = 0; c < n; ++c)
            ASSERT_EQ(cells[c], 1)
                << "dims " << dim << "," << dim + 1 << " n=" << n << " a=" << a << " cell " << c;
        }
      }
  }
}

// The spectrum measure itself: white noise spreads its power evenly, so the share inside the
// disc of radius n/8 is that disc's area share, pi / 64 (~0.049).
TEST(BlueNoise, LowFrequencyShareOfWhiteNoiseIsTheDiscArea) {
  Pcg32 rng(9, 2);
  double sum = 0;
  for (int r = 0; r < 4; ++r) {
    std::vector<float> img(kTilePixels);
    for (float& v : img) v = rng.next_float();
    sum += low_frequency_share(img);
  }
  EXPECT_NEAR(sum / 4, std::numbers::pi / 64, 0.006);
}

// The generator's claim, on half-plane integrands it was NOT optimised on (another seed): the
// error images of the optimised keys have far less low-frequency power than random keys'.
TEST(BlueNoise, OptimisedKeysPushErrorToHighFrequencies) {
  const BlueNoiseTables& optimised = BlueNoiseTables::optimized();
  BlueNoiseTables random(identity_origin());
  std::vector<HalfPlane> fs = random_half_planes(12345, 4);
  for (uint32_t spp : {1u, 4u}) {
    double share_opt = 0, share_rand = 0;
    for (int q = 0; q < kQuadruples; ++q)
      for (const HalfPlane& f : fs) {
        share_opt += low_frequency_share(error_image(optimised, q, spp, f));
        share_rand += low_frequency_share(error_image(random, q, spp, f));
      }
    double ratio = share_opt / share_rand;
    std::printf("spp %u: low-frequency share optimised %.4f, random %.4f, ratio %.3f\n", spp,
                share_opt / (kQuadruples * fs.size()), share_rand / (kQuadruples * fs.size()),
                ratio);
    // Measured with the committed table: 0.29 at 1 spp, 0.57 at 4 spp (docs/quality.md).
    EXPECT_LT(ratio, spp == 1 ? 0.4 : 0.75) << "spp " << spp;
  }
}

TEST(BlueNoise, Next4IsFourNext1AndPcgPastTheTables) {
  BlueNoiseSampler a(7), b(7);
  PcgSampler pcg(7);
  for (uint32_t index : {0u, 5u, 255u, 256u, 1000u}) {
    a.start_pixel_sample(300, 17, index);
    b.start_pixel_sample(300, 17, index);
    pcg.start_pixel_sample(300, 17, index);
    for (int quad = 0; quad < kQuadruples; ++quad) {
      std::array<float, 4> u = a.next4();
      for (int i = 0; i < 4; ++i) {
        float v = b.next1();
        EXPECT_EQ(u[i], v);
        EXPECT_GE(v, 0.0f);
        EXPECT_LT(v, 1.0f);
        if (index >= kSamples) {
          EXPECT_EQ(v, pcg.next1()) << "past the table: PCG numbers";
        }
      }
    }
  }
  // Dimensions 16+ of an in-table sample: the PCG sampler's numbers for that pixel sample.
  a.start_pixel_sample(3, 4, 9);
  pcg.start_pixel_sample(3, 4, 9);
  for (int i = 0; i < kQuadruples; ++i) a.next4();
  for (int i = 0; i < 8; ++i) EXPECT_EQ(a.next1(), pcg.next1());
}

// The embedded data (data/blue_noise_keys.u16) is what the generator promises: per quadruple a
// permutation of the tile's key sets, so every key set is used exactly once and the samples of
// the tile as a whole keep the random keys' distribution.
TEST(BlueNoise, EmbeddedOriginsUseEveryKeySetOncePerQuadruple) {
  for (int q = 0; q < kQuadruples; ++q) {
    std::vector<int> uses(kTilePixels, 0);
    for (int p = 0; p < kTilePixels; ++p) {
      uint16_t origin = kOptimizedOrigin[q * kTilePixels + p];
      ASSERT_LT(origin, kTilePixels) << "quadruple " << q << ", pixel " << p;
      ++uses[origin];
    }
    for (int k = 0; k < kTilePixels; ++k)
      ASSERT_EQ(uses[k], 1) << "quadruple " << q << ", key " << k;
  }
}

TEST(BlueNoise, TablesRejectBadOrigins) {
  std::vector<uint16_t> short_table(10);
  EXPECT_THROW(BlueNoiseTables{short_table}, std::invalid_argument);
  std::vector<uint16_t> bad = identity_origin();
  bad[5] = kTilePixels;
  EXPECT_THROW(BlueNoiseTables{bad}, std::invalid_argument);
}

Image render(const Scene& scene, const RenderSettings& s, const Sampler& sampler, uint32_t spp) {
  return testing::render_image(scene, s, sampler, spp);
}

double rmse(const Image& a, const Image& b) {
  return compare_images(a, b).rmse;
}

// Unbiased: the blue-noise image is as close to a PCG image as another PCG image is (two
// independent unbiased estimates), and the image means agree.
TEST(BlueNoise, RenderConvergesToThePcgImage) {
  Scene scene = load_scene("cornell");
  RenderSettings s;
  s.width = 24;
  s.height = 24;
  const uint32_t spp = 128;
  Image pcg1 = render(scene, s, PcgSampler(1), spp);
  Image pcg2 = render(scene, s, PcgSampler(2), spp);
  Image bn = render(scene, s, BlueNoiseSampler(3), spp);
  double noise = rmse(pcg1, pcg2);
  double diff = rmse(bn, pcg1);
  std::printf("rmse pcg-pcg %.5f, bluenoise-pcg %.5f\n", noise, diff);
  EXPECT_LT(diff, 1.05 * noise);
  auto mean = [](const Image& img) {
    double m = 0;
    for (int y = 0; y < img.height(); ++y)
      for (int x = 0; x < img.width(); ++x) m += luminance(img.at(x, y));
    return m / (img.width() * img.height());
  };
  EXPECT_NEAR(mean(bn) / mean(pcg1), 1.0, 0.02);
}

// Determinism: the wavefront scheduler (other batching, other sampler clones) gives the tile
// image bit for bit, so the image depends on the seed only.
TEST(BlueNoise, SameImageForAnyScheduler) {
  Scene scene = load_scene("cornell");
  RenderSettings s;
  s.width = 20;
  s.height = 12;
  s.quality.wavefront = false;
  BlueNoiseSampler sampler(4);
  Image tiles = render(scene, s, sampler, 3);
  s.quality.wavefront = true;
  s.quality.batch_size = 37;
  Image waves = render(scene, s, sampler, 3);
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x) ASSERT_EQ(tiles.at(x, y), waves.at(x, y));
}

}  // namespace
}  // namespace tuneray
