#include "render/tile_renderer.h"

#include <tbb/blocked_range.h>
#include <tbb/combinable.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>

namespace tuneray {

TileRenderer::TileRenderer(const Scene& scene, const Accel& accel, const CameraDesc& camera,
                           const RenderSettings& settings, const Sampler& prototype)
    : scene_(scene),
      settings_(settings),
      camera_(camera, settings.width, settings.height),
      integrator_(scene, accel, settings),
      prototype_(prototype) {}

int TileRenderer::tile_count() const {
  int ts = std::max(1, settings_.tile_size);
  return ((settings_.width + ts - 1) / ts) * ((settings_.height + ts - 1) / ts);
}

PassStats TileRenderer::render_pass(Film& film, uint32_t first_sample, uint32_t spp,
                                    const std::function<void()>& on_tile_done) const {
  const int ts = std::max(1, settings_.tile_size);
  const int tiles_x = (settings_.width + ts - 1) / ts;
  tbb::combinable<PathCounters> counters;
  auto start = std::chrono::steady_clock::now();

  tbb::parallel_for(
      tbb::blocked_range<int>(0, tile_count(), 1), [&](const tbb::blocked_range<int>& r) {
        std::unique_ptr<Sampler> sampler = prototype_.clone();
        PathCounters& local = counters.local();
        for (int tile = r.begin(); tile != r.end(); ++tile) {
          int x0 = (tile % tiles_x) * ts, y0 = (tile / tiles_x) * ts;
          int x1 = std::min(x0 + ts, settings_.width), y1 = std::min(y0 + ts, settings_.height);
          for (int y = y0; y < y1; ++y)
            for (int x = x0; x < x1; ++x) {
              Color sum(0.0f);
              for (uint32_t s = 0; s < spp; ++s) {
                sampler->start_pixel_sample(static_cast<uint32_t>(x), static_cast<uint32_t>(y),
                                            first_sample + s);
                std::array<float, 4> u = sampler->next4();
                Ray ray = camera_.generate_ray({x + u[0], y + u[1]}, {u[2], u[3]});
                sum += integrator_.radiance(ray, *sampler, local);
              }
              film.add(x, y, sum, spp);
            }
          if (on_tile_done) on_tile_done();
        }
      });

  PassStats stats;
  stats.render_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  counters.combine_each([&](const PathCounters& c) {
    stats.rays += c.rays;
    stats.shadow_rays += c.shadow_rays;
    stats.invalid_samples += c.invalid_samples;
  });
  return stats;
}

}  // namespace tuneray
