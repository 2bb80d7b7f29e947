// A small tuning problem with a known answer, used by the tuner, database and replay tests:
// a kernel with a block size and an unroll factor whose best block size grows with the input
// size (the only indicator).
#pragma once

#include <cmath>

#include "tuner/indicators.h"
#include "tuner/space.h"

namespace tuneray::tuner::testing {

inline Space kernel_space() {
  Space space;
  space.add_int_set("block", {1, 2, 4, 8, 16, 32, 64, 128}, 1)
      .add_int_set("unroll", {1, 2, 4, 8}, 1);
  return space;
}

inline IndicatorSchema kernel_schema() {
  IndicatorSchema schema;
  schema.add("size", 0.0, 1000.0);
  return schema;
}

// Best block: 2^(1 + size / 150), best unroll 4. Cost in "seconds", scale grows with size.
inline double kernel_cost(const State& state, const Config& c) {
  const double size = state[0];
  const double best_log_block = 1.0 + size / 150.0;
  const double d = std::log2(static_cast<double>(c.get_int("block"))) - best_log_block;
  const double u = std::log2(static_cast<double>(c.get_int("unroll"))) - 2.0;
  return (1.0 + size / 100.0) * (1.0 + 0.1 * d * d + 0.05 * u * u);
}

}  // namespace tuneray::tuner::testing
