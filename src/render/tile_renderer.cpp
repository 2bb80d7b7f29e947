#include "render/tile_renderer.h"

#include <tbb/blocked_range.h>
#include <tbb/combinable.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <memory>

#include "render/wave_pixel_order.h"

namespace tuneray {

namespace {

// The film coordinates of eight consecutive pixel samples, as floats. Their 24 words are loaded
// as three vectors and deinterleaved: eight scalar stores into a stack array and a vector load
// of it stalled on store forwarding (a quarter of start_paths' time in perf).
void pixel_coords8(const PixelSampleId* ids, simd::F8& x, simd::F8& y) {
  static_assert(sizeof(PixelSampleId) == 3 * sizeof(uint32_t), "x, y, index with no padding");
  const auto* words = reinterpret_cast<const __m256i*>(ids);
  // a = x0 y0 i0 x1 y1 i1 x2 y2, b = i2 x3 y3 i3 x4 y4 i4 x5, c = y5 i5 x6 y6 i6 x7 y7 i7
  const __m256i a = _mm256_loadu_si256(words), b = _mm256_loadu_si256(words + 1),
                c = _mm256_loadu_si256(words + 2);
  const __m256i xs = _mm256_blend_epi32(_mm256_blend_epi32(a, b, 0x92), c, 0x24);  // x0 x3 x6 x1 ..
  const __m256i ys = _mm256_blend_epi32(_mm256_blend_epi32(a, b, 0x24), c, 0x49);  // y5 y0 y3 y6 ..
  x = simd::F8(_mm256_cvtepi32_ps(
      _mm256_permutevar8x32_epi32(xs, _mm256_setr_epi32(0, 3, 6, 1, 4, 7, 2, 5))));
  y = simd::F8(_mm256_cvtepi32_ps(
      _mm256_permutevar8x32_epi32(ys, _mm256_setr_epi32(1, 4, 7, 2, 5, 0, 3, 6))));
}

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
    stats.reused_samples += c.reused_samples;
    stats.reuse.add(c.reuse);
  });
  stats.intersect_ms = intersect * 1e-6;
  stats.shadow_ms = shadow * 1e-6;
  stats.shading_ms = total > intersect + shadow ? (total - intersect - shadow) * 1e-6 : 0.0;
  return stats;
}

}  // namespace

// What a worker keeps between chunks and passes: its path slots' samplers, the wave of paths,
// its rays and results. Kept by the renderer, so a pass (a frame, when the tuner measures)
// allocates and page-faults nothing once the buffers have grown to a chunk.
struct TileRenderer::WaveBuffers {
  std::unique_ptr<SamplerBank> samplers;
  std::vector<PixelSampleId> ids;              // per slot
  std::vector<float> clamp;                    // per slot: its pixel's firefly clamp
  std::array<std::vector<float>, 4> camera_u;  // the camera's numbers, as planes over slots
  PathWave wave;
  std::array<std::vector<float>, kShadeSamples> u;  // planes over wave positions
  std::vector<uint32_t> sampled, sampled_at;        // slots drawing numbers, their positions
  std::vector<Ray> shadow_rays;
  std::vector<Hit> hits;
  std::vector<uint32_t> shadow_owner;  // wave position
  std::vector<Color> shadow_contribution;
  std::vector<uint8_t> occluded, alive;
  std::vector<Color> result;                         // per slot
  std::vector<RadianceCache::Record> cache_records;  // of this thread's training paths
  // Path reuse (path_reuse.h): per slot, the recorded vertices and the path's two parts until
  // the pools have been gathered; the pools.
  std::vector<ReuseVertices> reuse;
  std::vector<Color> indirect, camera;
  std::vector<Color> own;  // per slot: the path's own value, for ReuseMoments
  std::vector<uint32_t> pool_slots, pool_begin;
  PathReuseScratch reuse_scratch;
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
  reused_samples += o.reused_samples;
  reuse.add(o.reuse);
}

