// The equal-time quality switches: unbiased ones give the baseline's image (exactly, where the
// arithmetic is the same), biased ones do what they claim and are off by default.
#include <gtest/gtest.h>

#include <cmath>

#include "accel/embree_native.h"
#include "render/adaptive_sampling.h"
#include "render/environment_light.h"
#include "render/film.h"
#include "render/frame_budget.h"
#include "render/tile_renderer.h"
#include "render_helpers.h"
#include "scene/load.h"

namespace tuneray {
namespace {

Image render(const Scene& scene, const RenderSettings& settings, uint32_t spp) {
  return testing::render_image(scene, settings, spp);
}

RenderSettings small_settings() {
  RenderSettings s;
  s.width = 40;
  s.height = 30;
  s.seed = 5;
  return s;
}

size_t equal_pixels(const Image& a, const Image& b) {
  size_t n = 0;
  for (int y = 0; y < a.height(); ++y)
    for (int x = 0; x < a.width(); ++x) n += a.at(x, y) == b.at(x, y);
  return n;
}

TEST(QualitySwitches, DefaultsAreUnbiased) {
  EXPECT_FALSE(RenderSettings{}.quality.biased());
  QualityOptions o;
  o.clamp = 3;
  EXPECT_TRUE(o.biased());
}

// The wavefront scheduler runs the same integrator steps on the same random numbers and sums
// each pixel's samples in the same order, so its image is the tile image bit for bit, for any
// batch size (7 splits pixels' paths across waves unevenly).
TEST(QualitySwitches, WavefrontGivesTheTileImage) {
  Scene scene = load_scene("cornell");
  RenderSettings s = small_settings();
  Image tiles = render(scene, s, 3);
  s.quality.wavefront = true;
  for (int batch : {7, 256, 100000}) {
    s.quality.batch_size = batch;
    Image wave = render(scene, s, 3);
    EXPECT_EQ(equal_pixels(tiles, wave), static_cast<size_t>(s.width * s.height))
        << "batch " << batch;
  }
}

// Tile size only changes who renders a pixel, never its value.
TEST(QualitySwitches, TileSizeDoesNotChangeTheImage) {
  Scene scene = load_scene("cornell");
  RenderSettings s = small_settings();
  Image a = render(scene, s, 2);
  s.tile_size = 7;
  Image b = render(scene, s, 2);
  EXPECT_EQ(equal_pixels(a, b), static_cast<size_t>(s.width * s.height));
}

Environment gradient_environment(int w, int h) {
  Environment env;
  env.map = Image(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) env.map.at(x, y) = Color(x + 1.0f, y * 0.5f + 1, (x * y) % 7 + 1);
  env.scale = 0.75f;
  return env;
}

TEST(QualitySwitches, RgbaSkyTexelsGiveTheRgbValues) {
  Environment env = gradient_environment(32, 16);
  EnvironmentLight rgb(env, {false, false}), rgba(env, {true, false});
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 32; ++x) {
      Vec3f d = EnvironmentLight::uv_to_direction({(x + 0.5f) / 32, (y + 0.5f) / 16});
      EXPECT_EQ(rgba.eval(d), rgb.eval(d)) << x << "," << y;
      EXPECT_EQ(rgb.eval(d), env.map.at(x, y) * env.scale);
    }
}

TEST(QualitySwitches, LowresSkyIsTheEightByEightBlockMean) {
  Environment env = gradient_environment(32, 16);
  EnvironmentLight light(env, {true, true});
  for (int by = 0; by < 2; ++by)
    for (int bx = 0; bx < 4; ++bx) {
      Color mean(0.0f);
      for (int y = by * 8; y < by * 8 + 8; ++y)
        for (int x = bx * 8; x < bx * 8 + 8; ++x) mean += env.map.at(x, y) / 64.0f;
      // Any direction inside the block (here one near a corner) reads the block mean.
      Vec3f d = EnvironmentLight::uv_to_direction({(bx * 8 + 1.3f) / 32, (by * 8 + 6.6f) / 16});
      Color got = light.eval_lowres(d);
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], mean[c] * env.scale, 1e-5f);
    }
}

TEST(QualitySwitches, ClampLimitsTheLengthOfTheIndirectPart) {
  Scene scene = load_scene("cornell");
  EmbreeNativeAccel accel;
  RenderSettings s;
  s.quality.clamp = 2.0f;
  PathIntegrator integrator(scene, accel, s);
  PathState st;
  st.L = Color(30.0f, 40.0f, 0.0f);  // length 50
  st.L_camera = Color(5.0f);
  PathCounters counters;
  Color out = integrator.finish(st, counters);
  EXPECT_NEAR(out.x, 5.0f + 2.0f * 0.6f, 1e-5f);
  EXPECT_NEAR(out.y, 5.0f + 2.0f * 0.8f, 1e-5f);
  EXPECT_NEAR(out.z, 5.0f, 1e-5f);
  st.L = Color(0.3f, 0.4f, 0.0f);  // below m: untouched
  EXPECT_EQ(integrator.finish(st, counters), st.L_camera + st.L);
}

