#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <vector>

#include "render/sampling.h"
#include "test_bsdf_chi2.h"

namespace tuneray {
namespace {

using testing::chi2_survival;
using testing::chi2_test;
using testing::sphere_chi2;
using testing::SphereGrid;

constexpr double kMinPValue = 1e-3;
constexpr int kSamples = 200000;

Vec2f next2(Pcg32& rng) {
  float a = rng.next_float();
  return {a, rng.next_float()};
}

// --- The statistics helpers themselves --------------------------------------------------------

TEST(Chi2Helpers, SurvivalMatchesClosedForms) {
  // dof = 2: P(X >= x) = exp(-x / 2); dof = 1: erfc(sqrt(x / 2)).
  for (double x : {0.1, 1.0, 5.0, 20.0, 60.0}) {
    EXPECT_NEAR(chi2_survival(x, 2), std::exp(-x / 2), 1e-12 + 1e-9 * std::exp(-x / 2));
    EXPECT_NEAR(chi2_survival(x, 1), std::erfc(std::sqrt(x / 2)), 1e-9);
  }
  EXPECT_NEAR(chi2_survival(100.0, 100), 0.4811, 1e-3);  // table value
}

TEST(Chi2Helpers, RejectsAWrongPdf) {
  // Cosine-weighted samples tested against the uniform hemisphere density must fail.
  auto r =
      sphere_chi2([](Pcg32& rng) { return std::optional(sample_cosine_hemisphere(next2(rng))); },
                  [](Vec3f w) { return w.z > 0 ? 0.5 * kInvPi : 0.0; }, kSamples);
  EXPECT_LT(r.chi2.p_value, 1e-10);
}

TEST(Chi2Helpers, FlagsSamplesWhereThePdfIsZero) {
  auto r = sphere_chi2([](Pcg32& rng) { return std::optional(sample_uniform_sphere(next2(rng))); },
                       [](Vec3f w) { return cosine_hemisphere_pdf(w.z); }, 1000);
  EXPECT_FALSE(r.chi2.problem.empty());
}

// --- Warps ------------------------------------------------------------------------------------

TEST(Warps, CosineHemisphereMatchesItsPdf) {
  auto r = sphere_chi2(
      [](Pcg32& rng) {
        Vec3f w = sample_cosine_hemisphere(next2(rng));
        EXPECT_NEAR(length(w), 1.0f, 1e-5f);
        EXPECT_GE(w.z, 0.0f);
        return std::optional(w);
      },
      [](Vec3f w) { return cosine_hemisphere_pdf(w.z); }, kSamples);
  EXPECT_NEAR(r.pdf_integral, 1.0, 1e-4);
  EXPECT_TRUE(r.chi2.problem.empty()) << r.chi2.problem;
  EXPECT_GT(r.chi2.p_value, kMinPValue);
}

TEST(Warps, UniformSphereMatchesItsPdf) {
  auto r = sphere_chi2(
      [](Pcg32& rng) {
        Vec3f w = sample_uniform_sphere(next2(rng));
        EXPECT_NEAR(length(w), 1.0f, 1e-5f);
        return std::optional(w);
      },
      [](Vec3f) { return double(kUniformSpherePdf); }, kSamples);
  EXPECT_NEAR(r.pdf_integral, 1.0, 1e-4);
  EXPECT_GT(r.chi2.p_value, kMinPValue);
}

TEST(Warps, CosineHemisphereCornersStayValid) {
  for (Vec2f u :
       {Vec2f(0, 0), Vec2f(0.5f, 0.5f), Vec2f(0.99999994f, 0.99999994f), Vec2f(0, 0.99999994f)}) {
    Vec3f w = sample_cosine_hemisphere(u);
    EXPECT_TRUE(is_finite(w));
    EXPECT_NEAR(length(w), 1.0f, 1e-5f);
  }
  EXPECT_EQ(sample_cosine_hemisphere({0.5f, 0.5f}), Vec3f(0, 0, 1));
}

TEST(Warps, ConcentricDiskIsUniform) {
  // Rings of equal area (equal steps in r^2) times equal sectors: every cell expects the same.
  const int rings = 10, sectors = 20;
  std::vector<double> observed(rings * sectors, 0.0);
  Pcg32 rng(3);
  for (int i = 0; i < kSamples; ++i) {
    Vec2f d = sample_concentric_disk(next2(rng));
    float r2 = d.x * d.x + d.y * d.y;
    ASSERT_LE(r2, 1.0f + 1e-6f);
    float phi = std::atan2(d.y, d.x);
    if (phi < 0) phi += 2 * kPi;
    int ring = std::min(static_cast<int>(r2 * rings), rings - 1);
    int sector = std::min(static_cast<int>(phi / (2 * kPi) * sectors), sectors - 1);
    observed[ring * sectors + sector] += 1;
  }
  std::vector<double> expected(observed.size(), double(kSamples) / observed.size());
  EXPECT_GT(chi2_test(observed, expected).p_value, kMinPValue);
}

TEST(Warps, ConcentricDiskMapsSquareBoundaryToCircle) {
  for (float t : {0.0f, 0.1f, 0.37f, 0.5f, 0.8f, 1.0f}) {
    for (Vec2f u : {Vec2f(t, 0), Vec2f(t, 1), Vec2f(0, t), Vec2f(1, t)}) {
      Vec2f d = sample_concentric_disk(u);
      EXPECT_NEAR(d.x * d.x + d.y * d.y, 1.0f, 1e-5f);
    }
  }
}

TEST(Warps, QuarterSineAndCosineMatchLibm) {
  for (int i = -1000; i <= 1000; ++i) {
    float x = (kPi / 4) * static_cast<float>(i) / 1000.0f;
    EXPECT_NEAR(sin_quarter(x), std::sin(static_cast<double>(x)), 2e-7) << x;
    EXPECT_NEAR(cos_quarter(x), std::cos(static_cast<double>(x)), 2e-7) << x;
  }
}

TEST(Warps, ConcentricDiskMatchesTheTrigonometricMapping) {
  // Shirley & Chiu's mapping written with libm, point by point over a grid of the square.
  for (int i = 0; i <= 64; ++i)
    for (int j = 0; j <= 64; ++j) {
      double a = 2.0 * i / 64 - 1, b = 2.0 * j / 64 - 1;
      if (a == 0 && b == 0) continue;
      double r = std::abs(a) > std::abs(b) ? a : b;
      double phi = std::abs(a) > std::abs(b) ? kPi / 4 * (b / a) : kPi / 2 - kPi / 4 * (a / b);
      Vec2f d = sample_concentric_disk({i / 64.0f, j / 64.0f});
      EXPECT_NEAR(d.x, r * std::cos(phi), 1e-6) << a << " " << b;
      EXPECT_NEAR(d.y, r * std::sin(phi), 1e-6) << a << " " << b;
    }
}

TEST(Warps, TriangleIsUniform) {
  // Grid on the (b1, b2) unit square: cells below the diagonal hold area 1/n^2, cells the
  // diagonal cuts exactly in half hold 1/(2 n^2), the rest nothing. The triangle has area 1/2.
  const int n = 12;
  std::vector<double> observed(n * n, 0.0), expected(n * n, 0.0);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      double area = i + j < n - 1 ? 1.0 : (i + j == n - 1 ? 0.5 : 0.0);
      expected[i * n + j] = kSamples * 2.0 * area / (n * n);
    }
  }
  Pcg32 rng(5);
  for (int s = 0; s < kSamples; ++s) {
    Vec2f b = sample_uniform_triangle(next2(rng));
    ASSERT_GE(b.x, 0.0f);
    ASSERT_GE(b.y, 0.0f);
    ASSERT_LE(b.x + b.y, 1.0f + 1e-6f);
    int i = std::min(static_cast<int>(b.x * n), n - 1),
        j = std::min(static_cast<int>(b.y * n), n - 1);
    observed[i * n + j] += 1;
  }
  auto r = chi2_test(observed, expected);
  EXPECT_TRUE(r.problem.empty()) << r.problem;
  EXPECT_GT(r.p_value, kMinPValue);
}

