// Synthetic inputs for the denoiser's tests: noise-free guides and Gaussian noise with a fixed
// sequence.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "image/image.h"
#include "render/denoiser.h"
#include "render/denoiser_features.h"

namespace tuneray::testing {

// One albedo and one normal everywhere.
inline DenoiseFeatures flat_features(int w, int h, Color albedo = Color(0.5f)) {
  DenoiseFeatures f;
  f.width = w;
  f.height = h;
  f.albedo.assign(static_cast<size_t>(w) * h, albedo);
  f.normal.assign(static_cast<size_t>(w) * h, Vec3f(0, 0, 1));
  return f;
}

inline NoisyImage known_variance(const Image& color, float variance) {
  const size_t n = static_cast<size_t>(color.width()) * color.height();
  return {color, std::vector<float>(n, variance), std::vector<uint8_t>(n, 1)};
}

// Gaussian noise of standard deviation sigma on every channel (Box-Muller on mt19937, whose
// sequence the standard fixes, so the test sees the same numbers everywhere).
inline Image with_noise(const Image& clean, float sigma, uint32_t seed) {
  std::mt19937 rng(seed);
  auto uniform = [&rng] { return (static_cast<float>(rng()) + 0.5f) * 0x1p-32f; };
  Image out = clean;
  for (int y = 0; y < clean.height(); ++y)
    for (int x = 0; x < clean.width(); ++x) {
      float g[3];
      for (float& v : g)
        v = sigma * std::sqrt(-2.0f * std::log(uniform())) * std::cos(6.2831853f * uniform());
      out.at(x, y) += Color(g[0], g[1], g[2]);
    }
  return out;
}

// Whether pixel (x, y) is within one pixel of where the guides saw a light: the pixels the
// filter leaves exactly as they are.
inline bool near_light(const DenoiseFeatures& f, int x, int y) {
  for (int yy = std::max(0, y - 1); yy <= std::min(f.height - 1, y + 1); ++yy)
    for (int xx = std::max(0, x - 1); xx <= std::min(f.width - 1, x + 1); ++xx)
      if (f.emitter[static_cast<size_t>(yy) * f.width + xx]) return true;
  return false;
}

// The mean of two halves of equal sample counts: the full film's estimate.
inline Image mean_of(const Image& a, const Image& b) {
  Image out(a.width(), a.height());
  for (size_t p = 0; p < a.pixel_count(); ++p) out.data()[p] = (a.data()[p] + b.data()[p]) * 0.5f;
  return out;
}

}  // namespace tuneray::testing
