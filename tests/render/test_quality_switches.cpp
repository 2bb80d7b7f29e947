// The equal-time quality switches: unbiased ones give the baseline's image (exactly, where the
// arithmetic is the same), biased ones do what they claim and are off by default.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>

#include "accel/embree_native.h"
#include "common/scene_with_accel.h"
#include "render/adaptive_sampling.h"
#include "render/environment_light.h"
#include "render/film.h"
#include "render/frame_budget.h"
#include "render/tile_renderer.h"
#include "render_helpers.h"
#include "scene/builtins.h"
#include "scene/load.h"
#include "scene/mesh_data.h"

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
// batch size (7 splits pixels' paths across waves unevenly). The two group paths into the
// integrator's eight SIMD lanes differently, so this also checks that a path's result does not
// depend on the paths beside it: on Lambert with an area light (cornell), GGX and principled
// materials (mixed) and an environment map (sky).
TEST(QualitySwitches, WavefrontGivesTheTileImage) {
  for (const char* name : {"cornell", "mixed", "sky"}) {
    Scene scene = load_scene(name);
    RenderSettings s = small_settings();
    s.quality.wavefront = false;
    Image tiles = render(scene, s, 3);
    s.quality.wavefront = true;
    for (int batch : {7, 256, 100000}) {
      s.quality.batch_size = batch;
      Image wave = render(scene, s, 3);
      EXPECT_EQ(equal_pixels(tiles, wave), static_cast<size_t>(s.width * s.height))
          << name << ", batch " << batch;
    }
  }
}

// Branch-reduced material evaluation computes the same f and pdf (to float rounding; checked
// on 100k inputs in test_bsdf_branchless.cpp), and the integrator draws the same random numbers
// either way, so the image matches the per-type one to rounding on a scene with Lambert,
// anisotropic GGX and principled materials.
TEST(QualitySwitches, BranchlessMaterialsGiveThePerTypeImage) {
  Scene scene = load_scene("sky");
  RenderSettings s = small_settings();
  s.quality.branchless_materials = false;
  Image by_type = render(scene, s, 4);
  s.quality.branchless_materials = true;
  Image branchless = render(scene, s, 4);
  double largest = 0, mean = 0;
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x)
      for (int c = 0; c < 3; ++c) {
        double a = by_type.at(x, y)[c], b = branchless.at(x, y)[c];
        largest = std::max(largest, std::abs(a - b) / std::max(1e-3, std::abs(a)));
        mean += a / (3.0 * s.width * s.height);
      }
  EXPECT_GT(mean, 0.05);     // something was rendered
  EXPECT_LT(largest, 1e-3);  // relative, per channel and pixel
}

// Tile size only changes who renders a pixel, never its value.
TEST(QualitySwitches, TileSizeDoesNotChangeTheImage) {
  Scene scene = load_scene("cornell");
  RenderSettings s = small_settings();
  s.quality.wavefront = false;  // the tile scheduler is the one that reads the tile size
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
  PathIntegrator integrator(scene, accel, s);
  PathWave wave;
  wave.reserve(1);
  wave.size = 1;
  wave.start(0, Ray{}, 0);
  auto set = [&wave](int plane, Color c) {
    wave.plane(plane)[0] = c.x;
    wave.plane(plane + 1)[0] = c.y;
    wave.plane(plane + 2)[0] = c.z;
  };
  set(PathWave::kLX, Color(30.0f, 40.0f, 0.0f));  // length 50
  set(PathWave::kCameraX, Color(5.0f));
  PathCounters counters;
  Color out = integrator.finish(wave, 0, counters, 2.0f);
  EXPECT_NEAR(out.x, 5.0f + 2.0f * 0.6f, 1e-5f);
  EXPECT_NEAR(out.y, 5.0f + 2.0f * 0.8f, 1e-5f);
  EXPECT_NEAR(out.z, 5.0f, 1e-5f);
  EXPECT_EQ(integrator.finish(wave, 0, counters, 0.0f), Color(35.0f, 45.0f, 5.0f));  // 0 = off
  set(PathWave::kLX, Color(0.3f, 0.4f, 0.0f));  // below m: untouched
  EXPECT_EQ(integrator.finish(wave, 0, counters, 2.0f), Color(5.3f, 5.4f, 5.0f));
}

