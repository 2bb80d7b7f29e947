// What the blue-noise keys are optimised for and tested against: the per-pixel error of small
// test integrands (half-plane indicators on a quadruple's dimension pairs, the shape of an
// edge or a shadow boundary), and the low-frequency share of the error's power spectrum.
#pragma once

#include <cstdint>
#include <vector>

#include "render/blue_noise.h"

namespace tuneray::blue_noise {

// f(u) = [nx * u[a] + ny * u[b] < c] over dims a, b of a quadruple.
struct HalfPlane {
  int a = 0, b = 1;
  float nx = 1, ny = 0, c = 0.5f;
  double integral = 0.5;  // exact to ~1e-6 (midpoint rule on a fine grid)
};

std::vector<HalfPlane> random_half_planes(uint64_t seed, int count);

// Estimate minus integral of `f` with the first `spp` samples of quadruple `q` of `keys`.
float pixel_error(const BlueNoiseTables& tables, const PixelKeys& keys, int q, uint32_t spp,
                  const HalfPlane& f);

// The error of every tile pixel (row-major kTileSize^2) for quadruple q.
std::vector<float> error_image(const BlueNoiseTables& tables, int q, uint32_t spp,
                               const HalfPlane& f);

// Share of the (mean-removed) power spectrum of a kTileSize^2 image at frequencies with
// radius < kTileSize / 8 (white noise: ~0.05; blue noise: less).
double low_frequency_share(const std::vector<float>& image);

}  // namespace tuneray::blue_noise
