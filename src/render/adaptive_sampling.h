// Adaptive sampling: where to put extra samples so that the expected squared error of the whole
// image drops the most.
#pragma once

#include <cstdint>
#include <vector>

#include "render/film.h"

namespace tuneray {

struct AdaptiveOptions {
  // s_i gets a floor of this fraction of the mean s, so a pixel whose first samples happened
  // to agree is not starved.
  double sigma_floor = 0.05;
  // No pixel may end above this multiple of the mean sample count after the allocation (0 = no
  // cap): a safety net against one pixel drawing most of a frame. Measured on the shared
  // scenes (docs/quality.md), tighter caps (8x, 32x) only raised the RMSE at equal time, so it
  // is loose.
  double max_ratio = 64.0;
  // Estimate each pixel's variance as the mean over its 3x3 neighbourhood: noise is spatially
  // coherent (a glossy highlight, a penumbra), and a lone estimate from 4 samples is not.
  bool filter = true;
};

// Splits `budget` extra samples over the film's pixels. Pixel i with n_i samples and estimated
// standard deviation s_i has expected squared error s_i^2 / n_i; minimising the sum under a
// fixed total gives n_i + k_i proportional to s_i (Lagrange), so
// k_i = clamp(c s_i, 0, cap) - n_i (at least 0) with c found by bisection.
// Returns per-pixel counts (row-major) summing to <= budget; fractional targets are rounded
// with the remainder carried along each block of 16 rows, so the total falls short by less
// than two samples per block and each pixel gets its target rounded up or down.
std::vector<uint32_t> allocate_adaptive_samples(const Film& film, uint64_t budget,
                                                const AdaptiveOptions& options = {});

}  // namespace tuneray