// The relative clamp's m_i is k times the larger of the mean pixel-value length over i's 3x3
// neighbourhood and over the image (pixels without samples do not count); an absolute m takes
// precedence everywhere, and an empty film means no clamp (nothing to be relative to yet).
TEST(QualitySwitches, RelativeClampFollowsTheNeighbourhood) {
  Scene scene = load_scene("cornell");
  EmbreeNativeAccel accel;
  RenderSettings s = small_settings();
  s.width = 4;
  s.height = 1;
  s.quality.clamp_relative = 2.0f;
  EXPECT_TRUE(s.quality.biased());
  EXPECT_FALSE(s.quality.without_bias().biased());
  PcgSampler sampler(1);
  TileRenderer renderer(scene, accel, scene.cameras.at(0), s, sampler);
  Film film(4, 1);
  EXPECT_FALSE(renderer.clamp_for(film).active());
  film.add(0, 0, Color(6.0f, 8.0f, 0.0f) * 2.0f, 2);  // length 10
  film.add(1, 0, Color(0.0f, 1.0f, 0.0f), 1);         // length 1
  film.add(2, 0, Color(1.0f, 0.0f, 0.0f) * 3.0f, 3);  // length 1; pixel 3 has no samples
  // Image mean 4. Neighbourhoods: {10, 1} -> 5.5, {10, 1, 1} -> 4, {1, 1} -> 1, {1} -> 1.
  ClampThresholds t = renderer.clamp_for(film);
  EXPECT_NEAR(t.at(0), 2.0f * 5.5f, 1e-5f);
  EXPECT_NEAR(t.at(1), 2.0f * 4.0f, 1e-5f);
  EXPECT_NEAR(t.at(2), 2.0f * 4.0f, 1e-5f);  // the image mean is the floor
  EXPECT_NEAR(t.at(3), 2.0f * 4.0f, 1e-5f);
  s.quality.clamp = 0.5f;
  TileRenderer absolute(scene, accel, scene.cameras.at(0), s, sampler);
  for (size_t i = 0; i < 4; ++i) EXPECT_EQ(absolute.clamp_for(film).at(i), 0.5f);
}

// A relative clamp leaves an image without outliers alone. In the diffuse furnace (albedo 1,
// sky 1) a bounce adds at most 1/2 per channel through light sampling (power heuristic, uniform
// sky pdf 1/4pi against cos/pi) and at most 1 through a BSDF-sampled sky hit, so a 3-bounce
// sample's indirect length is below 4.5 sqrt(3) = 7.8; pixel values have length >= 1 on
// average (the sky seen directly is sqrt(3)), so k = 8 gives every m_i >= 8 (the image mean
// is the floor): nothing is clamped.
TEST(QualitySwitches, RelativeClampLeavesAFireflyFreeImageAlone) {
  Scene scene = load_scene("furnace");
  RenderSettings s = small_settings();
  EmbreeNativeAccel accel;
  accel.build({scene.positions.data(), scene.positions.size(), scene.triangles.data(),
               scene.triangles.size()});
  auto two_passes = [&](const RenderSettings& settings) {
    PcgSampler sampler(settings.seed);
    TileRenderer renderer(scene, accel, scene.cameras.at(0), settings, sampler);
    Film film(settings.width, settings.height);
    renderer.render_pass(film, 0, 1);
    renderer.render_pass(film, 1, 2);
    return film.resolve();
  };
  Image plain = two_passes(s);
  s.quality.clamp_relative = 8.0f;
  EXPECT_EQ(equal_pixels(plain, two_passes(s)), static_cast<size_t>(s.width * s.height));
  s.quality.clamp_relative = 0.25f;  // m below every sample's length: the image darkens
  Image clamped = two_passes(s);
  double plain_sum = 0, clamped_sum = 0;
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x) {
      plain_sum += luminance(plain.at(x, y));
      clamped_sum += luminance(clamped.at(x, y));
    }
  EXPECT_LT(clamped_sum, 0.9 * plain_sum);
}

