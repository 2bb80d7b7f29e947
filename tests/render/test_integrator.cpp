// Whole-integrator checks with analytic or cross-method answers: white furnace, agreement of
// the three light-transport strategies, determinism.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "accel/embree_native.h"
#include "image/metrics.h"
#include "render/camera.h"
#include "render/film.h"
#include "render/tile_renderer.h"
#include "render_helpers.h"
#include "scene/load.h"

namespace tuneray {
namespace {

struct Rendered {
  Image image;
  PassStats stats;
};

Rendered render(const Scene& scene, RenderSettings settings, uint32_t spp) {
  Rendered r;
  r.image = testing::render_image(scene, settings, spp, &r.stats);
  return r;
}

// Mean and standard error of the per-pixel values (all channels).
struct MeanError {
  double mean = 0, stderr_of_mean = 0;
};
MeanError pixel_statistics(const Image& img) {
  double sum = 0, sum2 = 0;
  size_t n = 0;
  for (int y = 0; y < img.height(); ++y)
    for (int x = 0; x < img.width(); ++x)
      for (int c = 0; c < 3; ++c) {
        double v = img.at(x, y)[c];
        sum += v;
        sum2 += v * v;
        ++n;
      }
  MeanError m;
  m.mean = sum / n;
  m.stderr_of_mean = std::sqrt(std::max(0.0, sum2 / n - m.mean * m.mean) / n);
  return m;
}

RenderSettings furnace_settings() {
  RenderSettings s;
  s.width = 24;
  s.height = 24;
  s.max_bounces = 64;  // Russian roulette ends paths long before
  s.russian_roulette_depth = 3;
  s.seed = 7;
  return s;
}

// A Lambertian sphere of albedo 1 in a uniform environment of radiance 1 reflects exactly 1
// in every direction: any pixel, any bounce count large enough, converges to 1.
TEST(Integrator, WhiteFurnaceDiffuseIsExactlyOne) {
  Scene scene = load_scene("furnace");
  Rendered r = render(scene, furnace_settings(), 128);
  MeanError m = pixel_statistics(r.image);
  // Truncation at 64 bounces loses 1 - (0.95)^61 only through roulette-free paths: negligible.
  EXPECT_NEAR(m.mean, 1.0, 4 * m.stderr_of_mean + 2e-3) << "stderr " << m.stderr_of_mean;
  EXPECT_EQ(r.stats.invalid_samples, 0u);
}

// Under a constant sky, light samples drawn from the BSDF (QualityOptions::bsdf_sky) and the
// BSDF-sampled rays that leave the scene share the sky between them by MIS. On the white
// furnace's convex sphere every such sample sees the sky: a diffuse path's value is then exactly
// its albedo, and a glossy one's varies with the BSDF's weight only, where uniform light samples
// (half of them below the surface) leave the usual noise. Noise: the RMS difference of two
// renders with different seeds over sqrt 2; both ways converge to the same image.
TEST(Integrator, SkyLightSamplesShapedByTheBsdfCutTheNoiseAndKeepTheMean) {
  for (const char* name : {"furnace", "furnace_ggx"}) {
    const Scene scene = load_scene(name);
    RenderSettings s = furnace_settings();
    s.quality = QualityOptions::reference();
    double noise[2] = {0, 0}, mean[2] = {0, 0}, mean_error[2] = {0, 0};
    for (const bool shaped : {false, true}) {
      s.quality.bsdf_sky = shaped;
      s.seed = 7;
      const Image a = render(scene, s, 16).image;
      s.seed = 8;
      const Rendered b = render(scene, s, 16);
      EXPECT_EQ(b.stats.invalid_samples, 0u);
      noise[shaped] = compare_images(a, b.image).rmse / std::sqrt(2.0);
      const MeanError m = pixel_statistics(b.image);
      mean[shaped] = m.mean;
      mean_error[shaped] = m.stderr_of_mean;
      std::printf("%s, %s sky samples: mean %.4f (stderr %.4f), noise %.4f\n", name,
                  shaped ? "BSDF-shaped" : "uniform", m.mean, m.stderr_of_mean, noise[shaped]);
    }
    EXPECT_NEAR(mean[1], mean[0], 4 * std::hypot(mean_error[0], mean_error[1]) + 1e-4) << name;
    // Measured 0.0009 against 0.040 on the diffuse sphere (what is left: pixels on the rim,
    // whose smooth normals send a few samples below the facets), 0.038 against 0.056 on GGX.
    const bool diffuse = std::string(name) == "furnace";
    EXPECT_LT(noise[1], (diffuse ? 0.05 : 0.8) * noise[0]) << name;
    if (diffuse) {
      EXPECT_NEAR(mean[1], 1.0, 1e-3);
    }
  }
}

// GGX with F0 = 1 and no multiple-scattering term loses energy: a convex sphere reflects each
// camera ray once into the environment, so a pixel on it converges to the directional albedo,
// which for alpha = 0.5 lies between 0.68 and 0.81 depending on the angle (quadrature, see
// test_bsdf_microfacet.cpp).
TEST(Integrator, WhiteFurnaceGgxLosesBoundedEnergy) {
  Scene scene = load_scene("furnace_ggx");
  ASSERT_EQ(scene.materials.size(), 1u);
  ASSERT_FLOAT_EQ(scene.materials[0].roughness_u, 0.5f);
  RenderSettings settings = furnace_settings();
  Rendered r = render(scene, settings, 256);

  // Pixels entirely on the sphere: every corner and the centre of the pixel hit it.
  EmbreeNativeAccel accel;
  accel.build({scene.positions.data(), scene.positions.size(), scene.triangles.data(),
               scene.triangles.size()});
  Camera camera(scene.cameras[0], settings.width, settings.height);
  double sum = 0, sum2 = 0;
  size_t n = 0;
  float highest = 0;
  for (int y = 0; y < settings.height; ++y)
    for (int x = 0; x < settings.width; ++x) {
      highest = std::max(highest, luminance(r.image.at(x, y)));
      bool covered = true;
      for (Vec2f o : {Vec2f(0, 0), Vec2f(1, 0), Vec2f(0, 1), Vec2f(1, 1), Vec2f(0.5f, 0.5f)}) {
        Hit hit;
        covered &= accel.intersect(camera.generate_ray({x + o.x, y + o.y}, {0, 0}), hit);
      }
      if (!covered) continue;
      double v = luminance(r.image.at(x, y));
      sum += v;
      sum2 += v * v;
      ++n;
    }
  ASSERT_GT(n, 50u);
  double mean = sum / n, stderr_of_mean = std::sqrt((sum2 / n - mean * mean) / n);
  EXPECT_GT(mean, 0.68 - 4 * stderr_of_mean);
  EXPECT_LT(mean, 0.81 + 4 * stderr_of_mean);
  EXPECT_LT(highest, 1.0f + 0.05f);  // nothing reflects more than it receives (plus noise)
}

// Light sampling only, BSDF sampling only and their MIS combination are three estimators of the
// same integral: their images must agree within noise, block by block. On the Cornell box (an
// area light) and on the voxels (a constant sky, its light samples shaped by the BSDF, beside a
// point light: the light choice's number is reused for the point, MIS with a selection
// probability below 1; BSDF sampling alone misses the point light there).
class Strategies : public ::testing::TestWithParam<const char*> {};
TEST_P(Strategies, ConvergeToTheSameImage) {
  Scene scene = load_scene(GetParam());
  RenderSettings s;
  s.width = 32;
  s.height = 24;
  s.max_bounces = 3;
  s.seed = 3;
  s.strategy = LightStrategy::kMis;
  Image mis = render(scene, s, 512).image;
  s.strategy = LightStrategy::kLightOnly;
  Image light = render(scene, s, 512).image;
  // BSDF sampling never finds a point light: compared only without them.
  const bool compare_bsdf = scene.point_lights.empty();
  s.strategy = LightStrategy::kBsdfOnly;
  Image bsdf = compare_bsdf ? render(scene, s, 2048).image : mis;

  // Compare 8x8-pixel block means: per-pixel noise of BSDF-only sampling is too high.
  constexpr int kBlock = 8;
  for (int by = 0; by < s.height / kBlock; ++by)
    for (int bx = 0; bx < s.width / kBlock; ++bx) {
      Color a(0), b(0), c(0);
      for (int y = by * kBlock; y < (by + 1) * kBlock; ++y)
        for (int x = bx * kBlock; x < (bx + 1) * kBlock; ++x) {
          a += mis.at(x, y);
          b += light.at(x, y);
          c += bsdf.at(x, y);
        }
      float la = luminance(a), lb = luminance(b), lc = luminance(c);
      EXPECT_NEAR(lb / la, 1.0f, 0.05f) << "block " << bx << "," << by << " light-only vs MIS";
      if (compare_bsdf) {
        EXPECT_NEAR(lc / la, 1.0f, 0.12f) << "block " << bx << "," << by << " BSDF-only vs MIS";
      }
    }
}
INSTANTIATE_TEST_SUITE_P(Integrator, Strategies, ::testing::Values("cornell", "voxels"));

TEST(Integrator, SameSeedGivesBitIdenticalImagesForAnyThreadCount) {
  Scene scene = load_scene("cornell");
  RenderSettings s;
  s.width = 40;
  s.height = 30;
  s.tile_size = 8;
  s.seed = 11;
  Image a, b, c;
  {
    tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    a = render(scene, s, 4).image;
  }
  b = render(scene, s, 4).image;
  s.seed = 12;
  c = render(scene, s, 4).image;
  size_t equal_ab = 0, equal_ac = 0;
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x) {
      equal_ab += a.at(x, y) == b.at(x, y);
      equal_ac += a.at(x, y) == c.at(x, y);
    }
  EXPECT_EQ(equal_ab, static_cast<size_t>(s.width * s.height));
  EXPECT_LT(equal_ac, static_cast<size_t>(s.width * s.height) / 2);  // a different seed differs
}

}  // namespace
}  // namespace tuneray
