// The denoiser's cost per frame at the benchmark resolution (640x360): the filter alone
// (every frame) and the feature pass of camera rays (once per film) on the Cornell box.
// A denoised frame is shown this much later, so it must stay small against a frame budget.
#include <benchmark/benchmark.h>

#include <cmath>

#include "accel/embree_native.h"
#include "math/rng.h"
#include "render/denoiser.h"
#include "render/denoiser_features.h"
#include "render/sampler.h"
#include "scene/builtins.h"

namespace tuneray {
namespace {

constexpr int kW = 640, kH = 360;

// 4 samples per pixel of exponentially distributed values: heavy-tailed like path samples.
Film noisy_film() {
  Film film(kW, kH);
  Pcg32 rng(3, 7);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x)
      for (int s = 0; s < 4; ++s) {
        float v = -std::log(1.0f - rng.next_float()) * (1.0f + (x * 7 + y * 3) % 5);
        film.add(x, y, Color(v), 1, SquareSum::of(Color(v)));
      }
  return film;
}

// Walls of four colours meeting at right angles in a grid of 40-pixel cells.
DenoiseFeatures grid_features() {
  DenoiseFeatures f;
  f.width = kW;
  f.height = kH;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      int cell = (x / 40 + y / 40) % 4;
      f.albedo.push_back(Color(0.2f + 0.2f * cell, 0.5f, 0.8f - 0.15f * cell));
      f.normal.push_back(cell % 2 ? Vec3f(0, 0, 1) : Vec3f(1, 0, 0));
    }
  return f;
}

void BM_DenoiseFilter(benchmark::State& state) {
  NoisyImage in = noisy_image(noisy_film());
  DenoiseFeatures f = grid_features();
  for (auto _ : state) benchmark::DoNotOptimize(denoise(in, f));
}
BENCHMARK(BM_DenoiseFilter)->Unit(benchmark::kMillisecond)->UseRealTime();

// A frame's filtering when the view's guide weights are kept (FrameResolver), and computing
// them (once per view).
void BM_DenoiseFilterSharedGuides(benchmark::State& state) {
  NoisyImage in = noisy_image(noisy_film());
  DenoiseFeatures f = grid_features();
  const GuideWeights guides(f, DenoiseParams{});
  for (auto _ : state) benchmark::DoNotOptimize(denoise(in, f, {}, &guides));
}
BENCHMARK(BM_DenoiseFilterSharedGuides)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_DenoiseGuideWeights(benchmark::State& state) {
  DenoiseFeatures f = grid_features();
  for (auto _ : state) benchmark::DoNotOptimize(GuideWeights(f, DenoiseParams{}));
}
BENCHMARK(BM_DenoiseGuideWeights)->Unit(benchmark::kMillisecond)->UseRealTime();

// The same with each iteration taking its taps' weighted mean instead of a first-order fit.
void BM_DenoiseFilterZeroOrder(benchmark::State& state) {
  NoisyImage in = noisy_image(noisy_film());
  DenoiseFeatures f = grid_features();
  DenoiseParams params;
  params.first_order = false;
  for (auto _ : state) benchmark::DoNotOptimize(denoise(in, f, params));
}
BENCHMARK(BM_DenoiseFilterZeroOrder)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_NoisyImageFromFilm(benchmark::State& state) {
  Film film = noisy_film();
  for (auto _ : state) benchmark::DoNotOptimize(noisy_image(film));
}
BENCHMARK(BM_NoisyImageFromFilm)->Unit(benchmark::kMillisecond)->UseRealTime();

// The guides' pass on the built-in Cornell box: from scratch at state.range(0) rays a pixel side,
// or (state.range(1) = 1) the 4x4 refinement of 2x2 guides, as FrameResolver renders it.
void BM_DenoiseFeaturesCornell(benchmark::State& state) {
  Scene scene = make_cornell_scene();
  EmbreeNativeAccel accel;
  accel.build({scene.positions.data(), scene.positions.size(), scene.triangles.data(),
               scene.triangles.size()});
  RenderSettings settings;
  PcgSampler sampler(1);
  TileRenderer renderer(scene, accel, scene.cameras.at(0), settings, sampler);
  const int side = static_cast<int>(state.range(0));
  const bool refine = state.range(1) != 0;
  const DenoiseFeatures coarse = render_denoise_features(renderer, kFirstFeatureRaysPerSide);
  for (auto _ : state)
    benchmark::DoNotOptimize(render_denoise_features(renderer, side, refine ? &coarse : nullptr));
}
BENCHMARK(BM_DenoiseFeaturesCornell)
    ->Args({kFirstFeatureRaysPerSide, 0})
    ->Args({kFeatureRaysPerSide, 0})
    ->Args({kFeatureRaysPerSide, 1})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace tuneray

BENCHMARK_MAIN();