// A lamp seen in a mirror is part of the visible scene, not a firefly: the clamp leaves
// emission reached through specular vertices alone, however low m is. The camera looks at a
// mirror that faces it; behind the camera hangs a bright emitter that the mirror shows.
TEST(QualitySwitches, ClampSparesEmissionSeenThroughMirrors) {
  Scene scene;
  scene.name = "mirror-lamp";
  uint32_t mirror = add_material(
      scene, {.name = "mirror", .type = MaterialType::kMirror, .specular_color = Color(1.0f)});
  uint32_t lamp =
      add_material(scene, {.name = "lamp", .base_color = Color(0.0f), .emission = Color(50.0f)});
  add_mesh(scene, "mirror", make_quad({-4, -4, 0}, {8, 0, 0}, {0, 8, 0}, {0, 0, 1}), mirror);
  add_mesh(scene, "lamp", make_quad({-20, -20, 6}, {40, 0, 0}, {0, 40, 0}, {0, 0, -1}), lamp);
  scene.cameras.push_back(look_at("front", Vec3f(0, 0, 3), Vec3f(0, 0, 0), 30.0f));
  RenderSettings s = small_settings();
  s.width = 8;
  s.height = 6;
  Image plain = render(scene, s, 2);
  s.quality.clamp = 0.5f;
  Image clamped = render(scene, s, 2);
  ASSERT_NEAR(plain.at(4, 3).x, 50.0f, 1e-3f);  // the lamp, through the mirror
  EXPECT_EQ(equal_pixels(plain, clamped), static_cast<size_t>(s.width * s.height));
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
// An 8x8 film of 8 samples per pixel: a 2x2 block alternates between 0 and 10, the rest is
// nearly constant.
bool in_noisy_block(int x, int y) {
  return x >= 2 && x < 4 && y >= 5 && y < 7;
}

Film noisy_block_film() {
  Film film(8, 8);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x)
      for (int s = 0; s < 8; ++s) {
        float v = in_noisy_block(x, y) ? (s % 2 ? 10.0f : 0.0f) : 1.0f + 0.01f * (s % 2);
        film.add(x, y, Color(v), 1, SquareSum::of(Color(v)));
      }
  return film;
}

// Share of `extra` that lands where `where(x, y)` holds; checks the total against the budget.
double share(const std::vector<uint32_t>& extra, uint64_t budget,
             const std::function<bool(int, int)>& where) {
  uint64_t total = 0, inside = 0;
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) {
      uint32_t k = extra[static_cast<size_t>(y) * 8 + x];
      total += k;
      if (where(x, y)) inside += k;
    }
  EXPECT_LE(total, budget);
  EXPECT_GE(total + 64, budget);  // rounding down loses less than one sample per pixel
  return static_cast<double>(inside) / static_cast<double>(total);
}

TEST(AdaptiveSampling, ExtraSamplesGoToTheHighVariancePixels) {
  AdaptiveOptions plain;
  plain.filter = false;
  plain.max_ratio = 0;
  EXPECT_GT(share(allocate_adaptive_samples(noisy_block_film(), 1000, plain), 1000, in_noisy_block),
            0.9);
}

// Filtered, the block's 1-pixel ring shares its estimate (8 samples could have missed the
// feature that makes it noisy), and the rest of the image still gets almost nothing.
TEST(AdaptiveSampling, FilteredEstimateKeepsExtraSamplesNearTheNoise) {
  AdaptiveOptions filtered;
  filtered.max_ratio = 0;
  auto near_block = [](int x, int y) { return x >= 1 && x < 5 && y >= 4 && y < 8; };
  std::vector<uint32_t> extra = allocate_adaptive_samples(noisy_block_film(), 1000, filtered);
  EXPECT_GT(share(extra, 1000, near_block), 0.9);
  EXPECT_LT(share(extra, 1000, in_noisy_block), 0.9);  // the ring got some
}

