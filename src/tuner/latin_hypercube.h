// Latin Hypercube sampling in [0,1]^dims: with n samples, each dimension is cut into n equal
// strata and every stratum holds exactly one sample (the position inside the stratum is
// uniform). It spreads few samples evenly along every axis, which is what the first simplex and
// the RBF centres need.
#pragma once

#include <cstddef>
#include <vector>

#include "tuner/rng.h"

namespace tuneray::tuner {

// Returns `count` points of dimension `dims`.
std::vector<std::vector<double>> latin_hypercube(size_t count, size_t dims, Rng& rng);

}  // namespace tuneray::tuner
