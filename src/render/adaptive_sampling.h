// Adaptive sampling: where to put extra samples so that the expected squared error of the whole
// image drops the most.
#pragma once

#include <cstdint>
#include <vector>

#include "render/film.h"

namespace tuneray {

// Splits `budget` extra samples over the film's pixels. Pixel i with n_i samples and estimated
// standard deviation s_i has expected squared error s_i^2 / n_i; minimising the sum under a
// fixed total gives n_i + k_i proportional to s_i (Lagrange), so k_i = max(0, c s_i - n_i) with
// c found by bisection. s_i gets a floor of 5% of the mean s so that a pixel whose first samples
// happened to agree is not starved. Returns per-pixel counts (row-major) summing to <= budget.
std::vector<uint32_t> allocate_adaptive_samples(const Film& film, uint64_t budget);

}  // namespace tuneray
