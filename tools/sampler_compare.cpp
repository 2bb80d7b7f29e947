// tuneray_sampler_compare: RMSE at equal spp of the PCG and blue-noise samplers against a
// PCG reference (docs/quality.md, "Blue-noise sampler"). Each row averages the RMSE over
// --seeds independent seeds, so the comparison is not one lucky draw. The last column uses the
// same sequences with unoptimised (white-noise) keys: the difference to it is what the key
// optimisation adds, the rest is stratification.
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <iostream>

#include "accel/embree_native.h"
#include "image/metrics.h"
#include "render/blue_noise_sampler.h"
#include "render/film.h"
#include "render/tile_renderer.h"
#include "scene/load.h"

namespace tuneray {
namespace {

struct Options {
  std::vector<std::string> scenes;
  std::string scenes_dir;
  int width = 320, height = 180;
  std::vector<uint32_t> spp{4, 16};
  uint32_t ref_spp = 256;
  int seeds = 3;
};

double rmse(const Image& a, const Image& b) {
  return compare_images(a, b).rmse;
}

// RMSE of the error after a 3x3 box filter (wrapping at the borders): how large the error
// looks from a distance. Blue-noise error is high-frequency and mostly cancels here.
double blurred_rmse(const Image& a, const Image& b) {
  const int w = a.width(), h = a.height();
  double sum = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      Color d(0.0f);
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          int xx = (x + dx + w) % w, yy = (y + dy + h) % h;
          d += a.at(xx, yy) - b.at(xx, yy);
        }
      d *= 1.0f / 9.0f;
      sum += d.x * d.x + d.y * d.y + d.z * d.z;
    }
  return std::sqrt(sum / (3.0 * w * h));
}

struct Errors {
  double plain = 0, blurred = 0;
  void add(const Image& img, const Image& ref, int n) {
    plain += rmse(img, ref) / n;
    blurred += blurred_rmse(img, ref) / n;
  }
};

int run(const Options& o) {
  std::vector<uint16_t> identity(static_cast<size_t>(blue_noise::kQuadruples) *
                                 blue_noise::kTilePixels);
  for (size_t i = 0; i < identity.size(); ++i)
    identity[i] = static_cast<uint16_t>(i % blue_noise::kTilePixels);
  const BlueNoiseTables random_keys(identity);
  for (const std::string& spec : o.scenes) {
    LoadOptions load;
    load.scenes_dir = o.scenes_dir;
    Scene scene = load_scene(spec, load);
    EmbreeNativeAccel accel;
    accel.build({scene.positions.data(), scene.positions.size(), scene.triangles.data(),
                 scene.triangles.size()});
    RenderSettings s;
    s.width = o.width;
    s.height = o.height;
    auto render_with = [&](const Sampler& sampler, uint32_t spp) {
      TileRenderer renderer(scene, accel, scene.cameras.at(0), s, sampler);
      Film film(s.width, s.height);
      renderer.render_pass(film, 0, spp);
      return film.resolve();
    };
    auto render = [&](SamplerKind kind, uint64_t seed, uint32_t spp) {
      return render_with(*make_sampler(kind, seed), spp);
    };
    Image reference = render(SamplerKind::kPcg, 1000, o.ref_spp);
    std::printf("%s (%dx%d, reference %u spp PCG)\n", spec.c_str(), o.width, o.height, o.ref_spp);
    for (uint32_t spp : o.spp) {
      Errors pcg, bn, white;
      for (int seed = 0; seed < o.seeds; ++seed) {
        pcg.add(render(SamplerKind::kPcg, seed, spp), reference, o.seeds);
        bn.add(render(SamplerKind::kBlueNoise, seed, spp), reference, o.seeds);
        white.add(render_with(BlueNoiseSampler(seed, random_keys), spp), reference, o.seeds);
      }
      std::printf(
          "  %3u spp: RMSE pcg %.5f  bluenoise %.5f (%.3f)  same tables, random keys %.5f "
          "(%.3f)\n",
          spp, pcg.plain, bn.plain, bn.plain / pcg.plain, white.plain, white.plain / pcg.plain);
      std::printf(
          "           3x3-blurred error: pcg %.5f  bluenoise %.5f (%.3f)  random keys %.5f "
          "(%.3f)\n",
          pcg.blurred, bn.blurred, bn.blurred / pcg.blurred, white.blurred,
          white.blurred / pcg.blurred);
      std::fflush(stdout);
    }
  }
  return 0;
}

}  // namespace
}  // namespace tuneray

int main(int argc, char** argv) {
  tuneray::Options o;
  CLI::App app{"RMSE of the PCG and blue-noise samplers at equal spp"};
  app.add_option("scenes", o.scenes, "Scenes (built-in name, mesh or JSON)")->required();
  app.add_option("--scenes-dir", o.scenes_dir, "Where JSON scenes' meshes are resolved");
  app.add_option("--width", o.width)->check(CLI::Range(1, 1 << 14))->capture_default_str();
  app.add_option("--height", o.height)->check(CLI::Range(1, 1 << 14))->capture_default_str();
  app.add_option("--spp", o.spp, "Sample counts compared")->capture_default_str();
  app.add_option("--ref-spp", o.ref_spp)->check(CLI::Range(1, 1 << 20))->capture_default_str();
  app.add_option("--seeds", o.seeds, "Seeds averaged per row")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  try {
    return tuneray::run(o);
  } catch (const std::exception& e) {
    std::cerr << "tuneray_sampler_compare: " << e.what() << "\n";
    return 1;
  }
}
