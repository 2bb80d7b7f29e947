// tuneray render SCENE: renders a scene progressively and writes the image(s) and a report.
#include <tbb/global_control.h>

#include <cctype>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "accel/factory.h"
#include "app/cli_parse.h"
#include "app/commands.h"
#include "app/ground_truth.h"
#include "app/progress.h"
#include "app/quality_cli.h"
#include "app/resource_limits.h"
#include "image/atomic_file.h"
#include "image/io.h"
#include "render/blue_noise_sampler.h"
#include "render/film.h"
#include "render/frame_budget.h"
#include "render/tile_renderer.h"
#include "scene/load.h"
#include "scene/one_texel.h"

namespace tuneray {

namespace {

struct RenderArgs {
  std::string scene = "cornell";
  int spp = 16;
  std::string size = "640x360";
  std::vector<std::string> outputs;
  std::string accel = "native";
  std::string bvh;
  int threads = 0;
  uint64_t seed = 0;
  int max_bounces = 3;
  int camera = 0;
  int tile_size = 32;
  std::string strategy = "mis";
  std::string report;
  std::string scenes_dir;
  float exposure = 0;
  bool quiet = false;
  bool profile_phases = false;
  double frame_ms = 0;  // > 0: frame-budget mode
  int frames = 1;
  double until_rmse = 0;  // > 0: stop once the image's estimated RMSE is below this
  std::string truth_dir;  // non-empty: render (or read) the cached ground truth
  QualityCli quality;
};

// Samples per pixel of a ground truth when --spp is not given (docs/quality.md).
constexpr int kTruthSpp = 4096;

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

std::string default_output(const Scene& scene) {
  std::string stem = std::filesystem::path(scene.name.empty() ? "render" : scene.name).stem();
  return "out/" + stem + ".png";
}

// Checked before rendering so a typo does not cost a long render.
void check_output_extensions(const std::vector<std::string>& outputs) {
  for (const std::string& out : outputs) {
    std::string ext = std::filesystem::path(out).extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (ext != ".png" && ext != ".exr" && ext != ".pfm")
      throw std::invalid_argument("cannot write '" + out +
                                  "': unknown image extension (use .png, .exr or .pfm)");
  }
}

void write_outputs(const std::vector<std::string>& outputs, const Image& image, float exposure) {
  WriteOptions write_options;
  write_options.exposure = exposure;
  for (const std::string& out : outputs) {
    std::filesystem::path parent = std::filesystem::path(out).parent_path();
    if (!parent.empty()) std::filesystem::create_directories(parent);
    write_image(out, image, write_options);
  }
}

void write_report(const std::string& path, const nlohmann::ordered_json& report) {
  if (path.empty()) return;
  std::filesystem::path parent = std::filesystem::path(path).parent_path();
  if (!parent.empty()) std::filesystem::create_directories(parent);
  ReplacingFile f(path);
  f << report.dump(2) << "\n";
  f.commit();
}

// --truth-dir: the ground truth of `bench quality` (same cache, same key), read or rendered.
int run_truth(const RenderArgs& a, int width, int height, const Scene& scene, const Accel& accel,
              double load_ms, double build_ms) {
  GroundTruthKey key{a.scene,     scene.cameras[a.camera], width, height, a.max_bounces, a.spp,
                     a.until_rmse};
  GroundTruthInfo info;
  Image image = ground_truth(a.truth_dir, key, scene, accel, &info, !a.quiet);
  write_outputs(a.outputs, image, a.exposure);
  std::string path = ground_truth_path(a.truth_dir, key);
  nlohmann::ordered_json report = {{"scene", a.scene},
                                   {"truth", path},
                                   {"rendered", info.rendered},
                                   {"spp", info.spp},
                                   {"estimated_rmse", info.estimated_rmse},
                                   {"load_ms", load_ms},
                                   {"build_ms", build_ms},
                                   {"render_ms", info.render_ms},
                                   {"outputs", a.outputs}};
  write_report(a.report, report);
  if (!a.quiet) {
    if (info.rendered)
      std::cout << "truth     " << path << " (" << info.spp << " spp in "
                << static_cast<int>(info.render_ms) << " ms, estimated RMSE " << info.estimated_rmse
                << ")\n";
    else
      std::cout << "truth     " << path << " (cached)\n";
    for (const auto& out : a.outputs) std::cout << "wrote     " << out << "\n";
  }
  return 0;
}

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

