// tuneray render SCENE: renders a scene progressively and writes the image(s) and a report
// (options: cmd_render_cli.cpp; outputs and --truth-dir: render_output.cpp).
#include <tbb/global_control.h>

#include <chrono>
#include <iostream>
#include <memory>

#include "accel/factory.h"
#include "app/cli_parse.h"
#include "app/progress.h"
#include "app/render_args.h"
#include "render/blue_noise_sampler.h"
#include "render/denoiser_frame.h"
#include "render/film.h"
#include "render/frame_budget.h"
#include "render/resource_limits.h"
#include "render/tile_renderer.h"
#include "scene/load.h"
#include "scene/one_texel.h"

namespace tuneray {

namespace {

double ms_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

LightStrategy parse_strategy(const std::string& s) {
  if (s == "mis") return LightStrategy::kMis;
  if (s == "light") return LightStrategy::kLightOnly;
  if (s == "bsdf") return LightStrategy::kBsdfOnly;
  throw std::invalid_argument("bad --strategy '" + s + "': expected mis, light or bsdf");
}

}  // namespace

int run_render(const RenderArgs& a) {
  auto [width, height] = parse_size(a.size);
  check_output_extensions(a.outputs);
  RenderSettings settings;
  settings.width = width;
  settings.height = height;
  settings.max_bounces = a.max_bounces;
  settings.tile_size = a.tile_size;
  settings.seed = a.seed;
  settings.strategy = parse_strategy(a.strategy);
  settings.quality = resolve_quality(a.quality);
  settings.quality.profile_phases = a.profile_phases;
  if (a.quality.adaptive_on && a.frame_ms <= 0)
    throw std::invalid_argument("--adaptive needs the frame-budget mode (--frame-ms)");
  if (!a.truth_dir.empty()) {
    if (settings.quality.biased())
      throw std::invalid_argument(
          "--truth-dir renders an unbiased reference: drop --clamp, --clamp-rel, --regularize "
          "and --lowres-sky");
    if (a.frame_ms > 0)
      throw std::invalid_argument("--truth-dir takes --spp (and --until-rmse), not --frame-ms");
  }
  if (a.until_rmse > 0 && a.frame_ms > 0)
    throw std::invalid_argument("--until-rmse takes --spp as its limit, not --frame-ms");

  check_render_memory(width, height);
  std::unique_ptr<tbb::global_control> thread_limit;
  if (const int threads = clamp_threads(a.threads); threads > 0)
    thread_limit = std::make_unique<tbb::global_control>(
        tbb::global_control::max_allowed_parallelism, static_cast<size_t>(threads));

  auto t0 = std::chrono::steady_clock::now();
  LoadOptions load_options;
  load_options.scenes_dir = a.scenes_dir;
  Scene scene = load_scene(a.scene, load_options);
  OneTexelStats one_texel;
  if (a.quality.one_texel) one_texel = collapse_one_texel_textures(scene);
  double load_ms = ms_since(t0);
  if (a.camera < 0 || a.camera >= static_cast<int>(scene.cameras.size()))
    throw std::invalid_argument("bad --camera " + std::to_string(a.camera) + ": scene '" + a.scene +
                                "' has cameras 0.." + std::to_string(scene.cameras.size() - 1));

  std::unique_ptr<Accel> accel = make_accel(a.accel, a.bvh);
  GeometryView geometry{scene.positions.data(), scene.positions.size(), scene.triangles.data(),
                        scene.triangles.size()};
  BuildStats build = accel->build(geometry);

  if (!a.truth_dir.empty())
    return run_truth(a, width, height, scene, *accel, load_ms, build.build_ms);

  std::unique_ptr<Sampler> sampler = make_sampler(settings.quality.sampler, a.seed);
  TileRenderer renderer(scene, *accel, scene.cameras[a.camera], settings, *sampler);
  Film film(width, height);
  ProgressBar progress("render", static_cast<uint64_t>(renderer.tile_count()) * a.spp,
                       !a.quiet && a.frame_ms <= 0 && stderr_is_terminal());
  PassStats total;
  nlohmann::ordered_json frames = nlohmann::ordered_json::array();
  if (a.frame_ms > 0) {
    FrameBudgetRenderer budget(renderer, a.frame_ms);
    for (int f = 0; f < a.frames; ++f) {
      FrameResult frame = budget.render_frame(film);
      total.accumulate(frame.stats);
      // Of the frame's samples, those traced with path reuse (all or none unless it is auto).
      const double reused_spp =
          static_cast<double>(frame.stats.reused_samples) / (static_cast<double>(width) * height);
      frames.push_back(
          {{"frame", f}, {"ms", frame.ms}, {"spp", frame.spp}, {"reused_spp", reused_spp}});
      if (!a.quiet)
        std::cout << "frame     " << f << ": " << frame.spp << " spp in " << frame.ms << " ms"
                  << (reused_spp > 0 ? " (" + std::to_string(reused_spp) + " with path reuse)" : "")
                  << "\n";
    }
  }
  for (int s = 0; a.frame_ms <= 0 && s < a.spp; ++s) {
    PassStats pass = renderer.render_pass(film, static_cast<uint32_t>(s), 1,
                                          [&progress] { progress.advance(); });
    total.accumulate(pass);
    if (a.until_rmse > 0 && s >= 1) {
      double estimate = film.estimated_rmse();
      progress.set_suffix("est. RMSE " + std::to_string(estimate));
      if (estimate < a.until_rmse) break;
    }
  }
  progress.finish();

  auto t_out = std::chrono::steady_clock::now();
  FrameResolver resolver;
  Image image = resolver.resolve(renderer, film);
  std::vector<std::string> outputs =
      a.outputs.empty() ? std::vector{default_output(scene)} : a.outputs;
  write_outputs(outputs, image, a.exposure);
  double output_ms = ms_since(t_out);

  nlohmann::ordered_json report = {
      {"scene", a.scene},
      {"triangles", scene.triangles.size()},
      {"width", width},
      {"height", height},
      {"spp", static_cast<double>(total.samples) / (width * height)},
      {"estimated_rmse", film.estimated_rmse()},
      {"frame_ms", a.frame_ms},
      {"frames", frames},
      {"one_texel_triangles", one_texel.collapsed},
      {"accel", accel->name()},
      {"accel_config", accel->describe()},
      {"load_ms", load_ms},
      {"build_ms", build.build_ms},
      {"render_ms", total.render_ms},
      {"output_ms", output_ms},
      {"rays", total.rays},
      {"shadow_rays", total.shadow_rays},
      {"mrays_per_s", total.mrays_per_s()},
      {"invalid_samples", total.invalid_samples},
      {"outputs", outputs},
  };
  if (a.profile_phases)
    report["phases_ms"] = {{"intersect", total.intersect_ms},
                           {"shading", total.shading_ms},
                           {"shadow", total.shadow_ms}};
  write_report(a.report, report);
  if (!a.quiet) {
    std::cout << "scene     " << a.scene << " (" << scene.triangles.size()
              << " triangles, loaded in " << static_cast<int>(load_ms) << " ms)\n"
              << "accel     " << accel->name() << " " << accel->describe() << ", built in "
              << build.build_ms << " ms\n"
              << "render    " << width << "x" << height << ", "
              << static_cast<double>(total.samples) / (width * height) << " spp in "
              << total.render_ms << " ms (" << total.mrays_per_s() << " Mrays/s)\n";
    if (a.profile_phases)
      std::cout << "phases    intersect " << total.intersect_ms << " ms, shading "
                << total.shading_ms << " ms, shadow " << total.shadow_ms
                << " ms (summed over threads)\n";
    for (const auto& out : outputs) std::cout << "wrote     " << out << "\n";
    if (!a.report.empty()) std::cout << "wrote     " << a.report << "\n";
    if (total.invalid_samples > 0)
      std::cout << "warning   " << total.invalid_samples << " samples with NaN/inf dropped\n";
  }
  return 0;
}

}  // namespace tuneray
