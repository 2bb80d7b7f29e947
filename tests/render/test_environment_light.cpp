// The environment map as a light: what sample() returns must agree with what eval() and pdf()
// say about the same direction, since MIS weighs the two strategies by those values.
#include <gtest/gtest.h>

#include <cmath>

#include "math/rng.h"
#include "render/environment_light.h"

namespace tuneray {
namespace {

Environment bright_patch_environment(int w, int h) {
  Environment env;
  env.map = Image(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      env.map.at(x, y) = Color(0.1f + x % 5, 0.2f + y % 3, (x > 40 && x < 44 && y < 9) ? 500 : 1);
  env.scale = 1.5f;
  return env;
}

// Distance of uv to the nearest texel edge, in texels: a direction computed from a sampled uv
// may round across an edge, where eval() of it rightly reads the neighbour.
float edge_distance(Vec2f uv, int w, int h) {
  auto frac_dist = [](float t) {
    float f = t - std::floor(t);
    return std::min(f, 1 - f);
  };
  return std::min(frac_dist(uv.x * w), frac_dist(uv.y * h));
}

TEST(EnvironmentLight, SamplesAgreeWithEvalAndPdf) {
  const int w = 64, h = 32;
  Environment env = bright_patch_environment(w, h);
  for (bool rgba : {false, true}) {
    EnvironmentLight light(env, {rgba, false});
    Pcg32 rng(5);
    int checked = 0;
    for (int s = 0; s < 20000; ++s) {
      EnvironmentSample es = light.sample({rng.next_float(), rng.next_float()});
      ASSERT_GT(es.pdf, 0.0f);
      ASSERT_NEAR(length(es.wi), 1.0f, 1e-5f);
      Vec2f uv = EnvironmentLight::direction_to_uv(es.wi);
      if (edge_distance(uv, w, h) < 1e-3f) continue;
      // Away from the poles, where sin(theta) of a rounded direction is still accurate.
      if (std::abs(es.wi.y) > 0.999f) continue;
      ++checked;
      ASSERT_EQ(es.radiance, light.eval(es.wi)) << "rgba " << rgba << " sample " << s;
      ASSERT_NEAR(light.pdf(es.wi), es.pdf, 1e-4f * es.pdf) << "rgba " << rgba << " sample " << s;
    }
    EXPECT_GT(checked, 19000);
  }
}

// The solid-angle pdf integrates to one over the sphere (midpoint rule in u and cos(theta),
// finer than the texels), an independent check of its sin(theta) Jacobian.
TEST(EnvironmentLight, PdfIntegratesToOneOverTheSphere) {
  EnvironmentLight light(bright_patch_environment(64, 32));
  const int nu = 1024, nz = 1024;
  double integral = 0;
  for (int j = 0; j < nz; ++j) {
    const float cos_theta = 1.0f - 2.0f * (j + 0.5f) / nz;
    const float sin_theta = std::sqrt(1 - cos_theta * cos_theta);
    for (int i = 0; i < nu; ++i) {
      const float phi = 2 * kPi * (i + 0.5f) / nu;
      const Vec3f d{sin_theta * std::cos(phi), cos_theta, sin_theta * std::sin(phi)};
      integral += light.pdf(d) * (4.0 * kPi / (double(nu) * nz));
    }
  }
  EXPECT_NEAR(integral, 1.0, 2e-3);
}

}  // namespace
}  // namespace tuneray