TEST(Warps, TriangleMapsCornersToVertices) {
  Vec2f a = sample_uniform_triangle({0, 0});
  EXPECT_FLOAT_EQ(a.x + a.y, 1.0f);  // the origin of the square lands on the p1-p2 edge
  Vec2f b = sample_uniform_triangle({1, 1});
  EXPECT_NEAR(b.x + b.y, 0.5f, 1e-6f);
}

TEST(Warps, PowerHeuristic) {
  EXPECT_FLOAT_EQ(power_heuristic(1, 1), 0.5f);
  EXPECT_FLOAT_EQ(power_heuristic(3, 1), 0.9f);
  EXPECT_FLOAT_EQ(power_heuristic(0, 0), 0.0f);
  EXPECT_FLOAT_EQ(power_heuristic(2, 5) + power_heuristic(5, 2), 1.0f);
}

// --- Distribution1D ---------------------------------------------------------------------------

const std::vector<float> kWeights = {
    0, 1, 0, 3, 0.5f, 0, 0, 2, std::numeric_limits<float>::quiet_NaN(), -4, 6, 0};

TEST(Distribution1D, IgnoresNegativeAndNaNWeights) {
  Distribution1D d(kWeights);
  EXPECT_EQ(d.size(), kWeights.size());
  EXPECT_FLOAT_EQ(d.total(), 12.5f);
  EXPECT_FLOAT_EQ(d.pmf(8), 0.0f);
  EXPECT_FLOAT_EQ(d.pmf(9), 0.0f);
  EXPECT_FLOAT_EQ(d.pmf(10), 6.0f / 12.5f);
}

