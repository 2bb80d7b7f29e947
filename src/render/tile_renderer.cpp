#include "render/tile_renderer.h"

#include <tbb/blocked_range.h>
#include <tbb/combinable.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <memory>

namespace tuneray {

namespace {

uint64_t now_ns() {
  return static_cast<uint64_t>(std::chrono::duration_cast<std::chrono::nanoseconds>(
                                   std::chrono::steady_clock::now().time_since_epoch())
                                   .count());
}

PassStats combine(tbb::combinable<PathCounters>& counters, double render_ms, uint64_t samples) {
  PassStats stats;
  stats.render_ms = render_ms;
  stats.samples = samples;
  uint64_t intersect = 0, shadow = 0, total = 0;
  counters.combine_each([&](const PathCounters& c) {
    stats.rays += c.rays;
    stats.shadow_rays += c.shadow_rays;
    stats.invalid_samples += c.invalid_samples;
    intersect += c.intersect_ns;
    shadow += c.shadow_ns;
    total += c.total_ns;
  });
  stats.intersect_ms = intersect * 1e-6;
  stats.shadow_ms = shadow * 1e-6;
  stats.shading_ms = total > intersect + shadow ? (total - intersect - shadow) * 1e-6 : 0.0;
  return stats;
}

}  // namespace

// What a wavefront worker keeps between chunks and passes: its path slots' samplers, states and
// queues. Kept by the renderer, so a pass (a frame, when the tuner measures) allocates and
// page-faults nothing once the buffers have grown to a wave.
struct TileRenderer::WaveBuffers {
  std::unique_ptr<SamplerBank> samplers;
  std::vector<PixelSampleId> ids;
  std::vector<float> camera_u;  // 4 per path
  std::vector<PathState> states;
  std::vector<uint32_t> queue, next_queue, sampled;
  std::vector<float> shade_u;  // a ShadeSamples per entry of `sampled`
  std::vector<Ray> rays, shadow_rays;
  std::vector<Hit> hits;
  std::vector<uint32_t> shadow_owner;
  std::vector<Color> shadow_contribution;
  std::vector<uint8_t> occluded;
};

struct TileRenderer::WavePool {
  tbb::enumerable_thread_specific<WaveBuffers> buffers;
};

void PassStats::accumulate(const PassStats& o) {
  render_ms += o.render_ms;
  rays += o.rays;
  shadow_rays += o.shadow_rays;
  invalid_samples += o.invalid_samples;
  samples += o.samples;
  intersect_ms += o.intersect_ms;
  shading_ms += o.shading_ms;
  shadow_ms += o.shadow_ms;
}

TileRenderer::TileRenderer(const Scene& scene, const Accel& accel, const CameraDesc& camera,
                           const RenderSettings& settings, const Sampler& prototype)
    : scene_(scene),
      settings_(settings),
      camera_(camera, settings.width, settings.height),
      integrator_(scene, accel, settings),
      prototype_(prototype),
      wave_pool_(std::make_unique<WavePool>()) {}

TileRenderer::~TileRenderer() = default;

int TileRenderer::tile_count() const {
  int ts = std::max(1, settings_.tile_size);
  return ((settings_.width + ts - 1) / ts) * ((settings_.height + ts - 1) / ts);
}

PassStats TileRenderer::render_pass(Film& film, uint32_t first_sample, uint32_t spp,
                                    const std::function<void()>& on_tile_done) const {
  PixelWork work{[first_sample](size_t) { return first_sample; }, [spp](size_t) { return spp; }};
  return run(film, work, on_tile_done);
}

PassStats TileRenderer::render_extra(Film& film, const std::vector<uint32_t>& extra) const {
  const int w = settings_.width;
  PixelWork work{[&film, w](size_t i) {
                   return film.samples(static_cast<int>(i % w), static_cast<int>(i / w));
                 },
                 [&extra](size_t i) { return extra[i]; }};
  // The first sample index is read before the pixel is written: each pixel has one writer.
  return run(film, work, {});
}

ClampThresholds TileRenderer::clamp_for(const Film& film) const {
  const QualityOptions& q = settings_.quality;
  if (q.clamp > 0) return ClampThresholds::uniform(q.clamp);
  if (q.clamp_relative > 0) return ClampThresholds::relative(film, q.clamp_relative);
  return {};
}

PassStats TileRenderer::run(Film& film, const PixelWork& work,
                            const std::function<void()>& on_tile_done) const {
  // Resolved once per pass, before any pixel of it is written, so the result does not depend
  // on the order in which threads finish.
  const ClampThresholds clamp = clamp_for(film);
  if (settings_.quality.wavefront) {
    PassStats stats = run_wavefront(film, work, clamp);
    if (on_tile_done)
      for (int i = 0; i < tile_count(); ++i) on_tile_done();
    return stats;
  }
  return run_tiles(film, work, clamp, on_tile_done);
}

PassStats TileRenderer::run_tiles(Film& film, const PixelWork& work, const ClampThresholds& clamp,
                                  const std::function<void()>& on_tile_done) const {
  const int ts = std::max(1, settings_.tile_size);
  const int tiles_x = (settings_.width + ts - 1) / ts;
  const bool profile = settings_.quality.profile_phases;
  tbb::combinable<PathCounters> counters;
  tbb::combinable<uint64_t> samples;
  auto start = std::chrono::steady_clock::now();

  tbb::parallel_for(
      tbb::blocked_range<int>(0, tile_count(), 1), [&](const tbb::blocked_range<int>& r) {
        // Eight pixel samples at a time, in the tile's pixel and sample order: their paths run
        // side by side through the integrator's eight lanes, one ray at a time.
        std::unique_ptr<Sampler> samplers[8];
        for (auto& sampler : samplers) sampler = prototype_.clone();
        Sampler* lanes[8];
        for (int i = 0; i < 8; ++i) lanes[i] = samplers[i].get();
        PathCounters& local = counters.local();
        uint64_t& local_samples = samples.local();
        for (int tile = r.begin(); tile != r.end(); ++tile) {
          uint64_t t0 = profile ? now_ns() : 0;
          int x0 = (tile % tiles_x) * ts, y0 = (tile / tiles_x) * ts;
          int x1 = std::min(x0 + ts, settings_.width), y1 = std::min(y0 + ts, settings_.height);
          struct LaneSample {
            int x, y;
            uint32_t index;
          };
          LaneSample group[8];
          Ray rays[8];
          float clamps[8];
          Color values[8];
          int filled = 0;
          PixelSamples pixel;
          int pixel_x = -1, pixel_y = -1;
          auto flush_pixel = [&] {
            if (pixel.count > 0) film.add(pixel_x, pixel_y, pixel);
            pixel = PixelSamples{};
          };
          // Traces the group and adds its values to their pixels, in order.
          auto run_group = [&] {
            integrator_.radiance8(rays, lanes, clamps, filled, local, values);
            for (int i = 0; i < filled; ++i) {
              if (group[i].x != pixel_x || group[i].y != pixel_y) {
                flush_pixel();
                pixel_x = group[i].x;
                pixel_y = group[i].y;
              }
              pixel.add(values[i], group[i].index);
            }
            local_samples += static_cast<uint64_t>(filled);
            filled = 0;
          };
          for (int y = y0; y < y1; ++y)
            for (int x = x0; x < x1; ++x) {
              size_t pixel_index = static_cast<size_t>(y) * settings_.width + x;
              uint32_t first = work.first(pixel_index), n = work.count(pixel_index);
              for (uint32_t s = 0; s < n; ++s) {
                Sampler& sampler = *lanes[filled];
                sampler.start_pixel_sample(static_cast<uint32_t>(x), static_cast<uint32_t>(y),
                                           first + s);
                std::array<float, 4> u = sampler.next4();
                rays[filled] = camera_.generate_ray({x + u[0], y + u[1]}, {u[2], u[3]});
                clamps[filled] = clamp.at(pixel_index);
                group[filled] = {x, y, first + s};
                if (++filled == 8) run_group();
              }
            }
          if (filled > 0) run_group();
          flush_pixel();
          if (profile) local.total_ns += now_ns() - t0;
          if (on_tile_done) on_tile_done();
        }
      });

  double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return combine(counters, ms, samples.combine(std::plus<uint64_t>()));
}

PassStats TileRenderer::run_wavefront(Film& film, const PixelWork& work,
                                      const ClampThresholds& clamp) const {
  const int width = settings_.width;
  const size_t pixel_count = static_cast<size_t>(width) * settings_.height;
  const size_t batch = static_cast<size_t>(std::max(1, settings_.quality.batch_size));
  const bool profile = settings_.quality.profile_phases;
  const Accel& accel = integrator_.accel();

  // Chunks of whole pixels (so each pixel has one writer and sums its samples in order) with
  // at most `batch` paths, unless one pixel alone has more.
  std::vector<size_t> chunk_begin{0};
  std::vector<uint32_t> first(pixel_count), count(pixel_count);
  uint64_t total_samples = 0;
  for (size_t i = 0, in_chunk = 0; i < pixel_count; ++i) {
    first[i] = work.first(i);
    count[i] = work.count(i);
    total_samples += count[i];
    if (in_chunk > 0 && in_chunk + count[i] > batch) {
      chunk_begin.push_back(i);
      in_chunk = 0;
    }
    in_chunk += count[i];
  }
  chunk_begin.push_back(pixel_count);

  tbb::combinable<PathCounters> counters;
  auto start = std::chrono::steady_clock::now();

  tbb::parallel_for(
      tbb::blocked_range<size_t>(0, chunk_begin.size() - 1, 1),
      [&](const tbb::blocked_range<size_t>& r) {
        PathCounters& local = counters.local();
        WaveBuffers& b = wave_pool_->buffers.local();
        if (!b.samplers) b.samplers = prototype_.make_bank();
        for (size_t chunk = r.begin(); chunk != r.end(); ++chunk) {
          uint64_t t_chunk = profile ? now_ns() : 0;
          size_t p0 = chunk_begin[chunk], p1 = chunk_begin[chunk + 1];

          // Generate.
          b.ids.clear();
          for (size_t p = p0; p < p1; ++p) {
            uint32_t x = static_cast<uint32_t>(p % width), y = static_cast<uint32_t>(p / width);
            for (uint32_t s = 0; s < count[p]; ++s) b.ids.push_back({x, y, first[p] + s});
          }
          const size_t paths = b.ids.size();
          b.camera_u.resize(4 * paths);
          b.samplers->start(0, b.ids, b.camera_u.data());
          b.states.resize(paths);
          b.queue.resize(paths);
          for (size_t k = 0; k < paths; ++k) {
            const float* u = &b.camera_u[4 * k];
            b.states[k] = PathIntegrator::start(camera_.generate_ray(
                {static_cast<float>(b.ids[k].x) + u[0], static_cast<float>(b.ids[k].y) + u[1]},
                {u[2], u[3]}));
            b.queue[k] = static_cast<uint32_t>(k);
          }

          // The first wave is the camera rays in pixel order; after a bounce they scatter.
          RayCoherence coherence = RayCoherence::kCoherent;
          while (!b.queue.empty()) {
            // Extend: one batch of closest-hit rays.
            size_t n = b.queue.size();
            b.rays.resize(n);
            b.hits.resize(n);
            for (size_t i = 0; i < n; ++i) b.rays[i] = b.states[b.queue[i]].ray;
            uint64_t t0 = profile ? now_ns() : 0;
            accel.intersect_batch(b.rays, b.hits, coherence);
            coherence = RayCoherence::kIncoherent;
            if (profile) local.intersect_ns += now_ns() - t0;
            local.rays += n;

            // The wave's random numbers, drawn together for the paths that will use them.
            b.sampled.clear();
            for (size_t i = 0; i < n; ++i)
              if (integrator_.needs_samples(b.states[b.queue[i]], b.hits[i].valid()))
                b.sampled.push_back(b.queue[i]);
            constexpr size_t kPerPath = sizeof(ShadeSamples) / sizeof(float);
            b.shade_u.resize(kPerPath * b.sampled.size());
            b.samplers->next4(b.sampled, kPerPath / 4, b.shade_u.data());

            // Shade: emission, light sample, next direction; shadow rays are collected.
            b.shadow_rays.clear();
            b.shadow_owner.clear();
            b.shadow_contribution.clear();
            b.next_queue.clear();
            // Hit data arrives while earlier hits are shaded: indices kFar hits ahead,
            // vertices kNear ahead (their indices prefetched kFar - kNear hits ago).
            constexpr size_t kFar = 16, kNear = 8;
            for (size_t i = 0; i < std::min(n, kFar); ++i) integrator_.prefetch_hit(b.hits[i], 0);
            for (size_t i = 0; i < std::min(n, kNear); ++i) integrator_.prefetch_hit(b.hits[i], 1);
            ShadeBatch batch;
            for (size_t i0 = 0, next_u = 0; i0 < n; i0 += 8) {
              batch.count = static_cast<int>(std::min<size_t>(8, n - i0));
              for (int k = 0; k < batch.count; ++k) {
                const size_t i = i0 + k;
                if (i + kFar < n) integrator_.prefetch_hit(b.hits[i + kFar], 0);
                if (i + kNear < n) integrator_.prefetch_hit(b.hits[i + kNear], 1);
                PathState& st = b.states[b.queue[i]];
                batch.state[k] = &st;
                batch.hit[k] = b.hits[i];
                if (integrator_.needs_samples(st, b.hits[i].valid()))
                  std::memcpy(&batch.u[k], &b.shade_u[kPerPath * next_u++], sizeof batch.u[k]);
              }
              integrator_.shade8(batch);
              for (int k = 0; k < batch.count; ++k) {
                const uint32_t q = b.queue[i0 + k];
                const ShadowRequest& shadow = batch.shadow[k];
                if (shadow.active) {
                  b.shadow_rays.push_back(shadow.ray);
                  b.shadow_owner.push_back(q);
                  b.shadow_contribution.push_back(shadow.contribution);
                }
                if (b.states[q].alive) b.next_queue.push_back(q);  // compaction
              }
            }

            // Connect: shadow rays as one batch.
            if (!b.shadow_rays.empty()) {
              b.occluded.resize(b.shadow_rays.size());
              t0 = profile ? now_ns() : 0;
              accel.occluded_batch(b.shadow_rays, b.occluded);
              if (profile) local.shadow_ns += now_ns() - t0;
              local.shadow_rays += b.shadow_rays.size();
              for (size_t i = 0; i < b.shadow_rays.size(); ++i)
                if (!b.occluded[i]) b.states[b.shadow_owner[i]].L += b.shadow_contribution[i];
            }
            std::swap(b.queue, b.next_queue);
          }

          // Accumulate each pixel's samples in index order, as the tile scheduler does.
          size_t k = 0;
          for (size_t p = p0; p < p1; ++p) {
            if (count[p] == 0) continue;
            PixelSamples samples;
            for (uint32_t s = 0; s < count[p]; ++s, ++k)
              samples.add(integrator_.finish(b.states[k], local, clamp.at(p)), first[p] + s);
            film.add(static_cast<int>(p % width), static_cast<int>(p / width), samples);
          }
          if (profile) local.total_ns += now_ns() - t_chunk;
        }
      });

  double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return combine(counters, ms, total_samples);
}

}  // namespace tuneray
