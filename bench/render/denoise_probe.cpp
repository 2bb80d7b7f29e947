// The denoiser's error against a reference, without timing: renders a scene at a fixed sample
// count (PCG, uniform spp, the given seed), then prints the RMSE of every fixed strength, of
// the per-pixel choice the half films make, and of an oracle that chooses with the reference
// (same 13x13 window). The numbers in docs/quality.md's denoiser sections come from here.
//
//   denoise_probe SCENE REFERENCE.pfm SPP [SEED] [--mean] [--no-plane]
//
// SCENE is a built-in name or a scene file ($TUNERAY_SCENES resolves its meshes); the
// reference sets the image size and must have been rendered with 8 bounces.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <vector>

#include "accel/embree_native.h"
#include "image/io.h"
#include "image/metrics.h"
#include "render/denoiser.h"
#include "render/denoiser_features.h"
#include "render/denoiser_selection.h"
#include "render/sampler.h"
#include "scene/load.h"

namespace tuneray {
namespace {

constexpr int kBounces = 8;

int run(int argc, char** argv) {
  std::vector<std::string> positional;
  DenoiseParams params;
  bool plane = true;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--mean")
      params.first_order = false;
    else if (a == "--no-plane")
      plane = false;
    else
      positional.push_back(a);
  }
  if (positional.size() < 3 || positional.size() > 4) {
    std::fprintf(stderr,
                 "usage: denoise_probe SCENE REFERENCE.pfm SPP [SEED] [--mean] [--no-plane]\n");
    return 2;
  }
  const int spp = std::atoi(positional[2].c_str());
  const uint64_t seed =
      positional.size() > 3 ? std::strtoull(positional[3].c_str(), nullptr, 10) : 1;
  if (spp < 2) {
    std::fprintf(stderr, "denoise_probe: SPP must be at least 2 (the halves need a sample each)\n");
    return 2;
  }
  LoadOptions load;
  if (const char* dir = std::getenv("TUNERAY_SCENES")) load.scenes_dir = dir;
  const Scene scene = load_scene(positional[0], load);
  const Image reference = read_image(positional[1]);
  EmbreeNativeAccel accel;
  accel.build({scene.positions.data(), scene.positions.size(), scene.triangles.data(),
               scene.triangles.size()});
  RenderSettings settings;
  settings.width = reference.width();
  settings.height = reference.height();
  settings.max_bounces = kBounces;
  settings.seed = seed;
  PcgSampler sampler(seed);
  TileRenderer renderer(scene, accel, scene.cameras.at(0), settings, sampler);
  Film film(settings.width, settings.height);
  renderer.render_pass(film, 0, static_cast<uint32_t>(spp));
  DenoiseFeatures features = render_denoise_features(renderer);
  if (!plane) features.position.clear();

  auto rmse = [&](const Image& image) { return compare_images(image, reference).rmse; };
  const NoisyImage full = noisy_image(film), a = noisy_half_image(film, 0),
                   b = noisy_half_image(film, 1);
  const std::vector<Image> levels = denoise_levels(full, features, params);
  std::printf("%s, %d spp, seed %llu, %s%s\nfixed strengths 0..%d:", positional[0].c_str(), spp,
              static_cast<unsigned long long>(seed),
              params.first_order ? "first-order fit" : "mean", plane ? ", plane guide" : "",
              params.iterations);
  for (const Image& level : levels) std::printf(" %.5f", rmse(level));
  const std::vector<uint8_t> choice =
      select_levels(denoise_levels(a, features, params), a, denoise_levels(b, features, params), b);
  NoisyImage truth{reference, std::vector<float>(full.variance.size(), 0.0f),
                   std::vector<uint8_t>(full.variance.size(), 1)};
  const std::vector<uint8_t> oracle = select_levels(levels, truth, levels, truth);
  std::printf("\nchosen by the halves: %.5f\noracle choice:        %.5f\n",
              rmse(compose_levels(levels, choice)), rmse(compose_levels(levels, oracle)));
  return 0;
}

}  // namespace
}  // namespace tuneray

int main(int argc, char** argv) {
  try {
    return tuneray::run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "denoise_probe: %s\n", e.what());
    return 1;
  }
}