TEST(Distribution1D, DiscreteFrequenciesMatchWeights) {
  Distribution1D d(kWeights);
  std::vector<double> observed(kWeights.size(), 0.0), expected(kWeights.size(), 0.0);
  for (size_t i = 0; i < kWeights.size(); ++i) expected[i] = kSamples * d.pmf(i);
  std::vector<double> remapped(10, 0.0);
  Pcg32 rng(11);
  for (int s = 0; s < kSamples; ++s) {
    float pmf = -1, u2 = -1;
    size_t i = d.sample_discrete(rng.next_float(), &pmf, &u2);
    ASSERT_LT(i, kWeights.size());
    ASSERT_GT(pmf, 0.0f) << "zero-weight bin " << i << " sampled";
    ASSERT_FLOAT_EQ(pmf, d.pmf(i));
    ASSERT_GE(u2, 0.0f);
    ASSERT_LT(u2, 1.0f);
    observed[i] += 1;
    remapped[std::min(static_cast<size_t>(u2 * 10), size_t{9})] += 1;
  }
  auto r = chi2_test(observed, expected);
  EXPECT_TRUE(r.problem.empty()) << r.problem;
  EXPECT_GT(r.p_value, kMinPValue);
  // The remapped number is again uniform, so it can drive a further choice.
  std::vector<double> uniform(10, kSamples / 10.0);
  EXPECT_GT(chi2_test(remapped, uniform).p_value, kMinPValue);
}

TEST(Distribution1D, ZeroWeightBinsNeverSampledAtTheEdges) {
  Distribution1D d(kWeights);
  const float below_one = 0x1.fffffep-1f;
  EXPECT_EQ(d.sample_discrete(0.0f, nullptr), 1u);
  EXPECT_EQ(d.sample_discrete(below_one, nullptr), 10u);
  // Exactly on a CDF step the next non-empty bin starts.
  EXPECT_EQ(d.sample_discrete(1.0f / 12.5f, nullptr), 3u);
  // One heavy bin at the end of many empty ones.
  std::vector<float> sparse(4096, 0.0f);
  sparse.back() = 1e-20f;
  Distribution1D s(sparse);
  for (float u : {0.0f, 0.5f, below_one}) EXPECT_EQ(s.sample_discrete(u, nullptr), 4095u);
}

