#include "app/cmd_bench_quality.h"

#include <fmt/core.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "accel/factory.h"
#include "app/cli_parse.h"
#include "app/ground_truth.h"
#include "app/scene_paths.h"
#include "image/metrics.h"
#include "render/film.h"
#include "render/frame_budget.h"
#include "render/tile_renderer.h"
#include "scene/load.h"
#include "scene/one_texel.h"

namespace tuneray {

namespace {

struct Config {
  std::string name;
  std::function<void(QualityOptions&, bool& one_texel, float clamp)> apply;
};

// The baseline has every switch off (12-byte sky texels, textures kept); each row switches one
// technique on; "all" switches every one on.
std::vector<Config> configurations() {
  auto set_all = [](QualityOptions& o, bool& one_texel, float clamp) {
    o.wavefront = o.sky_rgba = o.lowres_sky = o.regularize = o.adaptive = true;
    o.clamp = clamp;
    one_texel = true;
  };
  return {
      {"baseline", [](QualityOptions&, bool&, float) {}},
      {"wavefront", [](QualityOptions& o, bool&, float) { o.wavefront = true; }},
      {"sky-rgba", [](QualityOptions& o, bool&, float) { o.sky_rgba = true; }},
      {"one-texel", [](QualityOptions&, bool& t, float) { t = true; }},
      {"lowres-sky", [](QualityOptions& o, bool&, float) { o.lowres_sky = true; }},
      {"regularize", [](QualityOptions& o, bool&, float) { o.regularize = true; }},
      {"clamp", [](QualityOptions& o, bool&, float m) { o.clamp = m; }},
      {"adaptive", [](QualityOptions& o, bool&, float) { o.adaptive = true; }},
      {"all", set_all},
  };
}

QualityOptions baseline_options() {
  QualityOptions o;
  o.sky_rgba = false;
  return o;
}

struct ConfigResult {
  std::string name;
  std::vector<double> time_ms, spp, rmse;  // after each frame (time and spp cumulative)
  double ms_per_spp = 0, intersect = 0, shading = 0, shadow = 0;  // ms per spp
  double mrays_per_s = 0;
  double bias = 0;  // RMSE vs the unbiased render with the same random numbers; 0 if unbiased
};

double rmse(const Image& a, const Image& b) {
  return compare_images(a, b).rmse;
}

Image render_fixed(const Scene& scene, const Accel& accel, const CameraDesc& camera,
                   const RenderSettings& settings, uint64_t seed, int spp) {
  PcgSampler sampler(seed);
  TileRenderer renderer(scene, accel, camera, settings, sampler);
  Film film(settings.width, settings.height);
  renderer.render_pass(film, 0, static_cast<uint32_t>(spp));
  return film.resolve();
}

nlohmann::ordered_json run_scene(const BenchQualityArgs& a, const std::string& spec,
                                 std::vector<ConfigResult>& results, std::ostream& plot_data) {
  auto [width, height] = parse_size(a.size);
  LoadOptions load_options;
  load_options.scenes_dir = a.scenes_dir;
  Scene scene = load_scene(spec, load_options);
  Scene collapsed = scene;
  OneTexelStats texel_stats = collapse_one_texel_textures(collapsed);
  std::unique_ptr<Accel> accel = make_accel("native", "");
  accel->build({scene.positions.data(), scene.positions.size(), scene.triangles.data(),
                scene.triangles.size()});
  const CameraDesc& camera = scene.cameras.at(0);

  GroundTruthKey key{spec, camera, width, height, a.max_bounces, a.truth_spp};
  bool rendered = false;
  Image truth = ground_truth(a.truth_dir, key, scene, *accel, &rendered);
  fmt::print("{}: {} triangles, one-texel {} of {} candidates, truth {} ({})\n", scene.name,
             scene.triangles.size(), texel_stats.collapsed, texel_stats.candidates,
             ground_truth_path(a.truth_dir, key), rendered ? "rendered" : "cached");

  RenderSettings base;
  base.width = width;
  base.height = height;
  base.max_bounces = a.max_bounces;
  base.quality = baseline_options();
  Image unbiased_crn = render_fixed(scene, *accel, camera, base, 2, a.bias_spp);
  const double threads = tbb::this_task_arena::max_concurrency();
  double frame_ms = a.frame_ms;
  if (a.target_spp > 0) {  // budget from the baseline's speed on this scene and machine
    PcgSampler sampler(5);
    TileRenderer renderer(scene, *accel, camera, base, sampler);
    Film film(width, height);
    frame_ms = a.target_spp * renderer.render_pass(film, 0, 2).render_ms / 2;
  }
  fmt::print("frame budget {:.0f} ms\n", frame_ms);

  results.clear();
  for (const Config& config : configurations()) {
    if (!a.only.empty() && std::find(a.only.begin(), a.only.end(), config.name) == a.only.end())
      continue;
    RenderSettings s = base;
    bool one_texel = false;
    config.apply(s.quality, one_texel, a.clamp);
    const Scene& used = one_texel ? collapsed : scene;
    ConfigResult r;
    r.name = config.name;
    {
      PcgSampler sampler(1);
      TileRenderer renderer(used, *accel, camera, s, sampler);
      Film film(width, height);
      FrameBudgetRenderer budget(renderer, frame_ms);
      double t = 0, spp = 0;
      PassStats total;
      for (int f = 0; f < a.frames; ++f) {
        FrameResult frame = budget.render_frame(film);
        total.accumulate(frame.stats);
        t += frame.ms;
        spp += frame.spp;
        r.time_ms.push_back(t);
        r.spp.push_back(spp);
        r.rmse.push_back(rmse(film.resolve(), truth));
      }
      r.ms_per_spp = total.render_ms / std::max(spp, 1e-9);
      r.mrays_per_s = total.mrays_per_s();
    }
    {  // phase times from a separate profiled pass (the clocks cost a little)
      RenderSettings p = s;
      p.quality.profile_phases = true;
      p.quality.adaptive = false;
      PcgSampler sampler(3);
      TileRenderer renderer(used, *accel, camera, p, sampler);
      Film film(width, height);
      PassStats ps = renderer.render_pass(film, 0, 2);
      r.intersect = ps.intersect_ms / threads / 2;
      r.shading = ps.shading_ms / threads / 2;
      r.shadow = ps.shadow_ms / threads / 2;
    }
    if (s.quality.biased()) {
      RenderSettings b = s;
      b.quality.adaptive = false;
      r.bias = rmse(render_fixed(used, *accel, camera, b, 2, a.bias_spp), unbiased_crn);
    }
    plot_data << "\"" << scene.name << " " << r.name << "\"\n";
    for (size_t i = 0; i < r.time_ms.size(); ++i)
      plot_data << r.time_ms[i] << " " << r.rmse[i] << "\n";
    plot_data << "\n\n";
    results.push_back(r);
  }

  const double base_rmse = results.empty() ? 0 : results.front().rmse.back();
  fmt::print("{:<11} {:>8} {:>7} {:>7} {:>7} {:>7} {:>8} {:>9} {:>6} {:>8}\n", "config", "ms/spp",
             "isect", "shade", "shadow", "Mray/s", "spp", "RMSE", "vs base", "bias");
  nlohmann::ordered_json rows = nlohmann::ordered_json::array();
  for (const ConfigResult& r : results) {
    double ratio = base_rmse > 0 ? r.rmse.back() / base_rmse : 0;
    fmt::print(
        "{:<11} {:>8.2f} {:>7.2f} {:>7.2f} {:>7.2f} {:>7.2f} {:>8.1f} {:>9.5f} {:>6.3f} "
        "{:>8.5f}\n",
        r.name, r.ms_per_spp, r.intersect, r.shading, r.shadow, r.mrays_per_s, r.spp.back(),
        r.rmse.back(), ratio, r.bias);
    rows.push_back({{"config", r.name},
                    {"ms_per_spp", r.ms_per_spp},
                    {"intersect_ms_per_spp", r.intersect},
                    {"shading_ms_per_spp", r.shading},
                    {"shadow_ms_per_spp", r.shadow},
                    {"mrays_per_s", r.mrays_per_s},
                    {"spp", r.spp},
                    {"time_ms", r.time_ms},
                    {"rmse", r.rmse},
                    {"rmse_vs_baseline", ratio},
                    {"bias", r.bias}});
  }

  nlohmann::ordered_json sweep = nlohmann::ordered_json::array();
  if (a.sweep) {
    auto time_per_spp = [&](RenderSettings s) {
      PcgSampler sampler(4);
      TileRenderer renderer(scene, *accel, camera, s, sampler);
      Film film(width, height);
      return renderer.render_pass(film, 0, 2).render_ms / 2;
    };
    for (int tile : {8, 16, 32, 64}) {
      RenderSettings s = base;
      s.tile_size = tile;
      double ms = time_per_spp(s);
      fmt::print("sweep tile {:>5}: {:.2f} ms/spp\n", tile, ms);
      sweep.push_back({{"mode", "tile"}, {"size", tile}, {"ms_per_spp", ms}});
    }
    for (int batch : {256, 1024, 4096, 16384, 65536}) {
      RenderSettings s = base;
      s.quality.wavefront = true;
      s.quality.batch_size = batch;
      double ms = time_per_spp(s);
      fmt::print("sweep batch {:>5}: {:.2f} ms/spp\n", batch, ms);
      sweep.push_back({{"mode", "wavefront"}, {"size", batch}, {"ms_per_spp", ms}});
    }
  }
  return {{"scene", spec},
          {"name", scene.name},
          {"triangles", scene.triangles.size()},
          {"one_texel_candidates", texel_stats.candidates},
          {"one_texel_collapsed", texel_stats.collapsed},
          {"truth", ground_truth_path(a.truth_dir, key)},
          {"truth_spp", a.truth_spp},
          {"frame_ms", frame_ms},
          {"configs", rows},
          {"sweep", sweep}};
}

void write_plot_script(const std::string& prefix, const std::vector<std::string>& titles) {
  std::ofstream gp(prefix + ".gp");
  std::string data = std::filesystem::path(prefix + ".dat").filename().string();
  gp << "# gnuplot " << std::filesystem::path(prefix + ".gp").filename().string() << "\n"
     << "set terminal pngcairo size 1000,640\nset output '"
     << std::filesystem::path(prefix + ".png").filename().string() << "'\n"
     << "set xlabel 'time (ms)'\nset ylabel 'RMSE'\nset logscale y\nset key outside\n"
     << "plot ";
  for (size_t i = 0; i < titles.size(); ++i)
    gp << (i ? ", \\\n     " : "") << "'" << data << "' index " << i
       << " using 1:2 with linespoints title '" << titles[i] << "'";
  gp << "\n";
}

}  // namespace

int run_bench_quality(const BenchQualityArgs& a) {
  std::vector<std::string> scenes = a.scenes;
  if (scenes.empty()) scenes = shared_scene_json_files();
  if (scenes.empty()) throw std::invalid_argument("bench quality: no scenes given or found");
  nlohmann::ordered_json out = {{"size", a.size},
                                {"frame_ms", a.frame_ms},
                                {"frames", a.frames},
                                {"max_bounces", a.max_bounces},
                                {"threads", tbb::this_task_arena::max_concurrency()},
                                {"scenes", nlohmann::ordered_json::array()}};
  std::ofstream plot_data;
  if (!a.plot.empty()) {
    std::filesystem::path parent = std::filesystem::path(a.plot).parent_path();
    if (!parent.empty()) std::filesystem::create_directories(parent);
    plot_data.open(a.plot + ".dat");
  }
  std::ostringstream sink;
  std::vector<std::string> titles;
  for (const std::string& spec : scenes) {
    std::vector<ConfigResult> results;
    std::ostringstream data;
    out["scenes"].push_back(run_scene(a, spec, results, data));
    if (plot_data.is_open()) plot_data << data.str();
    for (const ConfigResult& r : results)
      titles.push_back(out["scenes"].back()["name"].get<std::string>() + " " + r.name);
  }
  if (!a.plot.empty()) write_plot_script(a.plot, titles);
  if (!a.json.empty()) {
    std::filesystem::path parent = std::filesystem::path(a.json).parent_path();
    if (!parent.empty()) std::filesystem::create_directories(parent);
    std::ofstream f(a.json);
    if (!(f << out.dump(2) << "\n")) throw std::runtime_error("cannot write " + a.json);
  }
  return 0;
}

}  // namespace tuneray