// The cap: no pixel ends above max_ratio x the mean count; what the noisy block cannot take
// goes to the others, and every pixel below the cap keeps its priority order.
TEST(AdaptiveSampling, NoPixelExceedsTheCap) {
  Film film = noisy_block_film();
  AdaptiveOptions capped;
  capped.filter = false;
  capped.max_ratio = 2.0;
  const uint64_t budget = 1000;
  std::vector<uint32_t> extra = allocate_adaptive_samples(film, budget, capped);
  const double cap = 2.0 * (64.0 * 8 + budget) / 64;  // 47.25 samples
  double block_share = share(extra, budget, in_noisy_block);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) {
      double total = 8.0 + extra[static_cast<size_t>(y) * 8 + x];
      EXPECT_LE(total, cap) << x << "," << y;
      if (in_noisy_block(x, y)) {
        EXPECT_EQ(total, std::floor(cap)) << x << "," << y;
      }
    }
  EXPECT_LT(block_share, 0.2);  // 4 x 39 of ~1000
}

// On a larger film with every pixel's noise different, the allocation is the Lagrange optimum
// rounded: one constant c with |have_i + k_i - c s_i| < 1 wherever a pixel gets samples, and
// c s_i < have_i + 1 wherever it gets none; the total is at most the budget and short of it by
// less than two samples per 16-row block. s_i is recomputed here from the film (unfiltered,
// with the floor).
TEST(AdaptiveSampling, AllocationIsTheOptimumForOneConstant) {
  const int w = 97, h = 61;
  Film film(w, h);
  uint32_t state = 12345;
  auto next = [&state] {
    state = state * 1664525u + 1013904223u;
    return static_cast<float>(state >> 8) * 0x1p-24f;
  };
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      int n = 2 + (x * 7 + y * 3) % 9;
      float spread = 0.01f + 5.0f * next() * next();
      for (int k = 0; k < n; ++k) {
        Color v(1.0f + spread * next());
        film.add(x, y, v, 1, SquareSum::of(v));
      }
    }
  AdaptiveOptions plain;
  plain.filter = false;
  plain.max_ratio = 0;
  const size_t n_pixels = static_cast<size_t>(w) * h;
  std::vector<double> sigma(n_pixels);
  double mean_sigma = 0;
  for (size_t i = 0; i < n_pixels; ++i) {
    int x = static_cast<int>(i % w), y = static_cast<int>(i / w);
    sigma[i] = std::sqrt(film.variance_of_mean(x, y) * film.samples(x, y));
    mean_sigma += sigma[i] / static_cast<double>(n_pixels);
  }
  for (double& s : sigma) s += plain.sigma_floor * mean_sigma;
  for (uint64_t budget : {uint64_t{50}, uint64_t{5000}, uint64_t{60000}}) {
    std::vector<uint32_t> extra = allocate_adaptive_samples(film, budget, plain);
    uint64_t total = 0;
    double c_low = 0, c_high = 1e300;  // the constants every pixel allows
    for (size_t i = 0; i < n_pixels; ++i) {
      total += extra[i];
      double have = film.samples(static_cast<int>(i % w), static_cast<int>(i / w));
      if (extra[i] > 0) {
        c_low = std::max(c_low, (have + extra[i] - 1) / sigma[i]);
        c_high = std::min(c_high, (have + extra[i] + 1) / sigma[i]);
      } else {
        c_high = std::min(c_high, (have + 1) / sigma[i]);
      }
    }
    EXPECT_LE(total, budget);
    EXPECT_GE(total + 2 * (h + 15) / 16, budget);
    EXPECT_LE(c_low, c_high * (1 + 1e-9)) << "no single constant explains budget " << budget;
  }
}

