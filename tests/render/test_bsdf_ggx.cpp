// The GGX pieces on their own: normalisation of D and of the visible-normal distribution (which
// ties the closed-form Smith Lambda to D), and visible-normal sampling against its density.
#include <gtest/gtest.h>

#include <numeric>

#include "render/bsdf.h"
#include "test_bsdf_chi2.h"

namespace tuneray {
namespace {

using testing::direction_from_angles;
using testing::SphereGrid;

struct Roughness {
  float ax, ay;
};
const Roughness kRoughness[] = {
    {0.1f, 0.1f}, {0.3f, 0.3f}, {1.0f, 1.0f}, {0.1f, 0.5f}, {1.0f, 0.2f}};

double total(const std::vector<double>& v) {
  return std::accumulate(v.begin(), v.end(), 0.0);
}

TEST(Ggx, ProjectedMicrofacetAreaIsOne) {
  // Integral of D(h) cos(theta_h) over the hemisphere = 1 for any roughness.
  SphereGrid grid{10, 20, 16};
  for (Roughness r : kRoughness) {
    double integral = total(grid.integrate([&](Vec3f h) { return ggx::D(h, r.ax, r.ay) * h.z; }));
    EXPECT_NEAR(integral, 1.0, 2e-3) << "alpha " << r.ax << "," << r.ay;
  }
}

TEST(Ggx, VisibleNormalDensityIsNormalised) {
  // Integral of G1(wo) max(0, wo.h) D(h) / wo.z = 1: Smith's Lambda is exactly what makes this
  // hold, so this checks Lambda against D.
  SphereGrid grid{10, 20, 16};
  for (Roughness r : kRoughness) {
    for (float theta : {0.0f, 45.0f, 80.0f}) {
      Vec3f wo = direction_from_angles(theta, 30.0f);
      double integral = total(grid.integrate([&](Vec3f h) {
        return ggx::G1(wo, r.ax, r.ay) * std::max(0.0f, dot(wo, h)) * ggx::D(h, r.ax, r.ay) / wo.z;
      }));
      EXPECT_NEAR(integral, 1.0, 2e-3) << "alpha " << r.ax << "," << r.ay << " theta " << theta;
    }
  }
}

TEST(Ggx, VisibleNormalSamplesMatchTheirDensity) {
  for (Roughness r : kRoughness) {
    for (float theta : {0.0f, 45.0f, 80.0f}) {
      Vec3f wo = direction_from_angles(theta, 30.0f);
      auto res = testing::sphere_chi2(
          [&](Pcg32& rng) {
            float a = rng.next_float();
            Vec3f h = ggx::sample_visible_normal(wo, r.ax, r.ay, {a, rng.next_float()});
            EXPECT_NEAR(length(h), 1.0f, 1e-5f);
            EXPECT_GE(dot(h, wo), -1e-5f);
            return std::optional(h);
          },
          [&](Vec3f h) {
            return ggx::G1(wo, r.ax, r.ay) * std::max(0.0f, dot(wo, h)) * ggx::D(h, r.ax, r.ay) /
                   wo.z;
          },
          100000);
      EXPECT_TRUE(res.chi2.problem.empty()) << res.chi2.problem;
      EXPECT_GT(res.chi2.p_value, 1e-3) << "alpha " << r.ax << "," << r.ay << " theta " << theta;
    }
  }
}

TEST(Ggx, ClosedFormValues) {
  const float a = 0.4f;
  EXPECT_NEAR(ggx::D({0, 0, 1}, a, a), 1.0f / (kPi * a * a), 1e-5f);
  EXPECT_FLOAT_EQ(ggx::Lambda({0, 0, 1}, a, a), 0.0f);
  EXPECT_FLOAT_EQ(ggx::G1({0, 0, 1}, a, a), 1.0f);
  EXPECT_EQ(ggx::D({0.6f, 0, -0.8f}, a, a), 0.0f);
  // Isotropic Lambda at theta: (-1 + sqrt(1 + a^2 tan^2 theta)) / 2.
  Vec3f w = direction_from_angles(60.0f, 123.0f);
  float t = std::tan(60.0f * kPi / 180);
  EXPECT_NEAR(ggx::Lambda(w, a, a), 0.5f * (std::sqrt(1 + a * a * t * t) - 1), 1e-5f);
}

TEST(Ggx, AnisotropyFollowsTheTangentAxes) {
  Vec3f hx = direction_from_angles(30.0f, 0.0f), hy = direction_from_angles(30.0f, 90.0f);
  EXPECT_NEAR(ggx::D(hx, 0.2f, 0.6f), ggx::D(hy, 0.6f, 0.2f), 1e-4f * ggx::D(hx, 0.2f, 0.6f));
  EXPECT_GT(ggx::D(hx, 0.6f, 0.2f), ggx::D(hy, 0.6f, 0.2f));  // rougher along x spreads along x
  EXPECT_NEAR(ggx::Lambda(hx, 0.2f, 0.6f), ggx::Lambda(hy, 0.6f, 0.2f), 1e-6f);
  // Equal alphas: no dependence on azimuth.
  for (float phi : {0.0f, 33.0f, 90.0f, 200.0f}) {
    Vec3f h = direction_from_angles(40.0f, phi);
    EXPECT_NEAR(ggx::D(h, 0.3f, 0.3f), ggx::D(direction_from_angles(40.0f, 0.0f), 0.3f, 0.3f),
                1e-4f);
  }
}

TEST(Ggx, HeightCorrelatedMaskingLiesBetweenSeparableAndMinimum) {
  for (Roughness r : kRoughness) {
    for (float to : {10.0f, 50.0f, 85.0f}) {
      for (float ti : {0.0f, 40.0f, 89.0f}) {
        Vec3f wo = direction_from_angles(to, 10.0f), wi = direction_from_angles(ti, 200.0f);
        float g2 = ggx::G2(wo, wi, r.ax, r.ay);
        float g1o = ggx::G1(wo, r.ax, r.ay), g1i = ggx::G1(wi, r.ax, r.ay);
        EXPECT_GE(g2, g1o * g1i - 1e-6f);
        EXPECT_LE(g2, std::min(g1o, g1i) + 1e-6f);
        EXPECT_NEAR(g2, ggx::G2(wi, wo, r.ax, r.ay), 1e-6f);
      }
    }
  }
}

}  // namespace
}  // namespace tuneray