TileRenderer::TileRenderer(const Scene& scene, const Accel& accel, const CameraDesc& camera,
                           const RenderSettings& settings, const Sampler& prototype)
    : scene_(scene),
      settings_(settings),
      camera_(camera, settings.width, settings.height),
      integrator_(scene, accel, settings),
      prototype_(prototype),
      reuse_on_(!settings.quality.path_reuse_auto),
      wave_pool_(std::make_unique<WavePool>()) {
  const std::vector<uint32_t> order = wave_pixel_order(settings.width, settings.height);
  const uint32_t width = static_cast<uint32_t>(std::max(1, settings.width));
  wave_pixels_.reserve(order.size());
  for (uint32_t p : order) wave_pixels_.push_back({p % width, p / width});
  const RadianceCacheOptions& c = settings.quality.cache;
  if (c.vertex > 0 && c.vertex < settings.max_bounces) {
    cache_ = std::make_unique<RadianceCache>(scene.bounds(), c.cell, c.levels);
    integrator_.use_radiance_cache(cache_.get());
  }
}

void TileRenderer::train_cache() const {
  if (!cache_) return;
  std::vector<RadianceCache::Record> all;
  for (WaveBuffers& b : wave_pool_->buffers) {
    all.insert(all.end(), b.cache_records.begin(), b.cache_records.end());
    b.cache_records.clear();
  }
  cache_->add(all);
}

TileRenderer::~TileRenderer() = default;

int TileRenderer::tile_count() const {
  int ts = std::max(1, settings_.tile_size);
  return ((settings_.width + ts - 1) / ts) * ((settings_.height + ts - 1) / ts);
}

PassStats TileRenderer::render_pass(Film& film, uint32_t first_sample, uint32_t spp,
                                    const std::function<void()>& on_tile_done) const {
  PixelWork work;
  work.uniform_first = first_sample;
  work.uniform_count = spp;
  return run(film, work, on_tile_done);
}

PassStats TileRenderer::render_extra(Film& film, const std::vector<uint32_t>& extra) const {
  PixelWork work;
  work.film = &film;
  work.extra = &extra;
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
  PixelWork pass = work;
  if (reuse_pool() > 0) pass.reuse_clip = ReuseMoments::clip_length(film.mean_value_length());
  PassStats stats;
  if (settings_.quality.wavefront) {
    stats = run_wavefront(film, pass, clamp);
    if (on_tile_done)
      for (int i = 0; i < tile_count(); ++i) on_tile_done();
  } else {
    stats = run_tiles(film, pass, clamp, on_tile_done);
  }
  train_cache();
  return stats;
}

void TileRenderer::start_paths(WaveBuffers& b, const ClampThresholds& clamp) const {
  const size_t paths = b.ids.size();
  const size_t padded = (paths + 7) / 8 * 8;
  if (!b.samplers) b.samplers = prototype_.make_bank();
  b.wave.with_cache = cache_ != nullptr;
  if (reuse_pool() > 0) {
    b.reuse.assign(paths, ReuseVertices{});
    b.indirect.resize(paths);
    b.camera.resize(paths);
    b.wave.reuse = b.reuse.data();
  } else {
    b.wave.reuse = nullptr;
  }
  float* camera_u[4];
  for (int j = 0; j < 4; ++j) {
    b.camera_u[j].resize(padded);
    camera_u[j] = b.camera_u[j].data();
  }
  b.samplers->start(0, b.ids, camera_u);
  b.wave.reserve(paths);
  b.wave.size = paths;
  b.clamp.resize(paths);
  b.result.resize(paths);
  const int width = settings_.width;
  for (size_t k0 = 0; k0 < paths; k0 += 8) {
    simd::F8 x, y;
    if (k0 + 8 <= paths) {
      pixel_coords8(&b.ids[k0], x, y);
    } else {
      alignas(32) float xs[8] = {}, ys[8] = {};
      for (size_t k = k0; k < paths; ++k) {
        xs[k - k0] = static_cast<float>(b.ids[k].x);
        ys[k - k0] = static_cast<float>(b.ids[k].y);
      }
      x = simd::F8::load(xs);
      y = simd::F8::load(ys);
    }
    simd::V8 org, dir;
    camera_.generate_rays8(x + simd::F8::load(camera_u[0] + k0),
                           y + simd::F8::load(camera_u[1] + k0), simd::F8::load(camera_u[2] + k0),
                           simd::F8::load(camera_u[3] + k0), org, dir);
    b.wave.start8(k0, org, dir);
  }
  for (size_t k = 0; k < paths; ++k)
    b.clamp[k] = clamp.at(static_cast<size_t>(b.ids[k].y) * width + b.ids[k].x);
}

