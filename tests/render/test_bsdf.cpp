// Lambert, mirror and smooth dielectric; the microfacet materials are in test_bsdf_microfacet.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

#include "render/bsdf.h"
#include "test_bsdf_chi2.h"

namespace tuneray {
namespace {

using testing::direction_from_angles;

BsdfParams make(MaterialType type) {
  BsdfParams p;
  p.type = type;
  return p;
}

Vec2f next2(Pcg32& rng) {
  float a = rng.next_float();
  return {a, rng.next_float()};
}

// --- Lambert ----------------------------------------------------------------------------------

TEST(Lambert, SamplesMatchPdfAndWeightsAreExact) {
  BsdfParams p = make(MaterialType::kLambert);
  p.base_color = Color(0.9f, 0.5f, 0.1f);
  for (float theta : {0.0f, 60.0f, 89.0f}) {
    Vec3f wo = direction_from_angles(theta, 20.0f);
    auto r = testing::sphere_chi2(
        [&](Pcg32& rng) -> std::optional<Vec3f> {
          BsdfSample s;
          if (!bsdf_sample(p, wo, rng.next_float(), next2(rng), s)) return std::nullopt;
          EXPECT_FALSE(s.is_delta);
          EXPECT_EQ(s.weight, p.base_color);
          EXPECT_NEAR(s.pdf, bsdf_pdf(p, wo, s.wi), 1e-6f);
          return s.wi;
        },
        [&](Vec3f wi) { return bsdf_pdf(p, wo, wi); }, 200000);
    EXPECT_NEAR(r.pdf_integral, 1.0, 1e-4);
    EXPECT_EQ(r.fail_fraction, 0.0);
    EXPECT_TRUE(r.chi2.problem.empty()) << r.chi2.problem;
    EXPECT_GT(r.chi2.p_value, 1e-3);
  }
}

TEST(Lambert, WhiteFurnaceReflectsEverything) {
  BsdfParams p = make(MaterialType::kLambert);
  p.base_color = Color(1.0f);
  Pcg32 rng(1);
  Vec3f wo = direction_from_angles(35.0f, 0.0f);
  for (int i = 0; i < 10000; ++i) {
    BsdfSample s;
    ASSERT_TRUE(bsdf_sample(p, wo, rng.next_float(), next2(rng), s));
    ASSERT_EQ(s.weight, Color(1.0f));  // every sample carries exactly all the energy
  }
  // Quadrature of f cos over the hemisphere agrees.
  testing::SphereGrid grid;
  auto cells =
      grid.integrate([&](Vec3f wi) { return bsdf_eval(p, wo, wi).x * std::max(0.0f, wi.z); });
  EXPECT_NEAR(std::accumulate(cells.begin(), cells.end(), 0.0), 1.0, 1e-4);
}

TEST(Lambert, ValueReciprocityAndHorizon) {
  BsdfParams p = make(MaterialType::kLambert);
  p.base_color = Color(0.5f, 0.25f, 1.0f);
  Vec3f a = direction_from_angles(10, 0), b = direction_from_angles(70, 150);
  EXPECT_EQ(bsdf_eval(p, a, b), p.base_color * kInvPi);
  EXPECT_EQ(bsdf_eval(p, a, b), bsdf_eval(p, b, a));
  Vec3f below(0.6f, 0, -0.8f);
  EXPECT_EQ(bsdf_eval(p, a, below), Color(0.0f));
  EXPECT_EQ(bsdf_eval(p, below, a), Color(0.0f));
  EXPECT_EQ(bsdf_pdf(p, a, below), 0.0f);
  EXPECT_EQ(bsdf_pdf(p, below, a), 0.0f);
  BsdfSample s;
  EXPECT_FALSE(bsdf_sample(p, below, 0.5f, {0.3f, 0.3f}, s));
  EXPECT_TRUE(bsdf_has_smooth_lobe(p));
}

// --- Mirror -----------------------------------------------------------------------------------

TEST(Mirror, ReflectsExactlyWithSpecularTint) {
  BsdfParams p = make(MaterialType::kMirror);
  p.specular_color = Color(0.9f, 0.8f, 0.7f);
  p.base_color = Color(0.1f);  // irrelevant for a mirror
  for (float theta : {0.0f, 30.0f, 89.5f}) {
    Vec3f wo = direction_from_angles(theta, 77.0f);
    BsdfSample s;
    ASSERT_TRUE(bsdf_sample(p, wo, 0.3f, {0.1f, 0.9f}, s));
    EXPECT_EQ(s.wi, Vec3f(-wo.x, -wo.y, wo.z));
    EXPECT_NEAR(length(s.wi + wo - Vec3f(0, 0, 2 * wo.z)), 0.0f, 1e-6f);  // wo + wi along n
    EXPECT_EQ(s.weight, p.specular_color);
    EXPECT_TRUE(s.is_delta);
    EXPECT_EQ(s.pdf, 1.0f);
    EXPECT_EQ(bsdf_eval(p, wo, s.wi), Color(0.0f));
    EXPECT_EQ(bsdf_pdf(p, wo, s.wi), 0.0f);
  }
  BsdfSample s;
  EXPECT_FALSE(bsdf_sample(p, {0, 0.6f, -0.8f}, 0.3f, {0.1f, 0.9f}, s));
  EXPECT_FALSE(bsdf_has_smooth_lobe(p));
}

// --- Fresnel and dielectric -------------------------------------------------------------------

TEST(Fresnel, NormalIncidence) {
  for (float n : {1.0f, 1.33f, 1.5f, 2.4f}) {
    float expected = (n - 1) * (n - 1) / ((n + 1) * (n + 1));
    EXPECT_NEAR(fresnel_dielectric(1.0f, n), expected, 1e-6f);
    EXPECT_NEAR(fresnel_dielectric(-1.0f, n), expected, 1e-6f);  // same from inside
  }
}

TEST(Fresnel, MatchesTheSineAndTangentForm) {
  // Independent textbook form: Rs = sin^2(ti - tt) / sin^2(ti + tt),
  // Rp = tan^2(ti - tt) / tan^2(ti + tt), F = (Rs + Rp) / 2.
  const double n = 1.5;
  for (double deg : {5.0, 20.0, 45.0, 56.0, 70.0, 85.0}) {
    double ti = deg * M_PI / 180, tt = std::asin(std::sin(ti) / n);
    double rs = std::pow(std::sin(ti - tt) / std::sin(ti + tt), 2);
    double rp = std::pow(std::tan(ti - tt) / std::tan(ti + tt), 2);
    EXPECT_NEAR(fresnel_dielectric(static_cast<float>(std::cos(ti)), 1.5f), 0.5 * (rs + rp), 1e-5)
        << deg << " degrees";
    // From inside along the refracted direction the reflectance is the same (reciprocity).
    EXPECT_NEAR(fresnel_dielectric(static_cast<float>(-std::cos(tt)), 1.5f), 0.5 * (rs + rp), 1e-5);
  }
  EXPECT_FLOAT_EQ(fresnel_dielectric(0.0f, 1.5f), 1.0f);  // grazing
}

TEST(Fresnel, TotalInternalReflectionBeyondCriticalAngle) {
  const float critical = std::asin(1 / 1.5f) * 180 / kPi;  // 41.8 degrees
  EXPECT_LT(fresnel_dielectric(-std::cos((critical - 0.5f) * kPi / 180), 1.5f), 1.0f);
  for (float deg : {critical + 0.1f, 50.0f, 80.0f, 89.9f})
    EXPECT_EQ(fresnel_dielectric(-std::cos(deg * kPi / 180), 1.5f), 1.0f) << deg;
}

TEST(Dielectric, LobeProbabilitiesFollowFresnel) {
  BsdfParams p = make(MaterialType::kDielectric);
  p.ior = 1.5f;
  Pcg32 rng(3);
  for (float theta : {0.0f, 40.0f, 75.0f, 89.0f}) {
    for (float side : {1.0f, -1.0f}) {
      Vec3f wo = direction_from_angles(theta, 45.0f);
      wo.z *= side;
      float f = fresnel_dielectric(wo.z, p.ior);
      const int n = 40000;
      int reflected = 0;
      for (int i = 0; i < n; ++i) {
        BsdfSample s;
        ASSERT_TRUE(bsdf_sample(p, wo, rng.next_float(), next2(rng), s));
        ASSERT_TRUE(s.is_delta);
        bool is_reflection = s.wi.z * wo.z > 0;
        reflected += is_reflection;
        // The two lobes' probabilities sum to one.
        ASSERT_NEAR(s.pdf, is_reflection ? f : 1 - f, 1e-6f);
      }
      double sigma = std::sqrt(f * (1 - f) / n);
      EXPECT_NEAR(double(reflected) / n, f, 5 * sigma + 1e-9) << theta << " side " << side;
    }
  }
}

TEST(Dielectric, TotalInternalReflectionAlwaysReflects) {
  BsdfParams p = make(MaterialType::kDielectric);
  p.ior = 1.5f;
  Vec3f wo = direction_from_angles(60.0f, 10.0f);
  wo.z = -wo.z;  // inside the glass, beyond the 41.8 degree critical angle
  for (float u : {0.0f, 0.5f, 0.999999f}) {
    BsdfSample s;
    ASSERT_TRUE(bsdf_sample(p, wo, u, {0.5f, 0.5f}, s));
    EXPECT_EQ(s.wi, Vec3f(-wo.x, -wo.y, wo.z));
    EXPECT_EQ(s.weight, Color(1.0f));
    EXPECT_EQ(s.pdf, 1.0f);
  }
}

TEST(Dielectric, RefractionObeysSnellAndIsReversible) {
  BsdfParams p = make(MaterialType::kDielectric);
  p.ior = 1.5f;
  p.transmittance = Color(0.9f, 0.5f, 0.2f);
  for (float theta : {0.0f, 30.0f, 70.0f}) {
    Vec3f wo = direction_from_angles(theta, 120.0f);
    BsdfSample s;
    ASSERT_TRUE(bsdf_sample(p, wo, 0.999f, {0.5f, 0.5f}, s));  // above F: refraction
    ASSERT_LT(s.wi.z, 0.0f);
    EXPECT_NEAR(length(s.wi), 1.0f, 1e-6f);
    float sin_o = std::hypot(wo.x, wo.y), sin_i = std::hypot(s.wi.x, s.wi.y);
    EXPECT_NEAR(sin_o, p.ior * sin_i, 1e-6f);                               // n1 sin1 = n2 sin2
    EXPECT_LE(dot(Vec3f(wo.x, wo.y, 0), Vec3f(s.wi.x, s.wi.y, 0)), 1e-7f);  // other side of n
    // Radiance entering the denser medium: tinted and divided by eta^2.
    Color expected = p.transmittance / (p.ior * p.ior);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(s.weight[c], expected[c], 1e-6f);
    // Coming back from inside along the refracted ray leads to wo again, with eta^2 gained.
    BsdfSample back;
    ASSERT_TRUE(bsdf_sample(p, s.wi, 0.999f, {0.5f, 0.5f}, back));
    EXPECT_NEAR(length(back.wi - wo), 0.0f, 1e-5f);
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(back.weight[c], p.transmittance[c] * p.ior * p.ior, 1e-5f);
  }
}

TEST(Dielectric, ConservesEnergy) {
  BsdfParams p = make(MaterialType::kDielectric);
  p.ior = 1.5f;
  Pcg32 rng(9);
  for (float side : {1.0f, -1.0f}) {
    for (float theta : {0.0f, 30.0f, 60.0f, 85.0f}) {
      Vec3f wo = direction_from_angles(theta, 0.0f);
      wo.z *= side;
      float eta = side > 0 ? p.ior : 1 / p.ior;
      float f = fresnel_dielectric(wo.z, p.ior);
      const int n = 50000;
      double energy = 0, throughput = 0;
      for (int i = 0; i < n; ++i) {
        BsdfSample s;
        ASSERT_TRUE(bsdf_sample(p, wo, rng.next_float(), next2(rng), s));
        bool refracted = s.wi.z * wo.z < 0;
        throughput += s.weight.y;
        energy += s.weight.y * (refracted ? eta * eta : 1.0f);
      }
      // Undoing the radiance scaling, glass neither creates nor absorbs energy.
      EXPECT_NEAR(energy / n, 1.0, 1e-5);
      double sigma = std::abs(1 - 1 / (eta * eta)) * std::sqrt(f * (1 - f) / n);
      EXPECT_NEAR(throughput / n, f + (1 - f) / (eta * eta), 5 * sigma + 1e-6);
    }
  }
}

TEST(Dielectric, IndexOneIsInvisible) {
  BsdfParams p = make(MaterialType::kDielectric);
  p.ior = 1.0f;
  Vec3f wo = direction_from_angles(50.0f, 10.0f);
  BsdfSample s;
  ASSERT_TRUE(bsdf_sample(p, wo, 0.0f, {0.5f, 0.5f}, s));
  EXPECT_NEAR(length(s.wi + wo), 0.0f, 1e-6f);
  EXPECT_EQ(s.weight, Color(1.0f));
  EXPECT_EQ(bsdf_eval(p, wo, s.wi), Color(0.0f));
  EXPECT_EQ(bsdf_pdf(p, wo, s.wi), 0.0f);
  EXPECT_FALSE(bsdf_has_smooth_lobe(p));
}

TEST(Dielectric, BrokenIndexGivesNoNaN) {
  BsdfParams p = make(MaterialType::kDielectric);
  for (float ior : {0.0f, -2.0f, std::nanf(""), INFINITY}) {
    p.ior = ior;
    BsdfSample s;
    Vec3f wo = direction_from_angles(30.0f, 10.0f);
    for (float u : {0.0f, 0.99f}) {
      if (bsdf_sample(p, wo, u, {0.5f, 0.5f}, s)) {
        EXPECT_TRUE(is_finite(s.wi) && is_finite(s.weight) && std::isfinite(s.pdf)) << ior;
      }
    }
  }
}

}  // namespace
}  // namespace tuneray
