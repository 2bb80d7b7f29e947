// The à-trous denoiser on synthetic images (exact and statistical properties) and on the
// built-in Cornell box (closer to the converged image than the raw estimate).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

#include "accel/embree_native.h"
#include "denoise_test_images.h"
#include "image/metrics.h"
#include "render/camera.h"
#include "render/denoiser.h"
#include "render/denoiser_features.h"
#include "render/denoiser_frame.h"
#include "render/sampler.h"
#include "scene/builtins.h"
#include "scene/mesh_data.h"

namespace tuneray {
namespace {

constexpr int kW = 48, kH = 32;

// Noise-free features: one albedo and one normal everywhere unless a test changes them.
DenoiseFeatures flat_features(Color albedo = Color(0.5f)) {
  return testing::flat_features(kW, kH, albedo);
}

using testing::known_variance;
using testing::near_light;
using testing::with_noise;

TEST(Denoiser, ConstantImageWithNoiseFreeFeaturesStaysExactlyConstant) {
  const Color c(0.3f, 0.55f, 0.7f);
  Image image(kW, kH, c);
  for (float variance : {0.0f, 0.01f, -1.0f}) {  // none, known, estimated from neighbours
    Image out = denoise(known_variance(image, variance), flat_features(Color(0.7f, 0.6f, 0.2f)));
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) {
        ASSERT_EQ(out.at(x, y).x, c.x) << x << "," << y;
        ASSERT_EQ(out.at(x, y).y, c.y) << x << "," << y;
        ASSERT_EQ(out.at(x, y).z, c.z) << x << "," << y;
      }
  }
}

TEST(Denoiser, NoiseOnAFlatRegionDropsTenfold) {
  const float sigma = 0.1f;
  Image clean(kW, kH, Color(0.4f));
  Image noisy = with_noise(clean, sigma, 7);
  Image out = denoise(known_variance(noisy, sigma * sigma), flat_features());
  double before = compare_images(noisy, clean).rmse, after = compare_images(out, clean).rmse;
  EXPECT_NEAR(before, sigma, 0.01);
  EXPECT_LT(after, before / 10) << before << " -> " << after;
}

TEST(Denoiser, EstimatedVarianceAlsoFilters) {
  // One-sample pixels: the noise level comes from the neighbourhood.
  const float sigma = 0.1f;
  Image clean(kW, kH, Color(0.4f));
  Image noisy = with_noise(clean, sigma, 8);
  Image out = denoise(known_variance(noisy, -1.0f), flat_features());
  EXPECT_LT(compare_images(out, clean).rmse, compare_images(noisy, clean).rmse / 5);
}

// Left half and right half differ in one feature; the noisy image follows the clean step.
void expect_edge_survives(const DenoiseFeatures& f, const Image& clean) {
  const float sigma = 0.05f;
  Image out = denoise(known_variance(with_noise(clean, sigma, 11), sigma * sigma), f);
  for (int y = 2; y < kH - 2; ++y)
    for (int x : {kW / 2 - 2, kW / 2 - 1, kW / 2, kW / 2 + 1}) {
      // Within a noise sigma of its own side's value, whereas the step is 0.6.
      EXPECT_NEAR(luminance(out.at(x, y)), luminance(clean.at(x, y)), sigma) << x << "," << y;
    }
}

TEST(Denoiser, AlbedoEdgeSurvives) {
  DenoiseFeatures f = flat_features();
  Image clean(kW, kH);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      float albedo = x < kW / 2 ? 0.2f : 0.8f;  // lit by 1: the image is the albedo
      f.albedo[static_cast<size_t>(y) * kW + x] = Color(albedo);
      clean.at(x, y) = Color(albedo);
    }
  expect_edge_survives(f, clean);
}

TEST(Denoiser, NormalEdgeSurvives) {
  DenoiseFeatures f = flat_features(Color(1.0f));
  Image clean(kW, kH);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      bool left = x < kW / 2;  // a wall facing the light and one at 90 degrees to it
      f.normal[static_cast<size_t>(y) * kW + x] = left ? Vec3f(0, 0, 1) : Vec3f(1, 0, 0);
      clean.at(x, y) = Color(left ? 0.8f : 0.2f);
    }
  expect_edge_survives(f, clean);
}