void TileRenderer::trace_paths(WaveBuffers& b, bool batched, PathCounters& local) const {
  const bool profile = settings_.quality.profile_phases;
  const Accel& accel = integrator_.accel();
  PathWave& wave = b.wave;
  // The first wave is the camera rays in pixel order; after a bounce they scatter.
  RayCoherence coherence = RayCoherence::kCoherent;
  while (wave.size > 0) {
    // Extend: the closest hits, as one batch or one ray at a time.
    const size_t n = wave.size;
    b.hits.resize(n);
    uint64_t t0 = profile ? now_ns() : 0;
    if (batched) {
      accel.intersect_planes(wave.ray_planes(), b.hits, coherence);
    } else {
      for (size_t i = 0; i < n; ++i) {
        b.hits[i] = Hit{};
        accel.intersect(wave.ray(i), b.hits[i]);
      }
    }
    coherence = RayCoherence::kIncoherent;
    if (profile) local.intersect_ns += now_ns() - t0;
    local.rays += n;

    // The wave's random numbers, drawn together for the paths that will use them.
    // Written unconditionally and kept by the count: which paths draw is as random as the
    // paths themselves, so a branch here is mispredicted often.
    b.sampled.resize(n);
    b.sampled_at.resize(n);
    size_t drawing = 0;
    for (size_t i = 0; i < n; ++i) {
      b.sampled[drawing] = wave.slot[i];
      b.sampled_at[drawing] = static_cast<uint32_t>(i);
      drawing += integrator_.needs_samples(wave, i, b.hits[i].valid()) ? 1 : 0;
    }

    float* u[kShadeSamples];
    for (int k = 0; k < kShadeSamples; ++k) {
      b.u[k].resize(wave.depth.size());
      u[k] = b.u[k].data();
    }
    b.samplers->next4(std::span(b.sampled).first(drawing), std::span(b.sampled_at).first(drawing),
                      kShadeSamples / 4, u);

    // Shade, eight paths at a time; shadow rays are collected.
    // At most one shadow ray per path: room for all, the count kept apart.
    b.shadow_rays.resize(n);
    b.shadow_owner.resize(n);
    b.shadow_contribution.resize(n);
    size_t shadows = 0;
    b.alive.resize((n + 7) / 8);
    // Hit data arrives while earlier hits are shaded: indices kFar hits ahead, vertices kNear
    // ahead (their indices prefetched kFar - kNear hits ago).
    constexpr size_t kFar = 16, kNear = 8;
    for (size_t i = 0; i < std::min(n, kFar); ++i) integrator_.prefetch_hit(b.hits[i], 0);
    for (size_t i = 0; i < std::min(n, kNear); ++i) integrator_.prefetch_hit(b.hits[i], 1);
    ShadowRequest shadow[8];  // shade8 sets every lane's `active`, the rest where it is set
    for (size_t i0 = 0; i0 < n; i0 += 8) {
      const int count = static_cast<int>(std::min<size_t>(8, n - i0));
      for (size_t i = i0 + kFar; i < std::min(n, i0 + kFar + 8); ++i)
        integrator_.prefetch_hit(b.hits[i], 0);
      for (size_t i = i0 + kNear; i < std::min(n, i0 + kNear + 8); ++i)
        integrator_.prefetch_hit(b.hits[i], 1);
      b.alive[i0 / 8] =
          static_cast<uint8_t>(integrator_.shade8(wave, i0, count, &b.hits[i0], u, shadow));
      for (int k = 0; k < count; ++k) {  // kept by the count, as the samples above
        b.shadow_rays[shadows] = shadow[k].ray;
        b.shadow_owner[shadows] = static_cast<uint32_t>(i0) + static_cast<uint32_t>(k);
        b.shadow_contribution[shadows] = shadow[k].contribution;
        shadows += shadow[k].active ? 1 : 0;
      }
    }

    // Connect: the shadow rays, as one batch or one at a time.
    if (shadows > 0) {
      b.occluded.resize(shadows);
      t0 = profile ? now_ns() : 0;
      if (batched) {
        accel.occluded_batch(std::span(b.shadow_rays).first(shadows), b.occluded);
      } else {
        for (size_t i = 0; i < shadows; ++i)
          b.occluded[i] = accel.occluded(b.shadow_rays[i]) ? 1 : 0;
      }
      if (profile) local.shadow_ns += now_ns() - t0;
      local.shadow_rays += shadows;
      for (size_t i = 0; i < shadows; ++i)
        if (!b.occluded[i]) wave.add_radiance(b.shadow_owner[i], b.shadow_contribution[i]);
    }

    // The paths that ended give their values; the others move to the front.
    for (size_t i = 0; i < n; ++i) {
      if ((b.alive[i / 8] >> (i % 8)) & 1) continue;
      const uint32_t slot = wave.slot[i];
      if (wave.reuse) {
        b.indirect[slot] = wave.radiance(i);
        b.camera[slot] = wave.camera_radiance(i);
      } else {
        b.result[slot] = integrator_.finish(wave, i, local, b.clamp[slot]);
      }
      if (const uint64_t key = wave.with_cache ? wave.cache_key(i) : 0) {
        const PixelSampleId& id = b.ids[slot];
        b.cache_records.push_back({key, id.y, id.x, id.index, wave.cache_incident(i)});
      }
    }
    wave.compact(b.alive);
  }
  if (wave.reuse) reuse_and_finish(b, local);
}

