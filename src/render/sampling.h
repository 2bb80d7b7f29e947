// Warps from uniform random numbers to directions/points, and tabulated distributions.
// Every warp has a matching pdf; tests check each pdf integrates to one and matches its samples.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "math/vec.h"

namespace tuneray {

// Cosine-weighted direction on the +z hemisphere; pdf = cos(theta) / pi.
Vec3f sample_cosine_hemisphere(Vec2f u);
inline float cosine_hemisphere_pdf(float cos_theta) {
  return cos_theta > 0 ? cos_theta * kInvPi : 0;
}

// Uniform direction on the unit sphere; pdf = 1 / (4 pi).
Vec3f sample_uniform_sphere(Vec2f u);
inline constexpr float kUniformSpherePdf = 1.0f / (4.0f * kPi);
// The largest float below 1: where a number rescaled into [0, 1) is clamped.
inline constexpr float kOneMinusEpsilon = 0x1.fffffep-1f;

// Uniform point on a disk of radius 1 (concentric mapping, for thin-lens cameras).
Vec2f sample_concentric_disk(Vec2f u);

// sin and cos of x in [-pi/4, pi/4] by their Taylor series to x^9 and x^10: the first term left
// out is below 2e-9 there, under float rounding. The series' divisors are written as reciprocals:
// without -ffast-math the compiler keeps x2 / 6 a division, and those ten divisions made the
// concentric disk mapping 4% of a Lambertian render.
inline float sin_quarter(float x) {
  float x2 = x * x;
  return x * (1 - x2 * (1.0f / 6) *
                      (1 - x2 * (1.0f / 20) * (1 - x2 * (1.0f / 42) * (1 - x2 * (1.0f / 72)))));
}
inline float cos_quarter(float x) {
  float x2 = x * x;
  return 1 - x2 * 0.5f *
                 (1 - x2 * (1.0f / 12) *
                          (1 - x2 * (1.0f / 30) * (1 - x2 * (1.0f / 56) * (1 - x2 * (1.0f / 90)))));
}

// Uniform barycentrics (b1, b2) on a triangle; the point is (1-b1-b2) p0 + b1 p1 + b2 p2.
Vec2f sample_uniform_triangle(Vec2f u);

// Power heuristic with beta = 2 (Veach 1997) for two strategies with one sample each.
inline float power_heuristic(float pdf_a, float pdf_b) {
  float a = pdf_a * pdf_a, b = pdf_b * pdf_b;
  return a + b > 0 ? a / (a + b) : 0.0f;
}

// Piecewise-constant 1D distribution over n bins of [0, 1).
class Distribution1D {
 public:
  Distribution1D() = default;
  explicit Distribution1D(std::span<const float> weights);  // negative/NaN weights count as 0

  size_t size() const { return weights_.size(); }
  float total() const { return total_; }  // sum of the weights
  // Discrete: picks bin i with probability weights[i] / total. `u` in [0,1). Returns the bin
  // and its probability in *pmf; *u_remapped (optional) is u rescaled to [0,1) inside the bin.
  size_t sample_discrete(float u, float* pmf, float* u_remapped = nullptr) const;
  float pmf(size_t i) const { return total_ > 0 ? weights_[i] / total_ : 0.0f; }
  // Where bin i starts on [0, 1] (i = size(): 1): sample_discrete picks the last bin whose
  // start is <= u.
  float cdf(size_t i) const { return cdf_[i]; }
  // Up to this many bins sample_discrete counts the starts at or below u instead of searching.
  static constexpr size_t kLinearSearchBins = 16;
  // Above it, the bin is found from a guide table of one entry per bin: entry k holds the bin
  // that u = k / n falls in, so a search starts there and rarely takes a step, where a binary
  // search over an environment map's row took ~10 mispredicted steps.
  // Continuous: x in [0,1) with density pdf(x) = n * weights[bin] / total.
  float sample_continuous(float u, float* pdf, size_t* bin = nullptr) const;
  float pdf_continuous(float x) const;

 private:
  // The last bin whose start is <= u, found from the guide table.
  size_t guided_search(float u) const;

  std::vector<float> weights_;
  std::vector<float> cdf_;       // size n + 1, cdf_[0] = 0, cdf_[n] = 1
  std::vector<uint32_t> guide_;  // empty up to kLinearSearchBins bins; else size n + 1
  float total_ = 0;
};

// Piecewise-constant 2D distribution over a width x height grid on [0,1)^2 (rows = v), e.g. an
// environment map weighted by luminance * sin(theta).
class Distribution2D {
 public:
  Distribution2D() = default;
  Distribution2D(std::span<const float> weights, int width, int height);

  bool empty() const { return conditional_.empty(); }
  // Returns (u, v) in [0,1)^2 with density *pdf (with respect to area on [0,1)^2), and in *cell
  // (optional) the index y * width + x of the grid cell it lies in.
  Vec2f sample(Vec2f u, float* pdf, size_t* cell = nullptr) const;
  float pdf(Vec2f uv) const;

 private:
  int width_ = 0, height_ = 0;
  std::vector<Distribution1D> conditional_;  // one per row
  Distribution1D marginal_;                  // over rows
};

}  // namespace tuneray