// The pixels on either side of the step at x = kW / 2 that end further than `tolerance` from
// their side's value.
int edge_pixels_off_their_side(const Image& out, const Image& clean, float tolerance) {
  int count = 0;
  for (int y = 2; y < kH - 2; ++y)
    for (int x : {kW / 2 - 1, kW / 2})
      count += std::abs(luminance(out.at(x, y)) - luminance(clean.at(x, y))) > tolerance;
  return count;
}

// A shadow's edge: one albedo and one normal on both sides, so only the visibility guide shows
// it. The noise is strong against the step (the luminance weight alone would keep a step of
// many sigma): the guide keeps the edge pixels on their side, and without it they blur.
TEST(Denoiser, ShadowEdgeSurvivesThroughTheVisibilityGuideAlone) {
  DenoiseFeatures f = flat_features(Color(1.0f));
  f.visibility.assign(f.albedo.size(), 1.0f);
  f.visibility_variance.assign(f.albedo.size(), 0.0f);
  Image clean(kW, kH);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const bool shadow = x < kW / 2;
      f.visibility[static_cast<size_t>(y) * kW + x] = shadow ? 0.0f : 1.0f;
      clean.at(x, y) = Color(shadow ? 0.2f : 0.5f);  // indirect light only in the shadow
    }
  const float sigma = 0.15f, tolerance = 0.05f;
  const NoisyImage noisy = known_variance(with_noise(clean, sigma, 11), sigma * sigma);
  EXPECT_EQ(edge_pixels_off_their_side(denoise(noisy, f), clean, tolerance), 0);
  f.visibility.clear();
  f.visibility_variance.clear();
  EXPECT_GT(edge_pixels_off_their_side(denoise(noisy, f), clean, tolerance), kH / 2);
}

// A box's face before a wall: one albedo and one normal, only the depth differs, which the
// position guide shows. The noise is strong against the step, as in the shadow test above.
TEST(Denoiser, ADepthStepSurvivesThroughThePositionGuideAlone) {
  DenoiseFeatures f = flat_features(Color(1.0f));
  f.position.resize(f.albedo.size());
  Image clean(kW, kH);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const bool front = x < kW / 2;
      // Both planes face +z (the flat normal); pixels 1 cm apart, the wall 1 m behind.
      f.position[static_cast<size_t>(y) * kW + x] = Vec3f(0.01f * x, 0.01f * y, front ? 0 : -1);
      clean.at(x, y) = Color(front ? 0.5f : 0.2f);
    }
  const float sigma = 0.15f, tolerance = 0.05f;
  const NoisyImage noisy = known_variance(with_noise(clean, sigma, 11), sigma * sigma);
  EXPECT_EQ(edge_pixels_off_their_side(denoise(noisy, f), clean, tolerance), 0);
  f.position.clear();
  EXPECT_GT(edge_pixels_off_their_side(denoise(noisy, f), clean, tolerance), kH / 2);
}

// Light rising towards an edge the normals show (a face lit more strongly near its rim): the
// mean of one side's taps lies inside the face, so it is darker than the rim; the first-order
// fit follows the slope up to the edge.
TEST(Denoiser, AGradientUpToAnEdgeKeepsItsValueWithTheFirstOrderFit) {
  DenoiseFeatures f = flat_features(Color(1.0f));
  Image clean(kW, kH);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const bool face = x < kW / 2;
      f.normal[static_cast<size_t>(y) * kW + x] = face ? Vec3f(0, 0, 1) : Vec3f(1, 0, 0);
      clean.at(x, y) = Color(face ? 0.2f + 0.02f * x : 0.1f);
    }
  const float sigma = 0.01f;
  const NoisyImage noisy = known_variance(with_noise(clean, sigma, 3), sigma * sigma);
  // The mean error of the face's last column over the rows (the noise averages out).
  auto rim_bias = [&](bool first_order) {
    DenoiseParams params;
    params.first_order = first_order;
    const Image out = denoise(noisy, f, params);
    double sum = 0;
    for (int y = 0; y < kH; ++y) sum += out.at(kW / 2 - 1, y).x - clean.at(kW / 2 - 1, y).x;
    return sum / kH;
  };
  // The slope is 0.02 a pixel: the mean sits half a pixel inside the face (measured -0.011;
  // the luminance weight keeps the far taps out), the fit a quarter of that (-0.0027).
  const double mean_bias = rim_bias(false), fit_bias = rim_bias(true);
  EXPECT_LT(mean_bias, -0.008);
  EXPECT_LT(std::abs(fit_bias), std::abs(mean_bias) / 3) << mean_bias;
}

