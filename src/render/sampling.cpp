#include "render/sampling.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace tuneray {

Vec2f sample_concentric_disk(Vec2f u) {
  // Shirley & Chiu 1997: maps concentric squares to concentric circles, so strata stay compact.
  // Both wedges need the sine and cosine of an angle in [-pi/4, pi/4] only (the second wedge's
  // angle is pi/2 minus one), where short series are exact to float precision: libm's sincosf
  // was 3% of a render's time.
  // The wedge test is a coin flip for random u: selects, not branches, so nothing mispredicts.
  float a = 2.0f * u.x - 1.0f, b = 2.0f * u.y - 1.0f;
  if (a == 0 && b == 0) return {0, 0};
  const bool horizontal = std::abs(a) > std::abs(b);
  const float r = horizontal ? a : b;
  const float phi = (kPi / 4) * ((horizontal ? b : a) / r);  // second wedge: pi/2 - phi
  const float s = sin_quarter(phi), c = cos_quarter(phi);
  return {r * (horizontal ? c : s), r * (horizontal ? s : c)};
}

Vec3f sample_cosine_hemisphere(Vec2f u) {
  // Malley's method: project a uniform disk point up onto the hemisphere.
  Vec2f d = sample_concentric_disk(u);
  float z = std::sqrt(std::max(0.0f, 1.0f - d.x * d.x - d.y * d.y));
  return {d.x, d.y, z};
}

Vec3f sample_uniform_sphere(Vec2f u) {
  float z = 1.0f - 2.0f * u.x;
  float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  float phi = 2.0f * kPi * u.y;
  return {r * std::cos(phi), r * std::sin(phi), z};
}

Vec2f sample_uniform_triangle(Vec2f u) {
  // Heitz 2019, "A Low-Distortion Map Between Triangle and Square": folds the square onto the
  // triangle along its diagonal without the square root of the classic mapping.
  float b0, b1;
  if (u.y > u.x) {
    b0 = 0.5f * u.x;
    b1 = u.y - b0;
  } else {
    b1 = 0.5f * u.y;
    b0 = u.x - b1;
  }
  // (b0, b1) weight p0 and p1 in the paper; our convention returns the weights of p1 and p2.
  return {b1, 1.0f - b0 - b1};
}

Distribution1D::Distribution1D(std::span<const float> weights)
    : weights_(weights.begin(), weights.end()), cdf_(weights.size() + 1) {
  double sum = 0;
  cdf_[0] = 0;
  for (size_t i = 0; i < weights_.size(); ++i) {
    if (!(weights_[i] > 0) || !std::isfinite(weights_[i])) weights_[i] = 0;
    sum += weights_[i];
    cdf_[i + 1] = static_cast<float>(sum);
  }
  total_ = static_cast<float>(sum);
  const size_t n = weights_.size();
  if (sum > 0) {
    // Normalise from the double sums so the last entry is exactly one.
    double running = 0;
    for (size_t i = 0; i < n; ++i) {
      running += weights_[i];
      cdf_[i + 1] = static_cast<float>(running / sum);
    }
  } else {
    // No mass: a uniform CDF keeps sampling well defined (valid bin, remapped u), while every
    // reported pmf/pdf is 0 so callers see that nothing can be sampled.
    for (size_t i = 0; i < n; ++i) cdf_[i + 1] = static_cast<float>(double(i + 1) / double(n));
  }
  if (n > 0) cdf_[n] = 1.0f;
  if (n > kLinearSearchBins) {
    guide_.resize(n + 1);
    size_t bin = 0;
    for (size_t k = 0; k < n; ++k) {
      const float u = static_cast<float>(k) / static_cast<float>(n);
      while (bin + 1 < n && cdf_[bin + 1] <= u) ++bin;
      guide_[k] = static_cast<uint32_t>(bin);
    }
    guide_[n] = static_cast<uint32_t>(n - 1);
  }
}

size_t Distribution1D::guided_search(float u) const {
  const size_t n = weights_.size();
  // Clamped as a float first: a cast of a negative, huge or NaN float is undefined.
  const float x = std::min(u * static_cast<float>(n), static_cast<float>(n - 1));
  const size_t k = x > 0 ? std::min(static_cast<size_t>(x), n - 1) : 0;
  size_t i = guide_[k];
  // u * n rounds, so u may lie just below the entry's own u: step back if needed. Every
  // step below keeps the invariant cdf_[i] <= u, so the result does not depend on the guide's
  // accuracy, only the number of steps does.
  while (i > 0 && cdf_[i] > u) --i;
  size_t end = std::min<size_t>(guide_[k + 1] + 1, n);
  if (end > i + 8) {  // many light bins in one entry: bisect them
    auto it = std::upper_bound(cdf_.begin() + static_cast<std::ptrdiff_t>(i) + 1,
                               cdf_.begin() + static_cast<std::ptrdiff_t>(end), u);
    i = static_cast<size_t>(it - cdf_.begin()) - 1;
  }
  while (i + 1 < n && cdf_[i + 1] <= u) ++i;
  return i;
}