void TileRenderer::reuse_and_finish(WaveBuffers& b, PathCounters& local) const {
  const uint64_t start = now_ns();  // all but the last loop is what a pass without reuse saves
  reuse_pools(b.ids, reuse_pool(), b.pool_slots, b.pool_begin);
  // Each path's own value, taken before the pools replace what its walk found (ReuseMoments).
  b.own.resize(b.ids.size());
  PathCounters own_counters;  // the own estimates are not added: their invalid ones do not count
  for (size_t slot = 0; slot < b.ids.size(); ++slot)
    b.own[slot] = integrator_.finish(b.indirect[slot], b.camera[slot], own_counters, b.clamp[slot]);
  const uint64_t t0 = settings_.quality.profile_phases ? now_ns() : 0;
  local.shadow_rays += reuse_paths(integrator_.accel(), b.pool_slots, b.pool_begin, b.reuse,
                                   b.indirect, b.reuse_scratch);
  if (settings_.quality.profile_phases) local.shadow_ns += now_ns() - t0;
  local.reuse.pool_ms += static_cast<double>(now_ns() - start) * 1e-6;
  for (size_t slot = 0; slot < b.ids.size(); ++slot)
    b.result[slot] = integrator_.finish(b.indirect[slot], b.camera[slot], local, b.clamp[slot]);
}

void TileRenderer::add_work_time(PathCounters& local, uint64_t ns) const {
  if (settings_.quality.profile_phases) local.total_ns += ns;
  if (reuse_pool() > 0) local.reuse.traced_ms += static_cast<double>(ns) * 1e-6;
}

void TileRenderer::add_to_film(const WaveBuffers& b, Film& film, float reuse_clip,
                               PathCounters& local) const {
  // Each pixel's samples are consecutive slots, in index order, as a lone path loop adds them;
  // each goes straight to the film (its record is in the cache after the first).
  // Film lines are asked for this many samples ahead (a few pixels at any spp).
  constexpr size_t kAhead = 32;
  const bool reused = b.wave.reuse != nullptr;
  for (size_t k = 0; k < b.ids.size(); ++k) {
    if (k + kAhead < b.ids.size()) film.prefetch(b.ids[k + kAhead].x, b.ids[k + kAhead].y);
    const PixelSampleId& id = b.ids[k];
    const int x = static_cast<int>(id.x), y = static_cast<int>(id.y);
    if (reused)
      local.reuse.add_sample(film, x, y, b.own[k], b.result[k], reuse_clip, reuse_pixels_);
    film.add_sample(x, y, b.result[k], id.index);
  }
  if (reused) local.reused_samples += b.ids.size();
}