// Two walls 26 degrees apart (n.n' = 0.9): the normal weight 0.9^128 keeps them apart, the
// weight 0.9^1 of normal_squarings = 0 lets the noise-level step blur.
TEST(Denoiser, TheNormalWeightsSharpnessIsItsSquarings) {
  DenoiseFeatures f = flat_features(Color(1.0f));
  Image clean(kW, kH);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const bool left = x < kW / 2;
      f.normal[static_cast<size_t>(y) * kW + x] =
          left ? Vec3f(0, 0, 1) : Vec3f(0.43588989f, 0, 0.9f);
      clean.at(x, y) = Color(left ? 0.5f : 0.2f);
    }
  const float sigma = 0.15f, tolerance = 0.05f;
  const NoisyImage noisy = known_variance(with_noise(clean, sigma, 11), sigma * sigma);
  auto off_side = [&](int squarings) {
    DenoiseParams params;
    params.normal_squarings = squarings;
    return edge_pixels_off_their_side(denoise(noisy, f, params), clean, tolerance);
  };
  EXPECT_EQ(off_side(DenoiseParams{}.normal_squarings), 0);
  EXPECT_GT(off_side(0), kH / 2);
}

// In soft shadows a pixel's few light samples make the guide noisy: its variance must let the
// filter average across that noise instead of stopping at every pixel.
TEST(Denoiser, ANoisyVisibilityGuideWithItsVarianceStillFilters) {
  const float sigma = 0.1f;
  Image clean(kW, kH, Color(0.4f));
  const NoisyImage noisy = known_variance(with_noise(clean, sigma, 7), sigma * sigma);
  DenoiseFeatures f = flat_features();
  const double unguided = compare_images(denoise(noisy, f), clean).rmse;
  // A penumbra at half visibility, estimated per pixel from 8 samples (variance 0.25 / 8).
  std::mt19937 rng(5);
  std::binomial_distribution<int> visible(8, 0.5);
  for (size_t p = 0; p < f.albedo.size(); ++p)
    f.visibility.push_back(static_cast<float>(visible(rng)) / 8.0f);
  f.visibility_variance.assign(f.albedo.size(), 0.25f / 8.0f);
  const double with_variance = compare_images(denoise(noisy, f), clean).rmse;
  std::fill(f.visibility_variance.begin(), f.visibility_variance.end(), 0.0f);
  const double as_if_exact = compare_images(denoise(noisy, f), clean).rmse;
  EXPECT_LT(with_variance, 1.2 * unguided) << unguided;
  EXPECT_GT(as_if_exact, 1.5 * unguided) << unguided;
}

TEST(Denoiser, PixelsWithoutSamplesTakeTheirNeighboursValue) {
  Image image(kW, kH, Color(0.25f));
  NoisyImage in = known_variance(image, 0.001f);
  for (int x = 10; x < 14; ++x) {
    size_t p = static_cast<size_t>(5) * kW + x;
    in.has_estimate[p] = 0;
    in.color.at(x, 5) = Color(0.0f);
  }
  Image out = denoise(in, flat_features());
  for (int x = 10; x < 14; ++x) EXPECT_NEAR(out.at(x, 5).x, 0.25f, 1e-5f) << x;
}

