// Progressive rendering with two schedulers around the one PathIntegrator. Both advance a wave of
// paths (PathWave) bounce by bounce (generate -> extend -> shade -> connect), shade eight paths
// at a time and pack the live paths to the front after every bounce:
// - tiles: square tiles that TBB spreads over all cores, a tile's samples one wave, its rays
//   traced one at a time through the accelerator's single-ray calls;
// - wavefront (quality.wavefront): runs of whole pixels as waves, taken in 8×8 blocks
//   (wave_pixel_order.h), rays traced in batches through the accelerator's batch entry points,
//   shadow rays collected and traced together.
// Both consume each pixel's samples in the same order, so they give the same image.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "accel/accel.h"
#include "render/camera.h"
#include "render/film.h"
#include "render/firefly_clamp.h"
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
  uint64_t samples = 0;  // pixel samples taken
  // Phase times summed over threads (ms), when quality.profile_phases is on.
  double intersect_ms = 0, shading_ms = 0, shadow_ms = 0;
  // Of the samples traced with path reuse: how many, and what they tell of its worth.
  uint64_t reused_samples = 0;
  ReuseMoments reuse;
  double mrays_per_s() const {
    return render_ms > 0 ? static_cast<double>(rays + shadow_rays) / (render_ms * 1e3) : 0.0;
  }
  void accumulate(const PassStats& other);
};

class TileRenderer {
 public:
  TileRenderer(const Scene& scene, const Accel& accel, const CameraDesc& camera,
               const RenderSettings& settings, const Sampler& prototype);
  ~TileRenderer();

  // Adds `spp` samples per pixel, sample indices [first_sample, first_sample + spp). The
  // result depends only on the seed and the sample indices, not on the thread count.
  // `on_tile_done` (optional) is called after each tile, from worker threads.
  PassStats render_pass(Film& film, uint32_t first_sample, uint32_t spp,
                        const std::function<void()>& on_tile_done = {}) const;

  // Adds extra[y * width + x] samples to each pixel, continuing its sample indices from
  // film.samples(x, y) (adaptive sampling).
  PassStats render_extra(Film& film, const std::vector<uint32_t>& extra) const;

  // Moves the camera; lights and the integrator are kept (cheap, for camera paths).
  void set_camera(const CameraDesc& camera) {
    camera_ = Camera(camera, settings_.width, settings_.height);
  }
  // Switches scheduler and work sizes between passes without rebuilding the integrator and its
  // lights: it keeps its own copy of the settings and reads none of these fields, and neither
  // changes the image, only the speed (the tuner measures them frame by frame). Path reuse is
  // the exception: its pools follow the scheduler's order, so there the noise differs.
  void set_work_sizes(bool wavefront, int tile_size, int batch_size) {
    settings_.quality.wavefront = wavefront;
    settings_.tile_size = tile_size;
    settings_.quality.batch_size = batch_size;
  }
  // Path reuse on or off for the passes to come (when the settings allow it at all: see
  // PathIntegrator::reuse_pool_pixels). On from the start unless quality.path_reuse_auto, which
  // leaves it to frame-budget rendering to switch (render/frame_budget.h).
  void set_path_reuse(bool on) { reuse_on_ = on; }
  // Where passes with reuse also add their moments pixel by pixel (null: nowhere; the caller
  // keeps it alive while it is set, and sized to the image).
  void set_reuse_pixels(ReusePixelMoments* pixels) { reuse_pixels_ = pixels; }
  // Pixels per path-reuse pool of the next pass; 0 = it traces without reuse.
  int reuse_pool() const { return reuse_on_ ? integrator_.reuse_pool_pixels() : 0; }

  // The firefly clamp of the next pass into `film`: quality.clamp everywhere if set, else
  // quality.clamp_relative thresholds from the film (none on an empty film), else none.
  ClampThresholds clamp_for(const Film& film) const;

  int tile_count() const;
  const PathIntegrator& integrator() const { return integrator_; }
  const Scene& scene() const { return scene_; }
  const Camera& camera() const { return camera_; }
  const RenderSettings& settings() const { return settings_; }

 private:
  // Which samples each pixel takes: indices [first, first + count). A uniform pass gives every
  // pixel the same (each frame the tuner measures); otherwise pixel (x, y), index
  // i = y * width + x, continues from the film's count with extra[i] more (adaptive sampling,
  // partial passes). Plain fields rather than callbacks: the schedulers read them per pixel.
  struct PixelWork {
    uint32_t uniform_first = 0, uniform_count = 0;
    const Film* film = nullptr;
    const std::vector<uint32_t>* extra = nullptr;  // null: uniform
    bool uniform() const { return extra == nullptr; }
    uint32_t first(uint32_t x, uint32_t y) const {
      return extra ? film->samples(static_cast<int>(x), static_cast<int>(y)) : uniform_first;
    }
    uint32_t count(size_t i) const { return extra ? (*extra)[i] : uniform_count; }
    // Passes with path reuse: the length at which ReuseMoments clip a sample's deviation.
    float reuse_clip = 0;
  };
  PassStats run(Film& film, const PixelWork& work, const std::function<void()>& on_tile_done) const;
  PassStats run_tiles(Film& film, const PixelWork& work, const ClampThresholds& clamp,
                      const std::function<void()>& on_tile_done) const;
  PassStats run_wavefront(Film& film, const PixelWork& work, const ClampThresholds& clamp) const;
  struct WaveBuffers;
  // The steps both schedulers share: the paths of b.ids start on their camera rays, are traced
  // to their ends (through the accelerator's batch calls or one ray at a time) and are added
  // to the film, each pixel's samples in index order.
  void start_paths(WaveBuffers& b, const ClampThresholds& clamp) const;
  void trace_paths(WaveBuffers& b, bool batched, PathCounters& counters) const;
  void add_to_film(const WaveBuffers& b, Film& film, float reuse_clip,
                   PathCounters& counters) const;
  // Path reuse: the wave's pools gathered (path_reuse.h), then every path's value taken.
  void reuse_and_finish(WaveBuffers& b, PathCounters& counters) const;
  // A chunk's or tile's thread time, to the phase profile and to path reuse's costs.
  void add_work_time(PathCounters& local, uint64_t ns) const;

  const Scene& scene_;
  RenderSettings settings_;
  Camera camera_;
  PathIntegrator integrator_;
  const Sampler& prototype_;
  bool reuse_on_;
  ReusePixelMoments* reuse_pixels_ = nullptr;
  struct WavePool;
  std::unique_ptr<WavePool> wave_pool_;  // per-thread wavefront buffers, kept between passes
  // QualityOptions::cache: read by the paths of a pass, trained between passes with the
  // records its training paths left in the wave buffers.
  std::unique_ptr<RadianceCache> cache_;
  void train_cache() const;
  struct WavePixel {
    uint32_t x, y;
  };
  // The pixels in the order waves take them (wave_pixel_order.h), as coordinates: the chunks
  // read them in that order, without a division per pixel.
  std::vector<WavePixel> wave_pixels_;
};

}  // namespace tuneray
