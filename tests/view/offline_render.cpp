#include "offline_render.h"

#include <cmath>
#include <stdexcept>

#include "accel/factory.h"
#include "image/tonemap.h"
#include "render/blue_noise_sampler.h"
#include "render/film.h"
#include "render/tile_renderer.h"

namespace tuneray::testing {

std::vector<uint8_t> offline_display_bytes(const Scene& scene, const CameraDesc& camera, int width,
                                           int height, uint32_t spp) {
  std::unique_ptr<Accel> accel = make_accel("native");
  accel->build({scene.positions.data(), scene.positions.size(), scene.triangles.data(),
                scene.triangles.size()});
  RenderSettings settings;
  settings.width = width;
  settings.height = height;
  settings.quality = QualityOptions::reference();
  std::unique_ptr<Sampler> sampler = make_sampler(SamplerKind::kPcg, 7);
  TileRenderer renderer(scene, *accel, camera, settings, *sampler);
  Film film(width, height);
  renderer.render_pass(film, 0, spp);
  Image image = film.resolve();
  std::vector<uint8_t> bytes;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < 3; ++c) bytes.push_back(encode_display_byte(image.at(x, y)[c], 1, false));
  return bytes;
}

double display_rmse(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
  if (a.size() != b.size() || a.empty()) throw std::invalid_argument("images differ in size");
  double sum = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    double d = (static_cast<double>(a[i]) - b[i]) / 255.0;
    sum += d * d;
  }
  return std::sqrt(sum / static_cast<double>(a.size()));
}

}  // namespace tuneray::testing
