// Statistical helpers for the sampling and BSDF tests: Pearson's chi-square test with pooling of
// sparse cells (as in Mitsuba's chi2 tests), and quadrature of densities over a (theta, phi) grid.
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>
#include <optional>
#include <string>
#include <vector>

#include "math/rng.h"
#include "math/vec.h"

namespace tuneray::testing {

// Regularized upper incomplete gamma function Q(a, x): series below a + 1, continued fraction
// (modified Lentz) above.
inline double gamma_q(double a, double x) {
  if (x <= 0) return 1.0;
  const double log_prefix = -x + a * std::log(x) - std::lgamma(a);
  if (x < a + 1) {
    double term = 1.0 / a, sum = term;
    for (int n = 1; n < 1000 && std::abs(term) > 1e-15 * std::abs(sum); ++n) {
      term *= x / (a + n);
      sum += term;
    }
    return std::max(0.0, 1.0 - sum * std::exp(log_prefix));
  }
  const double tiny = 1e-300;
  double b = x + 1 - a, c = 1 / tiny, d = 1 / b, h = d;
  for (int i = 1; i < 1000; ++i) {
    double an = -i * (i - a);
    b += 2;
    d = an * d + b;
    if (std::abs(d) < tiny) d = tiny;
    c = b + an / c;
    if (std::abs(c) < tiny) c = tiny;
    d = 1 / d;
    double step = d * c;
    h *= step;
    if (std::abs(step - 1) < 1e-15) break;
  }
  return std::exp(log_prefix) * h;
}

// P(X >= statistic) for X chi-square distributed with `dof` degrees of freedom.
inline double chi2_survival(double statistic, int dof) {
  return gamma_q(0.5 * dof, 0.5 * statistic);
}

struct Chi2Outcome {
  double p_value = 0;
  double statistic = 0;
  int dof = 0;
  std::string problem;  // set when a sample landed where the density is zero
};

// Pearson test of observed against expected counts (same total). Cells expecting fewer than
// `min_expected` are pooled, smallest first, until the pool is large enough to count as a cell.
inline Chi2Outcome chi2_test(const std::vector<double>& observed,
                             const std::vector<double>& expected, double min_expected = 5.0) {
  Chi2Outcome out;
  std::vector<size_t> order(observed.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(),
            [&](size_t a, size_t b) { return expected[a] < expected[b]; });
  double pool_obs = 0, pool_exp = 0;
  int cells = 0;
  for (size_t i : order) {
    if (expected[i] <= 0 && observed[i] > 0) {
      out.problem = "cell " + std::to_string(i) + " has " + std::to_string(observed[i]) +
                    " samples where the density integrates to 0";
      return out;
    }
    if (expected[i] < min_expected || (pool_exp > 0 && pool_exp < min_expected)) {
      pool_obs += observed[i];
      pool_exp += expected[i];
      if (pool_exp >= min_expected) {
        out.statistic += (pool_obs - pool_exp) * (pool_obs - pool_exp) / pool_exp;
        ++cells;
        pool_obs = pool_exp = 0;
      }
      continue;
    }
    out.statistic += (observed[i] - expected[i]) * (observed[i] - expected[i]) / expected[i];
    ++cells;
  }
  if (pool_exp > 0) {
    out.statistic += (pool_obs - pool_exp) * (pool_obs - pool_exp) / pool_exp;
    ++cells;
  }
  out.dof = std::max(cells - 1, 1);
  out.p_value = chi2_survival(out.statistic, out.dof);
  return out;
}

// Integrals of f(direction) over the cells of a theta x phi grid on the sphere (theta from +z),
// by composite 3-point Gauss-Legendre with `ires` sub-intervals per cell side. Only interior
// points are evaluated, so densities that jump at a cell edge (the horizon) are integrated on
// the correct side.
struct SphereGrid {
  int theta_bins = 10, phi_bins = 20, ires = 8;

  int cell_of(Vec3f w) const {
    float theta = std::acos(std::clamp(w.z, -1.0f, 1.0f));
    float phi = std::atan2(w.y, w.x);
    if (phi < 0) phi += 2 * kPi;
    int t = std::clamp(static_cast<int>(theta / kPi * theta_bins), 0, theta_bins - 1);
    int p = std::clamp(static_cast<int>(phi / (2 * kPi) * phi_bins), 0, phi_bins - 1);
    return t * phi_bins + p;
  }

  std::vector<double> integrate(const std::function<double(Vec3f)>& f) const {
    static constexpr double kNodes[3] = {-0.7745966692414834, 0.0, 0.7745966692414834};
    static constexpr double kWeights[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
    const double dt = M_PI / theta_bins / ires, dp = 2 * M_PI / phi_bins / ires;
    // Abscissae and weights along one axis of one cell, relative to the cell start.
    std::vector<double> offsets, weights;
    for (int k = 0; k < ires; ++k) {
      for (int g = 0; g < 3; ++g) {
        offsets.push_back(k + 0.5 * (1 + kNodes[g]));
        weights.push_back(0.5 * kWeights[g]);
      }
    }
    std::vector<double> cells(static_cast<size_t>(theta_bins * phi_bins), 0.0);
    for (int t = 0; t < theta_bins; ++t) {
      for (int p = 0; p < phi_bins; ++p) {
        double sum = 0;
        for (size_t i = 0; i < offsets.size(); ++i) {
          double theta = (t * ires + offsets[i]) * dt;
          double sin_t = std::sin(theta), cos_t = std::cos(theta);
          double row = 0;
          for (size_t j = 0; j < offsets.size(); ++j) {
            double phi = (p * ires + offsets[j]) * dp;
            Vec3f w(static_cast<float>(sin_t * std::cos(phi)),
                    static_cast<float>(sin_t * std::sin(phi)), static_cast<float>(cos_t));
            row += weights[j] * f(w);
          }
          sum += weights[i] * sin_t * row;
        }
        cells[static_cast<size_t>(t * phi_bins + p)] = sum * dt * dp;
      }
    }
    return cells;
  }
};

struct SphereChi2Result {
  Chi2Outcome chi2;
  double pdf_integral = 0;   // quadrature of the pdf over the sphere
  double fail_fraction = 0;  // share of sample() calls that produced no direction
};

// Draws `n` samples (sample returns nullopt when it produces none), bins them, and tests the
// distribution of successful samples against the pdf restricted and renormalised to them.
inline SphereChi2Result sphere_chi2(const std::function<std::optional<Vec3f>(Pcg32&)>& sample,
                                    const std::function<double(Vec3f)>& pdf, int n,
                                    uint64_t seed = 7, SphereGrid grid = {}) {
  SphereChi2Result r;
  std::vector<double> expected = grid.integrate(pdf);
  r.pdf_integral = std::accumulate(expected.begin(), expected.end(), 0.0);
  std::vector<double> observed(expected.size(), 0.0);
  Pcg32 rng(seed);
  int successes = 0;
  for (int i = 0; i < n; ++i) {
    std::optional<Vec3f> w = sample(rng);
    if (!w) continue;
    ++successes;
    observed[static_cast<size_t>(grid.cell_of(*w))] += 1;
  }
  r.fail_fraction = 1.0 - static_cast<double>(successes) / n;
  for (double& e : expected) e *= successes / r.pdf_integral;
  r.chi2 = chi2_test(observed, expected);
  return r;
}

inline Vec3f direction_from_angles(float theta_degrees, float phi_degrees) {
  float t = theta_degrees * kPi / 180, p = phi_degrees * kPi / 180;
  return {std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t)};
}

}  // namespace tuneray::testing