  std::unique_ptr<tbb::global_control> thread_limit;
  check_image_memory(width, height, "image");
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
      frames.push_back({{"frame", f}, {"ms", frame.ms}, {"spp", frame.spp}});
      if (!a.quiet)
        std::cout << "frame     " << f << ": " << frame.spp << " spp in " << frame.ms << " ms\n";
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
  Image image = film.resolve();
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

}  // namespace

CommandAction add_render_command(CLI::App& app) {
  auto args = std::make_shared<RenderArgs>();
  CLI::App* cmd = app.add_subcommand("render", "Render a scene to an image");
  cmd->add_option("scene", args->scene, "Built-in name, mesh file (.obj/.ply/.gltf) or .json scene")
      ->capture_default_str();
  CLI::Option* spp =
      cmd->add_option("--spp", args->spp, "Samples per pixel (with --truth-dir: 4096 unless given)")
          ->check(CLI::Range(1, 1 << 20))
          ->capture_default_str();
  cmd->add_option("--size", args->size, "Image size WIDTHxHEIGHT")->capture_default_str();
  cmd->add_option("--out", args->outputs, "Output file(s): .png, .exr or .pfm (repeatable)");
  cmd->add_option("--accel", args->accel, "Acceleration structure backend")->capture_default_str();
  cmd->add_option("--bvh", args->bvh, "Backend parameters key=value,... (see docs/bvh.md)");
  cmd->add_option("--threads", args->threads, "Worker threads (0 = all cores)")
      ->check(CLI::Range(0, 1024));
  cmd->add_option("--seed", args->seed, "Random seed")->capture_default_str();
  cmd->add_option("--max-bounces", args->max_bounces,
                  "Scattering events per path (1 = direct light)")
      ->check(CLI::Range(0, 1000))
      ->capture_default_str();
  cmd->add_option("--camera", args->camera, "Camera index")->capture_default_str();
  cmd->add_option("--tile-size", args->tile_size, "Tile side in pixels")
      ->check(CLI::Range(1, 4096))
      ->capture_default_str();
  cmd->add_option("--strategy", args->strategy,
                  "Light transport: mis, light (NEE only), bsdf (no NEE)")
      ->capture_default_str();
  cmd->add_option("--report", args->report, "Write timings as JSON to this file");
  cmd->add_option("--scenes-dir", args->scenes_dir,
                  "Folder to resolve scene files in ($TUNERAY_SCENES)");
  cmd->add_option("--exposure", args->exposure, "Exposure in stops for PNG output")
      ->capture_default_str();
  cmd->add_flag("--quiet,-q", args->quiet, "No progress bar or summary");
  cmd->add_flag("--profile-phases", args->profile_phases,
                "Time intersection, shading and shadow rays apart (summary and report; costs a "
                "little)");
  cmd->add_option("--frame-ms", args->frame_ms,
                  "Frame budget in ms: each frame adds as many spp as fit (replaces --spp)")
      ->check(CLI::Range(0.0, 1e7));
  cmd->add_option("--frames", args->frames, "Frames to accumulate in frame-budget mode")
      ->check(CLI::Range(1, 1 << 20))
      ->capture_default_str();
  cmd->add_option("--until-rmse", args->until_rmse,
                  "Stop before --spp once the image's estimated RMSE (from per-pixel variance) is "
                  "below this")
      ->check(CLI::Range(0.0, 1e30));
  cmd->add_option("--truth-dir", args->truth_dir,
                  "Ground-truth mode: read the cached unbiased reference of this scene, camera, "
                  "size, bounces and --spp/--until-rmse from this folder, or render and cache it "
                  "(tiles, PCG, seed 0; shared with bench quality)");
  add_quality_options(cmd, args->quality);
  return [args, spp] {
    if (!args->truth_dir.empty() && spp->count() == 0) args->spp = kTruthSpp;
    return run_render(*args);
  };
}

}  // namespace tuneray
