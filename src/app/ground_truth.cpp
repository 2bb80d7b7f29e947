#include "app/ground_truth.h"

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
  char name[40];
  std::snprintf(name, sizeof name, "truth-%016llx.exr",
                static_cast<unsigned long long>(fnv1a(s.str())));
  return (std::filesystem::path(dir) / name).string();
}

Image ground_truth(const std::string& dir, const GroundTruthKey& key, const Scene& scene,
                   const Accel& accel, bool* rendered) {
  std::string path = ground_truth_path(dir, key);
  if (std::filesystem::exists(path)) {
    Image cached = read_image(path);
    if (cached.width() == key.width && cached.height() == key.height) {
      if (rendered) *rendered = false;
      return cached;
    }
  }
  RenderSettings settings;  // defaults: tiles, nothing biased
  settings.width = key.width;
  settings.height = key.height;
  settings.max_bounces = key.max_bounces;
  PcgSampler sampler(0);
  TileRenderer renderer(scene, accel, key.camera, settings, sampler);
  Film film(key.width, key.height);
  for (int done = 0; done < key.spp;) {
    uint32_t n = static_cast<uint32_t>(std::min(16, key.spp - done));
    renderer.render_pass(film, static_cast<uint32_t>(done), n);
    done += static_cast<int>(n);
  }
  Image image = film.resolve();
  std::filesystem::create_directories(dir);
  write_image(path, image);
  if (rendered) *rendered = true;
  return image;
}

}  // namespace tuneray