TEST(Denoiser, SizeMismatchIsRefused) {
  Image image(kW + 1, kH);
  EXPECT_THROW(denoise(known_variance(image, 0.0f), flat_features()), std::invalid_argument);
  DenoiseFeatures f = flat_features();
  f.visibility.assign(f.albedo.size() - 1, 1.0f);
  f.visibility_variance.assign(f.albedo.size(), 0.0f);
  Image fits(kW, kH);
  EXPECT_THROW(denoise(known_variance(fits, 0.0f), f), std::invalid_argument);
  // Parameters set by `set` are refused.
  auto refused = [&](auto set) {
    DenoiseParams params;
    set(params);
    try {
      denoise(known_variance(fits, 0.0f), flat_features(), params);
    } catch (const std::invalid_argument&) {
      return true;
    }
    return false;
  };
  for (int squarings : {-1, 33})
    EXPECT_TRUE(refused([&](DenoiseParams& p) { p.normal_squarings = squarings; })) << squarings;
  for (float bad : {0.0f, -1.0f, NAN, INFINITY}) {
    EXPECT_TRUE(refused([&](DenoiseParams& p) { p.sigma_visibility = bad; })) << bad;
    EXPECT_TRUE(refused([&](DenoiseParams& p) { p.sigma_plane = bad; })) << bad;
  }
  for (float bad : {-1.0f, NAN, INFINITY}) {
    EXPECT_TRUE(refused([&](DenoiseParams& p) { p.slope_ridge = bad; })) << bad;
    EXPECT_TRUE(refused([&](DenoiseParams& p) { p.first_order_shrinkage = bad; })) << bad;
  }
  DenoiseFeatures short_positions = flat_features();
  short_positions.position.assign(short_positions.albedo.size() - 1, Vec3f(0.0f));
  EXPECT_THROW(denoise(known_variance(fits, 0.0f), short_positions), std::invalid_argument);
}

// A frame's filtering with the view's guide weights computed once (as FrameResolver does) is the
// same computation as one that computes them itself: equal to the bit, on an image whose width
// is not a multiple of the eight-pixel chunks, with albedo, normal, visibility and position
// edges; guide weights of another view or parameters are refused.
TEST(Denoiser, SharedGuideWeightsGiveTheSameImageAndOnlyFitTheirView) {
  const int w = 45, h = 31;
  DenoiseFeatures f = testing::flat_features(w, h, Color(0.5f));
  f.visibility.assign(static_cast<size_t>(w) * h, 1.0f);
  f.visibility_variance.assign(f.visibility.size(), 0.001f);
  f.position.assign(f.visibility.size(), Vec3f(0.0f));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t p = static_cast<size_t>(y) * w + x;
      if (x > 20) f.albedo[p] = Color(0.2f, 0.6f, 0.3f);
      if (y > 12) f.normal[p] = normalize(Vec3f(0.3f, 0.2f, 1.0f));
      if (x + y > 40) f.visibility[p] = 0.0f;
      f.position[p] = Vec3f(static_cast<float>(x), static_cast<float>(y), x > 30 ? 5.0f : 0.0f);
    }
  Image clean(w, h, Color(0.3f, 0.4f, 0.5f));
  NoisyImage in = known_variance(with_noise(clean, 0.1f, 11), 0.01f);
  in.has_estimate[7] = 0;
  in.variance[50] = -1.0f;

  DenoiseParams params;
  const GuideWeights guides(f, params);
  const std::vector<Image> own = denoise_levels(in, f, params);
  const std::vector<Image> shared = denoise_levels(in, f, params, 0, &guides);
  ASSERT_EQ(own.size(), shared.size());
  for (size_t level = 0; level < own.size(); ++level)
    EXPECT_EQ(compare_images(own[level], shared[level]).rmse, 0.0) << level;
  EXPECT_GT(compare_images(own.back(), in.color).rmse, 0.01);  // it did filter

  DenoiseParams fewer = params;
  fewer.iterations = 3;
  EXPECT_EQ(compare_images(denoise(in, f, fewer), denoise(in, f, fewer, &guides)).rmse, 0.0);
  DenoiseParams more = params;
  more.iterations = params.iterations + 1;
  EXPECT_THROW(denoise(in, f, more, &guides), std::invalid_argument);
  DenoiseParams sharper = params;
  sharper.sigma_albedo = 0.05f;
  EXPECT_THROW(denoise(in, f, sharper, &guides), std::invalid_argument);
  const DenoiseFeatures other = testing::flat_features(w + 1, h, Color(0.5f));
  EXPECT_THROW(denoise(known_variance(Image(w + 1, h), 0.0f), other, params, &guides),
               std::invalid_argument);
}