// Few bins are searched linearly, many by bisection: both must pick the same bin for every u,
// including u exactly on a step. The same weight pattern repeated past the linear limit gives
// the answer of the short table, shifted.
TEST(Distribution1D, LinearAndBinarySearchAgree) {
  std::vector<float> few = {0, 1, 0, 3, 0.5f, 0, 2, 6};
  std::vector<float> many;
  for (int copy = 0; copy < 8; ++copy) many.insert(many.end(), few.begin(), few.end());
  Distribution1D small(few), large(many);
  ASSERT_EQ(large.size(), 64u);
  for (int k = 0; k < 2000; ++k) {
    float u = static_cast<float>(k) / 2000.0f;
    size_t i = small.sample_discrete(u, nullptr);
    // In the large table, the same u lands in the first copy at u * 8's position: compare
    // via the bin of u / 8 (an exact power-of-two division keeps the steps exact).
    EXPECT_EQ(large.sample_discrete(u / 8, nullptr), i) << u;
  }
  // On the steps themselves: cdf steps of the small table are multiples of 1/12.5.
  for (float step : {1.0f / 12.5f, 4.0f / 12.5f, 4.5f / 12.5f, 6.5f / 12.5f}) {
    size_t i = small.sample_discrete(step, nullptr);
    EXPECT_GT(small.pmf(i), 0.0f);
    EXPECT_EQ(large.sample_discrete(step / 8, nullptr), i) << step;
  }
}

// Above the linear limit the bin comes from the guide table: it must be the bin a bisection of
// the whole CDF finds (the last start <= u), for any u, on weights that crowd many light bins
// into one guide entry (a dark region next to a sun) or leave long runs empty.
TEST(Distribution1D, GuidedSearchAgreesWithBisection) {
  std::vector<std::vector<float>> tables;
  Pcg32 rng(29);
  std::vector<float> random(1000);
  for (float& w : random) w = rng.next_float() < 0.3f ? 0.0f : rng.next_float();
  tables.push_back(random);
  std::vector<float> sun(4096, 1e-6f);
  for (int i = 2000; i < 2004; ++i) sun[i] = 1e5f;
  tables.push_back(sun);
  std::vector<float> runs(777, 0.0f);
  for (size_t i = 0; i < runs.size(); i += 97) runs[i] = static_cast<float>(i + 1);
  tables.push_back(runs);
  tables.push_back(std::vector<float>(100, 0.0f));  // no mass: the uniform CDF
  for (const auto& weights : tables) {
    Distribution1D d(weights);
    std::vector<float> cdf(weights.size() + 1);
    for (size_t i = 0; i <= weights.size(); ++i) cdf[i] = d.cdf(i);
    auto bisect = [&](float u) {
      auto it = std::upper_bound(cdf.begin(), cdf.end(), u);
      return std::min(static_cast<size_t>(it - cdf.begin()) - 1, weights.size() - 1);
    };
    std::vector<float> us;
    for (int s = 0; s < 20000; ++s) us.push_back(rng.next_float());
    for (size_t i = 0; i < weights.size(); ++i)  // on each step and beside it
      for (float u : {cdf[i], std::nextafter(cdf[i], 0.0f), std::nextafter(cdf[i], 1.0f)})
        if (u >= 0 && u < 1) us.push_back(u);
    us.push_back(0x1.fffffep-1f);
    for (float u : us) ASSERT_EQ(d.sample_discrete(u, nullptr), bisect(u)) << u;
  }
}

TEST(Distribution1D, ContinuousPdfIsConsistent) {
  Distribution1D d(kWeights);
  const int sub = 4;  // histogram finer than the bins checks uniformity inside each bin
  const size_t cells = kWeights.size() * sub;
  std::vector<double> observed(cells, 0.0), expected(cells, 0.0);
  for (size_t c = 0; c < cells; ++c) expected[c] = kSamples * d.pmf(c / sub) / sub;
  Pcg32 rng(13);
  for (int s = 0; s < kSamples; ++s) {
    float pdf = -1;
    size_t bin = 999;
    float x = d.sample_continuous(rng.next_float(), &pdf, &bin);
    ASSERT_GE(x, 0.0f);
    ASSERT_LT(x, 1.0f);
    ASSERT_EQ(static_cast<size_t>(x * kWeights.size()), bin);
    ASSERT_GT(pdf, 0.0f);
    ASSERT_FLOAT_EQ(pdf, d.pdf_continuous(x));
    observed[std::min(static_cast<size_t>(x * cells), cells - 1)] += 1;
  }
  EXPECT_GT(chi2_test(observed, expected).p_value, kMinPValue);
  // The density integrates to one (midpoint rule is exact for a step function).
  double integral = 0;
  for (size_t c = 0; c < cells; ++c) integral += d.pdf_continuous((c + 0.5f) / cells) / cells;
  EXPECT_NEAR(integral, 1.0, 1e-6);
  EXPECT_EQ(d.pdf_continuous(-0.1f), 0.0f);
  EXPECT_EQ(d.pdf_continuous(1.0f), 0.0f);
}

