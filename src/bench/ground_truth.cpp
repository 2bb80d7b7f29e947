#include "bench/ground_truth.h"

#include <filesystem>
#include <sstream>
#include <stdexcept>

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

// Written aside and renamed, so an interrupted run never leaves a truncated cache entry.
void write_cache_image(const std::string& path, const Image& image) {
  const std::string partial = path + ".partial.exr";
  write_image(partial, image);
  std::filesystem::rename(partial, path);
}

bool halves_cached(const std::string& dir, const GroundTruthKey& key) {
  return std::filesystem::exists(ground_truth_half_path(dir, key, 0)) &&
         std::filesystem::exists(ground_truth_half_path(dir, key, 1));
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
  if (std::filesystem::exists(path) && (!key.require_halves || halves_cached(dir, key))) {
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
  // The halves first: a truth found without them is one from before they were kept.
  for (int half : {0, 1})
    write_cache_image(ground_truth_half_path(dir, key, half), film.resolve_half(half));
  write_cache_image(path, image);
  return image;
}

std::string ground_truth_half_path(const std::string& dir, const GroundTruthKey& key, int half) {
  if (half != 0 && half != 1) throw std::invalid_argument("ground truth: the halves are 0 and 1");
  std::string path = ground_truth_path(dir, key);
  return path.substr(0, path.size() - 4) + ".half" + std::to_string(half) + ".exr";
}

std::optional<GroundTruthHalves> ground_truth_halves(const std::string& dir,
                                                     const GroundTruthKey& key) {
  if (!halves_cached(dir, key)) return std::nullopt;
  GroundTruthHalves halves;
  for (int half : {0, 1}) {
    const std::string path = ground_truth_half_path(dir, key, half);
    Image image = read_image(path);
    if (image.width() != key.width || image.height() != key.height)
      throw std::runtime_error(path + ": a " + std::to_string(image.width()) + "x" +
                               std::to_string(image.height()) + " image where the truth is " +
                               std::to_string(key.width) + "x" + std::to_string(key.height));
    (half == 0 ? halves.a : halves.b) = std::move(image);
  }
  return halves;
}

}  // namespace tuneray
