#include "bench/quality_bench.h"

#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <stdexcept>

#include "accel/factory.h"
#include "bench/quality_configs.h"
#include "bench/shown_frames.h"
#include "image/metrics.h"
#include "render/blue_noise_sampler.h"
#include "render/denoiser_frame.h"
#include "render/film.h"
#include "render/tile_renderer.h"
#include "scene/load.h"
#include "scene/one_texel.h"
#include "tuning/stats.h"

namespace tuneray {

namespace {

double rmse(const Image& a, const Image& b) {
  return compare_images(a, b).rmse;
}

// `spp` samples per pixel with the sampler the settings name: one sample first, then the rest,
// so a relative clamp has an image to be relative to (as in a frame-budget render).
Image render_fixed(const Scene& scene, const Accel& accel, const CameraDesc& camera,
                   const RenderSettings& settings, uint64_t seed, int spp) {
  std::unique_ptr<Sampler> sampler = make_sampler(settings.quality.sampler, seed);
  TileRenderer renderer(scene, accel, camera, settings, *sampler);
  Film film(settings.width, settings.height);
  renderer.render_pass(film, 0, 1);
  if (spp > 1) renderer.render_pass(film, 1, static_cast<uint32_t>(spp - 1));
  return FrameResolver().resolve(renderer, film);
}

// Median ms per spp of three 2-spp passes, after a 1-spp warm-up pass.
double measure_ms_per_spp(const Scene& scene, const Accel& accel, const CameraDesc& camera,
                          const RenderSettings& settings) {
  std::unique_ptr<Sampler> sampler = make_sampler(settings.quality.sampler, 4);
  TileRenderer renderer(scene, accel, camera, settings, *sampler);
  Film film(settings.width, settings.height);
  renderer.render_pass(film, 0, 1);
  std::vector<double> ms;
  for (uint32_t r = 0; r < 3; ++r)
    ms.push_back(renderer.render_pass(film, 1 + 2 * r, 2).render_ms / 2);
  return median(ms);
}

FrameRun run_frames(const Scene& scene, const Accel& accel, const CameraDesc& camera,
                    const RenderSettings& settings, double frame_ms, int frames, uint64_t seed,
                    const Image& truth) {
  FrameRun run;
  PassStats total;
  run_shown_frames(scene, accel, camera, settings, seed, frame_ms, [&](const ShownFrame& f) {
    total.accumulate(f.frame.stats);
    run.time_ms.push_back(f.time_ms);
    run.spp.push_back(f.spp);
    run.rmse.push_back(rmse(f.image, truth));
    return static_cast<int>(run.rmse.size()) < frames;
  });
  run.mrays_per_s = total.mrays_per_s();
  return run;
}

// Phase times (ms per spp per thread) from a separate profiled pass: the clocks cost a little.
void measure_phases(const Scene& scene, const Accel& accel, const CameraDesc& camera,
                    RenderSettings s, QualityRow& r) {
  s.quality.profile_phases = true;
  s.quality.adaptive = false;
  const double threads = tbb::this_task_arena::max_concurrency();
  std::unique_ptr<Sampler> sampler = make_sampler(s.quality.sampler, 3);
  TileRenderer renderer(scene, accel, camera, s, *sampler);
  Film film(s.width, s.height);
  PassStats ps = renderer.render_pass(film, 0, 2);
  r.intersect = ps.intersect_ms / threads / 2;
  r.shading = ps.shading_ms / threads / 2;
  r.shadow = ps.shadow_ms / threads / 2;
}

// Same sampler, seed and unbiased switches: only the bias differs between the two images.
double measure_bias(const Scene& scene, const Accel& accel, const CameraDesc& camera,
                    const RenderSettings& s, int spp) {
  RenderSettings biased = s;
  biased.quality.adaptive = false;
  RenderSettings unbiased = biased;
  unbiased.quality = biased.quality.without_bias();
  return rmse(render_fixed(scene, accel, camera, biased, 2, spp),
              render_fixed(scene, accel, camera, unbiased, 2, spp));
}

std::vector<SweepPoint> sweep(const Scene& scene, const Accel& accel, const CameraDesc& camera,
                              const RenderSettings& base, const QualityHooks& hooks) {
  std::vector<SweepPoint> points;
  auto add = [&](const char* mode, int size, const RenderSettings& s) {
    points.push_back({mode, size, measure_ms_per_spp(scene, accel, camera, s)});
    if (hooks.sweep) hooks.sweep(points.back());
  };
  for (int tile : {8, 16, 32, 64}) {
    RenderSettings s = base;
    s.tile_size = tile;
    add("tile", tile, s);
  }
  for (int batch : {256, 1024, 4096, 16384, 65536}) {
    RenderSettings s = base;
    s.quality.wavefront = true;
    s.quality.batch_size = batch;
    add("wavefront", batch, s);
  }
  return points;
}

}  // namespace

QualityScene run_quality_scene(const QualityBenchOptions& a, const std::string& spec,
                               const QualityHooks& hooks) {
  QualityScene out;
  out.spec = spec;
  LoadOptions load_options;
  load_options.scenes_dir = a.scenes_dir;
  Scene scene = load_scene(spec, load_options);
  Scene collapsed = scene;
  OneTexelStats texel_stats = collapse_one_texel_textures(collapsed);
  std::unique_ptr<Accel> accel = make_accel("native", "");
  accel->build({scene.positions.data(), scene.positions.size(), scene.triangles.data(),
                scene.triangles.size()});
  const CameraDesc& camera = scene.cameras.at(0);
  out.name = scene.name;
  out.triangles = scene.triangles.size();
  out.one_texel_candidates = texel_stats.candidates;
  out.one_texel_collapsed = texel_stats.collapsed;
  if (hooks.loaded) hooks.loaded(out);

  GroundTruthKey key{spec,          camera,      a.width,           a.height,
                     a.max_bounces, a.truth_spp, a.truth_until_rmse};
  key.require_halves = true;
  out.truth_path = ground_truth_path(a.truth_dir, key);
  Image truth = ground_truth(a.truth_dir, key, scene, *accel, &out.truth, hooks.truth_progress);
  const std::optional<GroundTruthHalves> halves = ground_truth_halves(a.truth_dir, key);
  if (!halves) throw std::runtime_error(out.truth_path + ": its halves are missing");
  const double noise_mse = reference_noise_mse(halves->a, halves->b);
  out.truth_noise_rmse = std::sqrt(noise_mse);
  out.truth_spp = out.truth.rendered ? out.truth.spp : a.truth_spp;

  RenderSettings base;
  base.width = a.width;
  base.height = a.height;
  base.max_bounces = a.max_bounces;
  base.quality = QualityOptions::reference();
  out.frame_ms = a.frame_ms;
  if (a.target_spp > 0)  // budget from the baseline's speed on this scene and machine
    out.frame_ms = a.target_spp * measure_ms_per_spp(scene, *accel, camera, base);
  if (hooks.ready) hooks.ready(out);

  struct Chosen {
    std::string name;
    RenderSettings settings;
    const Scene* scene;
  };
  std::vector<Chosen> chosen;
  for (const std::string& name : quality_configurations()) {
    if (!a.only.empty() && std::find(a.only.begin(), a.only.end(), name) == a.only.end()) continue;
    RenderSettings s = base;
    QualitySwitches switches = quality_switches(name, s.quality, a);
    s.quality = switches.quality;
    chosen.push_back({name, s, switches.one_texel ? &collapsed : &scene});
  }

  // Repeats run round-robin over the configurations, so a change in the machine's load
  // affects every row alike; each repeat has its own seed.
  std::vector<std::vector<FrameRun>> runs(chosen.size());
  for (int rep = 0; rep < a.repeats; ++rep) {
    for (size_t i = 0; i < chosen.size(); ++i)
      runs[i].push_back(run_frames(*chosen[i].scene, *accel, camera, chosen[i].settings,
                                   out.frame_ms, a.frames, 1 + 1000 * static_cast<uint64_t>(rep),
                                   truth));
    if (a.repeats > 1 && hooks.repeat_done) hooks.repeat_done(out, rep);
  }

  double base_rmse = 0, exact_base_rmse = 0;
  for (size_t i = 0; i < chosen.size(); ++i) {
    const RenderSettings& s = chosen[i].settings;
    const Scene& used = *chosen[i].scene;
    QualityRow r = summarize_runs(chosen[i].name, runs[i], out.frame_ms * a.frames);
    r.exact_rmse_at_budget = rmse_without_reference_noise(r.rmse_at_budget, noise_mse);
    measure_phases(used, *accel, camera, s, r);
    if (s.quality.biased()) r.bias = measure_bias(used, *accel, camera, s, a.bias_spp);
    if (r.name == "baseline") {
      base_rmse = r.rmse_at_budget;
      exact_base_rmse = r.exact_rmse_at_budget;
    }
    r.baseline_rmse = base_rmse;
    r.exact_baseline_rmse = exact_base_rmse;
    out.rows.push_back(r);
    if (hooks.row) hooks.row(out.rows.back());
  }
  if (a.sweep) out.sweep = sweep(scene, *accel, camera, base, hooks);
  return out;
}

}  // namespace tuneray
