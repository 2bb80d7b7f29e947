// Tile-parallel progressive rendering: the image is cut into square tiles that TBB spreads
// over all cores; each call adds `spp` samples to every pixel of the film.
#pragma once

#include <cstdint>
#include <functional>

#include "accel/accel.h"
#include "render/camera.h"
#include "render/film.h"
#include "render/path_integrator.h"
#include "render/render_settings.h"
#include "render/sampler.h"
#include "scene/scene.h"

namespace tuneray {

struct PassStats {
  double render_ms = 0;
  uint64_t rays = 0;
  uint64_t shadow_rays = 0;
  uint64_t invalid_samples = 0;
  double mrays_per_s() const {
    return render_ms > 0 ? static_cast<double>(rays + shadow_rays) / (render_ms * 1e3) : 0.0;
  }
};

class TileRenderer {
 public:
  TileRenderer(const Scene& scene, const Accel& accel, const CameraDesc& camera,
               const RenderSettings& settings, const Sampler& prototype);

  // Adds `spp` samples per pixel, sample indices [first_sample, first_sample + spp). The
  // result depends only on the seed and the sample indices, not on the thread count.
  // `on_tile_done` (optional) is called after each tile, from worker threads.
  PassStats render_pass(Film& film, uint32_t first_sample, uint32_t spp,
                        const std::function<void()>& on_tile_done = {}) const;

  // Moves the camera; lights and the integrator are kept (cheap, for camera paths).
  void set_camera(const CameraDesc& camera) {
    camera_ = Camera(camera, settings_.width, settings_.height);
  }

  int tile_count() const;
  const PathIntegrator& integrator() const { return integrator_; }

 private:
  const Scene& scene_;
  RenderSettings settings_;
  Camera camera_;
  PathIntegrator integrator_;
  const Sampler& prototype_;
};

}  // namespace tuneray
