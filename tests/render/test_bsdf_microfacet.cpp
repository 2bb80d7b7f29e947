// Glossy (GGX conductor) and principled (diffuse + GGX coat) materials: sampling against pdf,
// pdf normalisation, weight consistency, reciprocity and energy, over isotropic and anisotropic
// roughness and several viewing angles.
#include <gtest/gtest.h>

#include <cstdio>
#include <numeric>
#include <ostream>
#include <string>
#include <vector>

#include "render/bsdf.h"
#include "test_bsdf_chi2.h"

namespace tuneray {
namespace {

using testing::direction_from_angles;

struct Preset {
  const char* name;
  MaterialType type;
  Color base, specular;
};
const Preset kPresets[] = {
    {"Glossy", MaterialType::kGlossy, Color(0.0f), Color(0.9f, 0.6f, 0.3f)},
    {"Plastic", MaterialType::kPrincipled, Color(0.8f, 0.6f, 0.4f), Color(0.04f)},
    {"Satin", MaterialType::kPrincipled, Color(0.5f), Color(0.6f, 0.5f, 0.4f)},
};
struct Roughness {
  float ax, ay;
};
const Roughness kRoughness[] = {{0.1f, 0.1f}, {0.3f, 0.3f}, {0.6f, 0.6f},
                                {1.0f, 1.0f}, {0.1f, 0.5f}, {1.0f, 0.2f}};
const float kViewAngles[] = {0.0f, 30.0f, 60.0f, 80.0f};

struct Case {
  Preset preset;
  Roughness roughness;
  float theta_o;
};

std::vector<Case> all_cases() {
  std::vector<Case> cases;
  for (const Preset& p : kPresets)
    for (Roughness r : kRoughness)
      for (float t : kViewAngles) cases.push_back({p, r, t});
  return cases;
}

BsdfParams params_of(const Preset& preset, Roughness r) {
  BsdfParams p;
  p.type = preset.type;
  p.base_color = preset.base;
  p.specular_color = preset.specular;
  p.alpha_x = r.ax;
  p.alpha_y = r.ay;
  return p;
}

// Keeps ctest names and failure messages readable instead of a byte dump.
void PrintTo(const Case& c, std::ostream* os) {
  *os << c.preset.name << " alpha (" << c.roughness.ax << ", " << c.roughness.ay << ") theta_o "
      << c.theta_o;
}

std::string case_name(const ::testing::TestParamInfo<Case>& info) {
  const Case& c = info.param;
  auto pct = [](float v) { return std::to_string(static_cast<int>(v * 100 + 0.5f)); };
  return std::string(c.preset.name) + "_ax" + pct(c.roughness.ax) + "_ay" + pct(c.roughness.ay) +
         "_theta" + std::to_string(static_cast<int>(c.theta_o));
}

bool close(float a, float b, float rel) {
  return std::abs(a - b) <= rel * std::max(std::abs(a), std::abs(b)) + 1e-7f;
}

class MicrofacetTest : public ::testing::TestWithParam<Case> {};

TEST_P(MicrofacetTest, SamplingMatchesPdfAndEval) {
  const Case& c = GetParam();
  BsdfParams p = params_of(c.preset, c.roughness);
  Vec3f wo = direction_from_angles(c.theta_o, 35.0f);
  const int n = 200000;
  double albedo[3] = {0, 0, 0}, albedo_sq[3] = {0, 0, 0};
  int bad_weight = 0, bad_pdf = 0, bad_sample = 0;
  auto r = testing::sphere_chi2(
      [&](Pcg32& rng) -> std::optional<Vec3f> {
        float u_lobe = rng.next_float();
        float a = rng.next_float();
        BsdfSample s;
        if (!bsdf_sample(p, wo, u_lobe, {a, rng.next_float()}, s)) return std::nullopt;
        if (s.is_delta || !(s.wi.z > 0) || !(s.pdf > 0) || !is_finite(s.weight) ||
            std::abs(length(s.wi) - 1) > 1e-5f)
          ++bad_sample;
        if (!close(s.pdf, bsdf_pdf(p, wo, s.wi), 1e-4f)) ++bad_pdf;
        Color expected = bsdf_eval(p, wo, s.wi) * (s.wi.z / s.pdf);
        for (int ch = 0; ch < 3; ++ch) {
          if (!close(s.weight[ch], expected[ch], 1e-4f)) ++bad_weight;
          albedo[ch] += s.weight[ch];
          albedo_sq[ch] += double(s.weight[ch]) * s.weight[ch];
        }
        return s.wi;
      },
      [&](Vec3f wi) { return bsdf_pdf(p, wo, wi); }, n);
  EXPECT_EQ(bad_sample, 0);
  EXPECT_EQ(bad_pdf, 0);
  EXPECT_EQ(bad_weight, 0);
  // Samples lost below the horizon are exactly the pdf mass missing from the hemisphere.
  EXPECT_NEAR(r.pdf_integral + r.fail_fraction, 1.0, 4e-3)
      << "pdf integral " << r.pdf_integral << " failures " << r.fail_fraction;
  EXPECT_TRUE(r.chi2.problem.empty()) << r.chi2.problem;
  EXPECT_GT(r.chi2.p_value, 1e-3) << "chi2 " << r.chi2.statistic << " dof " << r.chi2.dof;

  // Albedo two ways: mean sample weight vs quadrature of f cos.
  testing::SphereGrid grid;
  for (int ch = 0; ch < 3; ++ch) {
    auto cells =
        grid.integrate([&](Vec3f wi) { return bsdf_eval(p, wo, wi)[ch] * std::max(0.0f, wi.z); });
    double quadrature = std::accumulate(cells.begin(), cells.end(), 0.0);
    double mc = albedo[ch] / n;
    double sigma = std::sqrt(std::max(0.0, albedo_sq[ch] / n - mc * mc) / n);
    EXPECT_NEAR(mc, quadrature, 5 * sigma + 2e-3) << "channel " << ch;
    EXPECT_LE(mc, 1.0 + 5 * sigma + 1e-3);
  }
}

TEST_P(MicrofacetTest, Reciprocity) {
  const Case& c = GetParam();
  BsdfParams p = params_of(c.preset, c.roughness);
  Pcg32 rng(21);
  for (int i = 0; i < 2000; ++i) {
    auto upper = [&] {
      float z = rng.next_float(), phi = 2 * kPi * rng.next_float();
      float s = std::sqrt(std::max(0.0f, 1 - z * z));
      return Vec3f(s * std::cos(phi), s * std::sin(phi), z);
    };
    Vec3f a = upper(), b = upper();
    if (a.z < 1e-3f || b.z < 1e-3f) continue;
    Color fab = bsdf_eval(p, a, b), fba = bsdf_eval(p, b, a);
    for (int ch = 0; ch < 3; ++ch)
      ASSERT_TRUE(close(fab[ch], fba[ch], 1e-4f)) << fab[ch] << " vs " << fba[ch];
  }
  Vec3f wo = direction_from_angles(c.theta_o, 35.0f), below(0.3f, 0.4f, -0.866f);
  EXPECT_EQ(bsdf_eval(p, wo, below), Color(0.0f));
  EXPECT_EQ(bsdf_eval(p, below, wo), Color(0.0f));
  EXPECT_EQ(bsdf_pdf(p, wo, below), 0.0f);
  EXPECT_TRUE(bsdf_has_smooth_lobe(p));
}

INSTANTIATE_TEST_SUITE_P(Materials, MicrofacetTest, ::testing::ValuesIn(all_cases()), case_name);

// Mean sample weight (failures count as 0): the directional albedo.
double albedo(const BsdfParams& p, Vec3f wo, int n, double* sigma) {
  Pcg32 rng(31);
  double sum = 0, sum_sq = 0;
  for (int i = 0; i < n; ++i) {
    float u_lobe = rng.next_float(), a = rng.next_float();
    BsdfSample s;
    if (!bsdf_sample(p, wo, u_lobe, {a, rng.next_float()}, s)) continue;
    double w = max_component(s.weight);
    sum += w;
    sum_sq += w * w;
  }
  double mean = sum / n;
  *sigma = std::sqrt(std::max(0.0, sum_sq / n - mean * mean) / n);
  return mean;
}

TEST(MicrofacetEnergy, WhiteConductorLosesBoundedEnergy) {
  // Directional albedo of single-scattering GGX with F0 = 1 and height-correlated G2, from an
  // independent double-precision midpoint integration (2000 x 4000 cells) of D G2 / (4 cos_o).
  // The loss is what multiple scattering between microfacets would return; it grows with alpha.
  struct Reference {
    float alpha;
    double albedo[4];  // at theta_o = 0, 30, 60, 80 degrees
  };
  const Reference kReference[] = {
      {0.1f, {0.9883, 0.9861, 0.9692, 0.8955}}, {0.25f, {0.9158, 0.9041, 0.8573, 0.8556}},
      {0.3f, {0.8774, 0.8639, 0.8217, 0.8482}}, {0.5f, {0.6878, 0.6831, 0.6983, 0.8053}},
      {0.7f, {0.5037, 0.5176, 0.5899, 0.7509}}, {1.0f, {0.3069, 0.3352, 0.4507, 0.6682}}};
  const float kAngles[4] = {0.0f, 30.0f, 60.0f, 80.0f};
  BsdfParams p;
  p.type = MaterialType::kGlossy;
  p.specular_color = Color(1.0f);
  for (const Reference& ref : kReference) {
    p.alpha_x = p.alpha_y = ref.alpha;
    for (int i = 0; i < 4; ++i) {
      double sigma;
      double a = albedo(p, direction_from_angles(kAngles[i], 0.0f), 100000, &sigma);
      EXPECT_NEAR(a, ref.albedo[i], 5 * sigma + 1e-3)
          << "alpha " << ref.alpha << " theta " << kAngles[i];
      EXPECT_LE(a, 1.0);
      // alpha = 0.25 is "roughness 0.5" under the usual alpha = roughness^2 mapping.
      if (ref.alpha == 0.25f) {
        EXPECT_GE(a, 0.8);
      }
    }
  }
}

TEST(MicrofacetEnergy, PrincipledNeverCreatesEnergy) {
  BsdfParams p;
  p.type = MaterialType::kPrincipled;
  p.base_color = Color(1.0f);
  for (float f0 : {0.02f, 0.04f, 0.2f, 0.5f, 1.0f}) {
    p.specular_color = Color(f0);
    double lowest = 2, highest = 0;
    for (Roughness r : kRoughness) {
      for (float theta : {0.0f, 45.0f, 70.0f, 85.0f}) {
        p.alpha_x = r.ax;
        p.alpha_y = r.ay;
        double sigma;
        double a = albedo(p, direction_from_angles(theta, 20.0f), 50000, &sigma);
        EXPECT_LE(a, 1.0 + 5 * sigma + 1e-3)
            << "F0 " << f0 << " alpha " << r.ax << "," << r.ay << " theta " << theta;
        lowest = std::min(lowest, a);
        highest = std::max(highest, a);
      }
    }
    std::printf("principled base=1 F0=%.2f albedo range [%.3f, %.3f]\n", f0, lowest, highest);
  }
}

TEST(MicrofacetEnergy, PrincipledWithoutCoatIsLambert) {
  BsdfParams p;
  p.type = MaterialType::kPrincipled;
  p.base_color = Color(0.7f, 0.4f, 0.2f);
  p.specular_color = Color(0.0f);
  BsdfParams lambert = p;
  lambert.type = MaterialType::kLambert;
  Pcg32 rng(41);
  for (int i = 0; i < 1000; ++i) {
    Vec3f wo = direction_from_angles(89 * rng.next_float(), 360 * rng.next_float());
    float u_lobe = rng.next_float(), a = rng.next_float();
    Vec2f u(a, rng.next_float());
    BsdfSample s, sl;
    ASSERT_TRUE(bsdf_sample(p, wo, u_lobe, u, s));
    ASSERT_TRUE(bsdf_sample(lambert, wo, u_lobe, u, sl));
    EXPECT_EQ(s.wi, sl.wi);
    for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(s.weight[ch], sl.weight[ch], 1e-6f);
    EXPECT_NEAR(s.pdf, sl.pdf, 1e-6f);
    Color f = bsdf_eval(p, wo, s.wi), fl = bsdf_eval(lambert, wo, s.wi);
    for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(f[ch], fl[ch], 1e-7f);
  }
}

TEST(MicrofacetEnergy, TinyRoughnessStaysFinite) {
  BsdfParams p;
  p.type = MaterialType::kGlossy;
  p.specular_color = Color(1.0f);
  for (float alpha : {0.0f, 1e-6f, std::nanf("")}) {
    p.alpha_x = p.alpha_y = alpha;
    Vec3f wo = direction_from_angles(40.0f, 0.0f);
    BsdfSample s;
    ASSERT_TRUE(bsdf_sample(p, wo, 0.5f, {0.3f, 0.6f}, s));
    EXPECT_TRUE(is_finite(s.weight) && std::isfinite(s.pdf) && s.pdf > 0);
    EXPECT_NEAR(length(s.wi - Vec3f(-wo.x, -wo.y, wo.z)), 0.0f, 0.01f);  // a near-mirror
    EXPECT_TRUE(is_finite(bsdf_eval(p, wo, s.wi)));
  }
}

}  // namespace
}  // namespace tuneray