TEST(AdaptiveSampling, VarianceOfTheMeanMatchesTheSampleFormula) {
  Film film(1, 1);
  const float v[] = {1, 2, 4, 7};
  for (float x : v) film.add(0, 0, Color(x, 2 * x, 0), 1, SquareSum::of(Color(x, 2 * x, 0)));
  // red: mean 3.5, sample variance ((2.5^2 + 1.5^2 + 0.5^2 + 3.5^2) / 3) = 7; green 4 x 7 = 28;
  // blue 0: the mean over channels is 35 / 3, over n = 4 samples 35 / 12
  EXPECT_NEAR(film.variance_of_mean(0, 0), 35.0 / 12.0, 1e-5);
}

// The built-in Cornell box rendered in uniform frames (no adaptive sampling) into `film`.
struct UniformCornellFrames {
  testing::SceneWithNativeAccel cornell{load_scene("cornell")};
  RenderSettings s = [] {
    RenderSettings settings = small_settings();
    settings.quality.adaptive = false;
    return settings;
  }();
  PcgSampler sampler{1};
  TileRenderer renderer{cornell.scene, cornell.accel, cornell.scene.cameras.at(0), s, sampler};
  Film film{s.width, s.height};
};

// A budget far below one pass adds a partial pass per frame: a quarter of the pixels first
// (no cost known yet), then a tenth, in row order, until every pixel has exactly one sample.
TEST(FrameBudget, TinyBudgetsAddPartialPassesThatCompleteARound) {
  UniformCornellFrames frames;
  const RenderSettings& s = frames.s;
  Film& film = frames.film;
  FrameBudgetRenderer budget(frames.renderer, 1e-6);
  const uint64_t pixels = static_cast<uint64_t>(s.width) * s.height;  // 1200
  EXPECT_EQ(budget.render_frame(film).stats.samples, 300u);
  EXPECT_EQ(film.samples(0, 0), 1u);
  EXPECT_EQ(film.samples(299 % s.width, 299 / s.width), 1u);  // the quarter's last pixel
  EXPECT_EQ(film.samples(300 % s.width, 300 / s.width), 0u);
  uint64_t total = 300;
  for (int f = 0; f < 8; ++f) {
    uint64_t added = budget.render_frame(film).stats.samples;
    EXPECT_EQ(added, f < 7 ? 120u : 60u) << "frame " << f + 1;  // the last one ends the round
    total += added;
  }
  EXPECT_EQ(total, pixels);
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x) ASSERT_EQ(film.samples(x, y), 1u) << x << "," << y;
}

// Time set aside for showing the frame (the denoiser's filtering) comes out of the budget: with
// all of a 2 s budget set aside, a frame adds only the smallest pass (a tenth of the pixels)
// once the cost is known, instead of two seconds of samples.
TEST(FrameBudget, TimeSetAsideForShowingTheFrameComesOutOfTheBudget) {
  UniformCornellFrames frames;
  Film& film = frames.film;
  FrameBudgetRenderer budget(frames.renderer, 2000);
  EXPECT_EQ(budget.render_frame(film, 2000).stats.samples, 300u);  // the first, unknown cost
  for (int f = 0; f < 3; ++f) EXPECT_EQ(budget.render_frame(film, 2500).stats.samples, 120u);
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
  s.quality.path_reuse = 0;  // its pools follow the passes, so partial ones change the image
  PcgSampler sampler(s.seed);
  TileRenderer renderer(scene, accel, scene.cameras.at(0), s, sampler);
  Film film(s.width, s.height);
  FrameBudgetRenderer budget(renderer, 1e-6);
  // Partial passes (the budget fits less than one) until three rounds are complete.
  const uint64_t pixels = static_cast<uint64_t>(s.width) * s.height;
  uint64_t total = 0;
  for (int f = 0; f < 100 && total < 3 * pixels; ++f)
    total += budget.render_frame(film).stats.samples;
  ASSERT_EQ(total, 3 * pixels);
  RenderSettings plain = small_settings();
  Image expected = render(scene, plain, 3);
  EXPECT_EQ(equal_pixels(film.resolve(), expected), static_cast<size_t>(s.width * s.height));
}

}  // namespace
}  // namespace tuneray