TEST(Distribution1D, AllZeroWeightsGiveZeroProbabilityWithoutNaN) {
  std::vector<float> zeros(5, 0.0f);
  Distribution1D d(zeros);
  EXPECT_EQ(d.total(), 0.0f);
  for (float u : {0.0f, 0.3f, 0.99f}) {
    float pmf = -1, u2 = -1, pdf = -1;
    size_t i = d.sample_discrete(u, &pmf, &u2);
    EXPECT_LT(i, 5u);
    EXPECT_EQ(pmf, 0.0f);
    EXPECT_TRUE(u2 >= 0 && u2 < 1);
    float x = d.sample_continuous(u, &pdf);
    EXPECT_TRUE(x >= 0 && x < 1);
    EXPECT_EQ(pdf, 0.0f);
    EXPECT_EQ(d.pdf_continuous(x), 0.0f);
  }
  Distribution1D empty;
  float pmf = -1;
  EXPECT_EQ(empty.sample_discrete(0.5f, &pmf), 0u);
  EXPECT_EQ(pmf, 0.0f);
}

// --- Distribution2D ---------------------------------------------------------------------------

TEST(Distribution2D, FrequenciesAndPdfMatchWeights) {
  const int w = 8, h = 5;
  std::vector<float> weights(w * h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      weights[y * w + x] = (y == 2 || x == 3) ? 0.0f : float((x + 1) * (y + 2) % 7);
  double total = std::accumulate(weights.begin(), weights.end(), 0.0);
  Distribution2D d(weights, w, h);
  ASSERT_FALSE(d.empty());
  std::vector<double> observed(w * h, 0.0), expected(w * h, 0.0);
  for (int c = 0; c < w * h; ++c) expected[c] = kSamples * weights[c] / total;
  Pcg32 rng(17);
  for (int s = 0; s < kSamples; ++s) {
    float pdf = -1;
    Vec2f uv = d.sample(next2(rng), &pdf);
    ASSERT_TRUE(uv.x >= 0 && uv.x < 1 && uv.y >= 0 && uv.y < 1);
    int x = static_cast<int>(uv.x * w), y = static_cast<int>(uv.y * h);
    ASSERT_GT(weights[y * w + x], 0.0f) << "zero-weight cell " << x << "," << y << " sampled";
    ASSERT_NEAR(pdf, w * h * weights[y * w + x] / total, 1e-4 * pdf);
    ASSERT_FLOAT_EQ(pdf, d.pdf(uv));
    observed[y * w + x] += 1;
  }
  auto r = chi2_test(observed, expected);
  EXPECT_TRUE(r.problem.empty()) << r.problem;
  EXPECT_GT(r.p_value, kMinPValue);
  double integral = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) integral += d.pdf({(x + 0.5f) / w, (y + 0.5f) / h}) / (w * h);
  EXPECT_NEAR(integral, 1.0, 1e-5);
}

TEST(Distribution2D, RejectsBadSizes) {
  std::vector<float> weights(6, 1.0f);
  EXPECT_THROW(Distribution2D(weights, 4, 2), std::invalid_argument);
  EXPECT_THROW(Distribution2D(weights, 0, 6), std::invalid_argument);
  EXPECT_NO_THROW(Distribution2D(weights, 3, 2));
}

TEST(Distribution2D, AllZeroIsHarmless) {
  std::vector<float> zeros(12, 0.0f);
  Distribution2D d(zeros, 4, 3);
  float pdf = -1;
  Vec2f uv = d.sample({0.3f, 0.7f}, &pdf);
  EXPECT_EQ(pdf, 0.0f);
  EXPECT_TRUE(std::isfinite(uv.x) && std::isfinite(uv.y));
  EXPECT_EQ(d.pdf({0.5f, 0.5f}), 0.0f);
  Distribution2D none;
  EXPECT_TRUE(none.empty());
  EXPECT_EQ(none.pdf({0.5f, 0.5f}), 0.0f);
}

}  // namespace
}  // namespace tuneray
