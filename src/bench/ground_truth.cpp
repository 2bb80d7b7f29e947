#include "bench/ground_truth.h"

#include <filesystem>
#include <sstream>

#include "image/io.h"
#include "render/film.h"
#include "render/tile_renderer.h"

namespace tuneray {

namespace {
uint64_t fnv1a(const std::string& text) {
  uint64_t h = 1469598103934665603ULL;
  for (unsigned char c : text) h = (h ^ c) * 1099511628211ULL;
  return h;
}
}  // namespace

std::string ground_truth_path(const std::string& dir, const GroundTruthKey& k) {
  std::ostringstream s;
  s.precision(9);
  const CameraDesc& c = k.camera;
  s << "v1|" << k.scene_spec << "|" << c.position.x << "," << c.position.y << "," << c.position.z
    << "|" << c.target.x << "," << c.target.y << "," << c.target.z << "|" << c.up.x << "," << c.up.y
    << "," << c.up.z << "|" << c.vfov_deg << "|" << c.lens_radius << "|" << c.focus_distance << "|"
    << k.width << "x" << k.height << "|" << k.max_bounces << "|" << k.spp;
  if (k.until_rmse > 0) s << "|rmse<" << k.until_rmse;  // absent: names of older caches hold
  char name[40];
  std::snprintf(name, sizeof name, "truth-%016llx.exr",
                static_cast<unsigned long long>(fnv1a(s.str())));
  return (std::filesystem::path(dir) / name).string();
}

RenderSettings ground_truth_settings(const GroundTruthKey& key) {
  RenderSettings settings;
  settings.width = key.width;
  settings.height = key.height;
  settings.max_bounces = key.max_bounces;
  settings.seed = 0;
  settings.quality = QualityOptions::reference();
  return settings;
}

Image ground_truth(const std::string& dir, const GroundTruthKey& key, const Scene& scene,
                   const Accel& accel, GroundTruthInfo* info, const TruthProgress& progress) {
  GroundTruthInfo local;
  GroundTruthInfo& out = info ? *info : local;
  out = {};
  std::string path = ground_truth_path(dir, key);
  if (std::filesystem::exists(path)) {
    Image cached = read_image(path);
    if (cached.width() == key.width && cached.height() == key.height) return cached;
  }
  RenderSettings settings = ground_truth_settings(key);
  PcgSampler sampler(settings.seed);
  TileRenderer renderer(scene, accel, key.camera, settings, sampler);
  Film film(key.width, key.height);
  constexpr int kPass = 16;  // spp between error checks
  while (out.spp < key.spp) {
    uint32_t n = static_cast<uint32_t>(std::min(kPass, key.spp - out.spp));
    out.render_ms += renderer.render_pass(film, static_cast<uint32_t>(out.spp), n).render_ms;
    out.spp += static_cast<int>(n);
    if (key.until_rmse > 0) out.estimated_rmse = film.estimated_rmse();
    if (progress) progress(static_cast<int>(n), key.until_rmse > 0 ? out.estimated_rmse : -1.0);
    if (key.until_rmse > 0 && out.estimated_rmse < key.until_rmse) break;
  }
  out.estimated_rmse = film.estimated_rmse();
  out.rendered = true;
  Image image = film.resolve();
  std::filesystem::create_directories(dir);
  // Written aside and renamed, so an interrupted run never leaves a truncated cache entry.
  std::string partial = path + ".partial.exr";
  write_image(partial, image);
  std::filesystem::rename(partial, path);
  return image;
}

}  // namespace tuneray