// A point light over a floor, a square occluder between them: its shadow on the floor is the
// square scaled by 2 from the light. Where all of a pixel's feature rays reach the floor well
// inside that shadow, visibility is exactly 0; well outside it, exactly 1; noise-free both.
// Where they all reach the floor, their mean position lies on it.
TEST(DenoiseFeatures, VisibilityAndPositionAreExactUnderAPointLight) {
  Scene scene;
  const uint32_t grey = add_material(scene, Material{});
  add_mesh(scene, "floor", make_quad({-4, 0, -4}, {8, 0, 0}, {0, 0, 8}, {0, 1, 0}), grey);
  add_mesh(scene, "occluder", make_quad({-0.5f, 1, -0.5f}, {1, 0, 0}, {0, 0, 1}, {0, 1, 0}), grey);
  scene.point_lights.push_back({Vec3f(0, 2, 0), Color(5.0f)});
  CameraDesc view;
  view.position = {0, 5, 6};
  view.target = {0, 0, 0};
  scene.cameras.push_back(view);
  EmbreeNativeAccel accel;
  accel.build({scene.positions.data(), scene.positions.size(), scene.triangles.data(),
               scene.triangles.size()});
  RenderSettings settings;
  settings.width = 64;
  settings.height = 48;
  PcgSampler sampler(1);
  const TileRenderer renderer(scene, accel, scene.cameras.at(0), settings, sampler);
  const DenoiseFeatures f = render_denoise_features(renderer);
  ASSERT_EQ(f.visibility.size(), static_cast<size_t>(64 * 48));

  // Where the feature rays land, from the plane equations (not the accelerator).
  const Camera camera(view, settings.width, settings.height);
  auto on_floor = [&](int x, int y, float lo, float hi) {  // every ray's |x|, |z| in [lo, hi]
    for (int j = 0; j < kFeatureRaysPerSide; ++j)
      for (int i = 0; i < kFeatureRaysPerSide; ++i) {
        const Vec2f at{x + (i + 0.5f) / kFeatureRaysPerSide, y + (j + 0.5f) / kFeatureRaysPerSide};
        const Ray r = camera.generate_ray(at, {0.5f, 0.5f});
        const float t_occluder = (1 - r.org.y) / r.dir.y;
        const Vec3f o = r.org + r.dir * t_occluder;
        if (t_occluder > 0 && std::abs(o.x) <= 0.5f && std::abs(o.z) <= 0.5f) return false;
        const Vec3f p = r.org + r.dir * (-r.org.y / r.dir.y);
        const float m = std::max(std::abs(p.x), std::abs(p.z));
        if (r.dir.y >= 0 || m < lo || m > hi) return false;
      }
    return true;
  };
  int shadowed = 0, lit = 0;
  for (int y = 0; y < settings.height; ++y)
    for (int x = 0; x < settings.width; ++x) {
      const size_t p = static_cast<size_t>(y) * settings.width + x;
      EXPECT_GE(f.visibility[p], 0.0f);
      EXPECT_LE(f.visibility[p], 1.0f);
      EXPECT_GE(f.visibility_variance[p], 0.0f);
      if (on_floor(x, y, 0.0f, 3.9f)) {  // the mean of points on the floor
        EXPECT_NEAR(f.position[p].y, 0.0f, 1e-5f) << x << "," << y;
      }
      if (on_floor(x, y, 0.0f, 0.9f)) {
        ++shadowed;
        EXPECT_EQ(f.visibility[p], 0.0f) << x << "," << y;
        EXPECT_EQ(f.visibility_variance[p], 0.0f) << x << "," << y;
      } else if (on_floor(x, y, 1.1f, 3.9f)) {
        ++lit;
        EXPECT_EQ(f.visibility[p], 1.0f) << x << "," << y;
        EXPECT_EQ(f.visibility_variance[p], 0.0f) << x << "," << y;
      }
    }
  EXPECT_GT(shadowed, 20);
  EXPECT_GT(lit, 200);
}

TEST(Denoiser, DenoiseIsABiasedSwitchThatGroundTruthsKeepOff) {
  QualityOptions o;
  EXPECT_FALSE(o.denoise);  // the ablation did not show a win on every scene (docs/quality.md)
  o.denoise = true;
  EXPECT_TRUE(o.biased());
  EXPECT_FALSE(o.without_bias().denoise);
  EXPECT_FALSE(QualityOptions::reference().denoise);
}

