// Adaptive sampling's bookkeeping per pass at the benchmark resolution (640x360): the variance
// estimate, its 3x3 filter and the bisection for the Lagrange constant. This is time a frame
// does not spend on samples, so it must stay small against a frame budget of ~100 ms.
#include <benchmark/benchmark.h>

#include <cmath>

#include "math/rng.h"
#include "render/adaptive_sampling.h"
#include "render/film.h"

namespace tuneray {
namespace {

// 8 samples per pixel of exponentially distributed values: heavy-tailed like path samples.
Film noisy_film(int w, int h) {
  Film film(w, h);
  Pcg32 rng(3, 7);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int s = 0; s < 8; ++s) {
        float v = -std::log(1.0f - rng.next_float()) * (1.0f + (x * 7 + y * 3) % 5);
        film.add(x, y, Color(v), 1, SquareSum::of(Color(v)));
      }
  return film;
}

void BM_AllocateAdaptiveSamples(benchmark::State& state) {
  Film film = noisy_film(640, 360);
  AdaptiveOptions options;
  options.filter = state.range(0) != 0;
  const uint64_t budget = 640 * 360 * 4;
  for (auto _ : state) benchmark::DoNotOptimize(allocate_adaptive_samples(film, budget, options));
}
BENCHMARK(BM_AllocateAdaptiveSamples)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace tuneray