size_t Distribution1D::sample_discrete(float u, float* pmf_out, float* u_remapped) const {
  const size_t n = weights_.size();
  if (n == 0) {
    if (pmf_out) *pmf_out = 0;
    if (u_remapped) *u_remapped = u;
    return 0;
  }
  // Last bin whose CDF start is <= u. Bins of zero weight have cdf_[i] == cdf_[i + 1] and are
  // therefore never the last such bin (u < 1 = cdf_[n]). Few bins (a scene's lights) are
  // counted without branches; a binary search mispredicts at every step.
  size_t i;
  if (n <= kLinearSearchBins) {
    size_t starts_at_or_below = 0;
    for (size_t j = 1; j < n; ++j) starts_at_or_below += cdf_[j] <= u ? 1 : 0;
    i = starts_at_or_below;
  } else {
    i = guided_search(u);
  }
  if (pmf_out) *pmf_out = pmf(i);
  if (u_remapped) {
    float width = cdf_[i + 1] - cdf_[i];
    float r = width > 0 ? (u - cdf_[i]) / width : 0.0f;
    *u_remapped = std::clamp(r, 0.0f, kOneMinusEpsilon);
  }
  return i;
}

float Distribution1D::sample_continuous(float u, float* pdf, size_t* bin) const {
  float u_in_bin = 0;
  size_t i = sample_discrete(u, nullptr, &u_in_bin);
  if (bin) *bin = i;
  const size_t n = weights_.size();
  if (n == 0) {
    if (pdf) *pdf = 0;
    return 0;
  }
  if (pdf) *pdf = total_ > 0 ? static_cast<float>(n) * weights_[i] / total_ : 0.0f;
  const float fn = static_cast<float>(n);
  float x = std::min((static_cast<float>(i) + u_in_bin) / fn, kOneMinusEpsilon);
  // Rounding can push x across a bin edge; pdf_continuous(x) must see the bin we sampled.
  while (static_cast<size_t>(x * fn) > i) x = std::nextafter(x, 0.0f);
  while (static_cast<size_t>(x * fn) < i) x = std::nextafter(x, 1.0f);
  return x;
}

float Distribution1D::pdf_continuous(float x) const {
  const size_t n = weights_.size();
  if (n == 0 || !(total_ > 0) || !(x >= 0 && x < 1)) return 0.0f;
  size_t i = std::min(static_cast<size_t>(x * static_cast<float>(n)), n - 1);
  return static_cast<float>(n) * weights_[i] / total_;
}

Distribution2D::Distribution2D(std::span<const float> weights, int width, int height)
    : width_(width), height_(height) {
  if (width <= 0 || height <= 0) {
    throw std::invalid_argument("render/sampling.cpp: Distribution2D needs a positive size, got " +
                                std::to_string(width) + "x" + std::to_string(height));
  }
  size_t w = static_cast<size_t>(width), h = static_cast<size_t>(height);
  if (weights.size() != w * h) {
    throw std::invalid_argument("render/sampling.cpp: Distribution2D of " + std::to_string(width) +
                                "x" + std::to_string(height) + " given " +
                                std::to_string(weights.size()) + " weights");
  }
  conditional_.reserve(h);
  std::vector<float> row_totals(h);
  for (size_t y = 0; y < h; ++y) {
    conditional_.emplace_back(weights.subspan(y * w, w));
    row_totals[y] = conditional_.back().total();
  }
  marginal_ = Distribution1D(row_totals);
}

Vec2f Distribution2D::sample(Vec2f u, float* pdf, size_t* cell) const {
  if (empty()) {
    if (pdf) *pdf = 0;
    if (cell) *cell = 0;
    return {0, 0};
  }
  float pdf_v = 0, pdf_u = 0;
  size_t row = 0, column = 0;
  float v = marginal_.sample_continuous(u.y, &pdf_v, &row);
  float x = conditional_[row].sample_continuous(u.x, &pdf_u, &column);
  if (pdf) *pdf = pdf_v * pdf_u;
  if (cell) *cell = row * static_cast<size_t>(width_) + column;
  return {x, v};
}

float Distribution2D::pdf(Vec2f uv) const {
  if (empty() || !(uv.y >= 0 && uv.y < 1)) return 0.0f;
  size_t row = std::min(static_cast<size_t>(uv.y * static_cast<float>(height_)),
                        static_cast<size_t>(height_ - 1));
  return marginal_.pdf_continuous(uv.y) * conditional_[row].pdf_continuous(uv.x);
}

}  // namespace tuneray