PassStats TileRenderer::run_tiles(Film& film, const PixelWork& work, const ClampThresholds& clamp,
                                  const std::function<void()>& on_tile_done) const {
  const int ts = std::max(1, settings_.tile_size);
  const int tiles_x = (settings_.width + ts - 1) / ts;
  const bool timed = settings_.quality.profile_phases || reuse_pool() > 0;
  tbb::combinable<PathCounters> counters;
  tbb::combinable<uint64_t> samples;
  auto start = std::chrono::steady_clock::now();

  tbb::parallel_for(
      tbb::blocked_range<int>(0, tile_count(), 1), [&](const tbb::blocked_range<int>& r) {
        PathCounters& local = counters.local();
        uint64_t& local_samples = samples.local();
        WaveBuffers& b = wave_pool_->buffers.local();
        for (int tile = r.begin(); tile != r.end(); ++tile) {
          const uint64_t t0 = timed ? now_ns() : 0;
          int x0 = (tile % tiles_x) * ts, y0 = (tile / tiles_x) * ts;
          int x1 = std::min(x0 + ts, settings_.width), y1 = std::min(y0 + ts, settings_.height);
          // The tile's pixel samples, traced one ray at a time, shaded eight at a time.
          b.ids.clear();
          for (int y = y0; y < y1; ++y)
            for (int x = x0; x < x1; ++x) {
              size_t pixel = static_cast<size_t>(y) * settings_.width + x;
              const uint32_t n = work.count(pixel);
              if (n == 0) continue;  // as in run_wavefront: the film is not read for it
              const uint32_t first = work.first(static_cast<uint32_t>(x), static_cast<uint32_t>(y));
              for (uint32_t s = 0; s < n; ++s)
                b.ids.push_back({static_cast<uint32_t>(x), static_cast<uint32_t>(y), first + s});
            }
          if (!b.ids.empty()) {
            start_paths(b, clamp);
            trace_paths(b, false, local);
            add_to_film(b, film, work.reuse_clip, local);
            local_samples += b.ids.size();
          }
          if (timed) add_work_time(local, now_ns() - t0);
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
  const size_t pixel_count = wave_pixels_.size();
  const size_t batch = static_cast<size_t>(std::max(1, settings_.quality.batch_size));
  const bool timed = settings_.quality.profile_phases || reuse_pool() > 0;

  // Chunks of whole pixels (so each pixel has one writer and sums its samples in order) with
  // at most `batch` paths, unless one pixel alone has more; positions in wave_pixels_. A
  // uniform pass's chunks are equal runs of pixels; otherwise each position's samples are
  // tabled once, in wave order, so the chunks read them in sequence.
  std::vector<size_t> chunk_begin{0};
  std::vector<uint32_t> first, count;  // per position, for a pass that is not uniform
  uint64_t total_samples = 0;
  if (work.uniform()) {
    const size_t spp = work.uniform_count;
    const size_t per_chunk =
        spp == 0 ? std::max<size_t>(1, pixel_count) : std::max<size_t>(1, batch / spp);
    // Path reuse's pools are runs of pixels: chunks of whole pools keep them, so the image
    // does not depend on the batch size.
    const size_t pool = static_cast<size_t>(std::max(1, reuse_pool()));
    const size_t chunk_pixels = (per_chunk + pool - 1) / pool * pool;
    for (size_t k = chunk_pixels; k < pixel_count; k += chunk_pixels) chunk_begin.push_back(k);
    total_samples = static_cast<uint64_t>(spp) * pixel_count;
  } else {
    first.resize(pixel_count);
    count.resize(pixel_count);
    for (size_t k = 0, in_chunk = 0; k < pixel_count; ++k) {
      const WavePixel px = wave_pixels_[k];
      count[k] = work.count(static_cast<size_t>(px.y) * width + px.x);
      // A partial pass leaves most pixels out: their film records are not read.
      first[k] = count[k] > 0 ? work.first(px.x, px.y) : 0;
      total_samples += count[k];
      if (in_chunk > 0 && in_chunk + count[k] > batch) {
        chunk_begin.push_back(k);
        in_chunk = 0;
      }
      in_chunk += count[k];
    }
  }
  chunk_begin.push_back(pixel_count);

  tbb::combinable<PathCounters> counters;
  auto start = std::chrono::steady_clock::now();

  tbb::parallel_for(tbb::blocked_range<size_t>(0, chunk_begin.size() - 1, 1),
                    [&](const tbb::blocked_range<size_t>& r) {
                      PathCounters& local = counters.local();
                      WaveBuffers& b = wave_pool_->buffers.local();
                      for (size_t chunk = r.begin(); chunk != r.end(); ++chunk) {
                        const uint64_t t_chunk = timed ? now_ns() : 0;
                        b.ids.clear();
                        for (size_t k = chunk_begin[chunk]; k < chunk_begin[chunk + 1]; ++k) {
                          const WavePixel px = wave_pixels_[k];
                          const uint32_t f = work.uniform() ? work.uniform_first : first[k];
                          const uint32_t n = work.uniform() ? work.uniform_count : count[k];
                          for (uint32_t s = 0; s < n; ++s) b.ids.push_back({px.x, px.y, f + s});
                        }
                        if (!b.ids.empty()) {
                          start_paths(b, clamp);
                          trace_paths(b, true, local);
                          add_to_film(b, film, work.reuse_clip, local);
                        }
                        if (timed) add_work_time(local, now_ns() - t_chunk);
                      }
                    });

  double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return combine(counters, ms, total_samples);
}

}  // namespace tuneray
