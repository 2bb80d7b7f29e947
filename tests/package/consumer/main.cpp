// Ask/tell with tuneray's tuner: find the integer x in [-20, 20] that minimises (x - 3)^2 + 1.
// This file is the README's example and the installed-package test's consumer.
#include <cstdio>

#include "tuner/hybrid_tuner.h"

int main() {
  using namespace tuneray::tuner;
  Space space;
  space.add_int("x", -20, 20, /*default_value=*/-15);
  // Indicators describe the current input (e.g. a problem size); the tuner keeps what it learns
  // per input. This program has a single input.
  IndicatorSchema schema;
  schema.add("input", 0.0, 1.0);
  HybridTuner tuner(space, schema, TunerOptions{});

  const State input{0.5};
  for (int step = 0; step < 60; ++step) {
    const Config config = tuner.suggest(input);  // ask
    const double x = static_cast<double>(config.get_int("x"));
    tuner.report(config, (x - 3.0) * (x - 3.0) + 1.0);  // tell: a cost > 0, lower is better
  }
  std::printf("best x = %lld\n", static_cast<long long>(tuner.best(input).get_int("x")));
}