class CornellDenoise : public ::testing::Test {
 protected:
  void SetUp() override {
    accel_.build({scene_.positions.data(), scene_.positions.size(), scene_.triangles.data(),
                  scene_.triangles.size()});
    settings_.width = 64;
    settings_.height = 48;
    settings_.quality = QualityOptions::reference();
  }
  Film render(const RenderSettings& s, uint32_t spp, uint64_t seed = 1) const {
    PcgSampler sampler(seed);
    TileRenderer renderer(scene_, accel_, scene_.cameras.at(0), s, sampler);
    Film film(s.width, s.height);
    renderer.render_pass(film, 0, spp);
    return film;
  }
  DenoiseFeatures features(const RenderSettings& s) const {
    PcgSampler sampler(1);
    return render_denoise_features(TileRenderer(scene_, accel_, scene_.cameras.at(0), s, sampler));
  }

  Scene scene_ = make_cornell_scene();
  EmbreeNativeAccel accel_;
  RenderSettings settings_;
};

TEST_F(CornellDenoise, LowSppDenoisedIsCloserToTheConvergedImageAndTheLightsRimStaysRaw) {
  Image converged = render(settings_, 1024, 99).resolve();
  Film film = render(settings_, 8);
  Image raw = film.resolve();
  DenoiseFeatures f = features(settings_);
  Image denoised = denoise(noisy_image(film), f);
  // Squared error away from the light (the pixels the filter may change) and the raw pixels.
  double raw_error = 0, denoised_error = 0;
  int rim = 0;
  for (int y = 0; y < raw.height(); ++y)
    for (int x = 0; x < raw.width(); ++x) {
      if (near_light(f, x, y)) {
        ++rim;
        ASSERT_EQ(denoised.at(x, y).x, raw.at(x, y).x) << x << "," << y;
        continue;
      }
      Color r = raw.at(x, y) - converged.at(x, y), d = denoised.at(x, y) - converged.at(x, y);
      raw_error += dot(r, r);
      denoised_error += dot(d, d);
    }
  EXPECT_GT(rim, 0);  // the light is in view
  EXPECT_LT(std::sqrt(denoised_error), 0.6 * std::sqrt(raw_error))
      << std::sqrt(raw_error) << " -> " << std::sqrt(denoised_error);
}

TEST_F(CornellDenoise, FeaturesAreTheSameForBothSchedulersAndFaceTheCamera) {
  RenderSettings tiles = settings_, waves = settings_;
  tiles.quality.wavefront = false;
  waves.quality.wavefront = true;
  waves.quality.batch_size = 256;
  DenoiseFeatures a = features(tiles), b = features(waves);
  ASSERT_EQ(a.albedo.size(), static_cast<size_t>(64 * 48));
  int distinct_albedos = 0;
  for (size_t p = 0; p < a.albedo.size(); ++p) {
    ASSERT_EQ(a.albedo[p].x, b.albedo[p].x);
    ASSERT_EQ(a.normal[p].z, b.normal[p].z);
    EXPECT_NEAR(length(a.normal[p]), 1.0f, 1e-4f);
    EXPECT_GE(min_component(a.albedo[p]), 0.0f);
    if (p > 0 && a.albedo[p].x != a.albedo[p - 1].x) ++distinct_albedos;
  }
  EXPECT_GT(distinct_albedos, 48);  // the walls differ in colour: edges on most rows
}

TEST_F(CornellDenoise, TheResolverDenoisesOnlyWhenAskedAndLeavesTheFilmAlone) {
  RenderSettings on = settings_;
  on.quality.denoise = true;
  PcgSampler sampler(1);
  TileRenderer off_renderer(scene_, accel_, scene_.cameras.at(0), settings_, sampler);
  TileRenderer on_renderer(scene_, accel_, scene_.cameras.at(0), on, sampler);
  Film film = render(settings_, 4);
  Image raw = film.resolve();
  FrameResolver resolver;
  Image plain = resolver.resolve(off_renderer, film);
  EXPECT_EQ(compare_images(plain, raw).rmse, 0.0);
  Image filtered = resolver.resolve(on_renderer, film);
  EXPECT_GT(compare_images(filtered, raw).rmse, 0.0);
  EXPECT_EQ(compare_images(film.resolve(), raw).rmse, 0.0);  // the film is unchanged
  EXPECT_GT(resolver.last_ms(), 0.0);
}

}  // namespace
}  // namespace tuneray