// Regularization widens lobes only: an all-Lambert scene (the diffuse furnace) is unchanged bit
// for bit.
TEST(QualitySwitches, RegularizationLeavesDiffuseScenesAlone) {
  Scene scene = load_scene("furnace");
  for (const Material& m : scene.materials) ASSERT_EQ(m.type, MaterialType::kLambert);
  RenderSettings s = small_settings();
  s.max_bounces = 4;
  Image a = render(scene, s, 2);
  s.quality.regularize = true;
  Image b = render(scene, s, 2);
  EXPECT_EQ(equal_pixels(a, b), static_cast<size_t>(s.width * s.height));
}

// 8x8 film: four pixels alternate between 0 and 10 (variance 25+), the rest are constant.
TEST(AdaptiveSampling, ExtraSamplesGoToTheHighVariancePixels) {
  Film film(8, 8);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) {
      bool noisy = x >= 2 && x < 4 && y >= 5 && y < 7;
      for (int s = 0; s < 8; ++s) {
        float v = noisy ? (s % 2 ? 10.0f : 0.0f) : 1.0f + 0.01f * (s % 2);
        film.add(x, y, Color(v), 1, static_cast<double>(v) * v);
      }
    }
  std::vector<uint32_t> extra = allocate_adaptive_samples(film, 1000);
  uint64_t total = 0, noisy_total = 0;
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) {
      uint32_t k = extra[static_cast<size_t>(y) * 8 + x];
      total += k;
      if (x >= 2 && x < 4 && y >= 5 && y < 7) noisy_total += k;
    }
  EXPECT_LE(total, 1000u);
  EXPECT_GE(total, 900u);  // rounding down loses at most a pixel's fraction each
  EXPECT_GT(noisy_total, total * 9 / 10);
}

TEST(AdaptiveSampling, VarianceOfTheMeanMatchesTheSampleFormula) {
  Film film(1, 1);
  const float v[] = {1, 2, 4, 7};
  for (float x : v) film.add(0, 0, Color(x), 1, static_cast<double>(x) * x);
  // mean 3.5, sample variance ((2.5^2 + 1.5^2 + 0.5^2 + 3.5^2) / 3) = 7, / n = 1.75
  EXPECT_NEAR(film.variance_of_mean(0, 0), 1.75, 1e-5);
}

// A budget far below one pass still adds exactly one sample per pixel per frame.
TEST(FrameBudget, EveryFrameAddsAtLeastOneSamplePerPixel) {
  Scene scene = load_scene("cornell");
  EmbreeNativeAccel accel;
  accel.build({scene.positions.data(), scene.positions.size(), scene.triangles.data(),
               scene.triangles.size()});
  RenderSettings s = small_settings();
  PcgSampler sampler(1);
  TileRenderer renderer(scene, accel, scene.cameras.at(0), s, sampler);
  Film film(s.width, s.height);
  FrameBudgetRenderer budget(renderer, 1e-6);
  for (int f = 0; f < 3; ++f) EXPECT_DOUBLE_EQ(budget.render_frame(film).spp, 1.0);
  EXPECT_EQ(film.samples(0, 0), 3u);
  EXPECT_EQ(film.samples(s.width - 1, s.height - 1), 3u);
}

// Adaptive frames keep every pixel's sample indices distinct: the image after the uniform
// warm-up equals a plain render of the same spp.
TEST(FrameBudget, AdaptiveWarmupEqualsUniformSampling) {
  Scene scene = load_scene("cornell");
  EmbreeNativeAccel accel;
  accel.build({scene.positions.data(), scene.positions.size(), scene.triangles.data(),
               scene.triangles.size()});
  RenderSettings s = small_settings();
  s.quality.adaptive = true;
  s.quality.adaptive_min_spp = 4;
  PcgSampler sampler(s.seed);
  TileRenderer renderer(scene, accel, scene.cameras.at(0), s, sampler);
  Film film(s.width, s.height);
  FrameBudgetRenderer budget(renderer, 1e-6);
  for (int f = 0; f < 3; ++f) budget.render_frame(film);
  RenderSettings plain = small_settings();
  Image expected = render(scene, plain, 3);
  EXPECT_EQ(equal_pixels(film.resolve(), expected), static_cast<size_t>(s.width * s.height));
}

}  // namespace
}  // namespace tuneray
