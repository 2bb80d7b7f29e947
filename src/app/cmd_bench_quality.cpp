#include "app/cmd_bench_quality.h"

#include <fmt/core.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>

#include "accel/factory.h"
#include "app/cli_parse.h"
#include "app/equal_time.h"
#include "app/ground_truth.h"
#include "app/scene_paths.h"
#include "image/metrics.h"
#include "render/blue_noise_sampler.h"
#include "render/film.h"
#include "render/frame_budget.h"
#include "render/tile_renderer.h"
#include "scene/load.h"
#include "scene/one_texel.h"
#include "tuning/stats.h"

namespace tuneray {

namespace {

// What a row switches on: the render options plus the load-time one-texel folding.
struct Switches {
  QualityOptions quality;
  bool one_texel = false;
};

struct Config {
  std::string name;
  std::function<void(Switches&, const BenchQualityArgs&)> apply;
};

void set_clamp(QualityOptions& o, const BenchQualityArgs& a) {
  o.clamp = a.clamp;
  o.clamp_relative = a.clamp > 0 ? 0.0f : a.clamp_relative;
}

void set_unbiased(Switches& s) {
  QualityOptions& o = s.quality;
  o.wavefront = o.sky_rgba = o.branchless_materials = o.adaptive = true;
  o.sampler = SamplerKind::kBlueNoise;
  s.one_texel = true;
}

// The baseline has every switch off (tiles, 12-byte sky texels, textures kept, per-type
// material evaluation, PCG numbers, uniform sampling); each row switches one technique on;
// "unbiased" switches on every technique that leaves the expected image alone, "defaults" is
// QualityOptions{} (what the renderer does unless told otherwise), "all" switches on every one.
const std::vector<Config>& configurations() {
  static const std::vector<Config> configs = {
      {"baseline", [](Switches&, const BenchQualityArgs&) {}},
      {"wavefront", [](Switches& s, const BenchQualityArgs&) { s.quality.wavefront = true; }},
      {"sky-rgba", [](Switches& s, const BenchQualityArgs&) { s.quality.sky_rgba = true; }},
      {"one-texel", [](Switches& s, const BenchQualityArgs&) { s.one_texel = true; }},
      {"branchless",
       [](Switches& s, const BenchQualityArgs&) { s.quality.branchless_materials = true; }},
      {"bluenoise",
       [](Switches& s, const BenchQualityArgs&) { s.quality.sampler = SamplerKind::kBlueNoise; }},
      {"adaptive", [](Switches& s, const BenchQualityArgs&) { s.quality.adaptive = true; }},
      {"lowres-sky", [](Switches& s, const BenchQualityArgs&) { s.quality.lowres_sky = true; }},
      {"regularize", [](Switches& s, const BenchQualityArgs&) { s.quality.regularize = true; }},
      {"clamp", [](Switches& s, const BenchQualityArgs& a) { set_clamp(s.quality, a); }},
      {"unbiased", [](Switches& s, const BenchQualityArgs&) { set_unbiased(s); }},
      {"defaults",
       [](Switches& s, const BenchQualityArgs&) {
         s.quality = QualityOptions{};  // what `render` and RenderSettings{} use
         s.one_texel = true;
       }},
      {"all",
       [](Switches& s, const BenchQualityArgs& a) {
         set_unbiased(s);
         s.quality.lowres_sky = s.quality.regularize = true;
         set_clamp(s.quality, a);
       }},
  };
  return configs;
}

struct ConfigResult {
  std::string name;
  std::vector<double> time_ms, spp, rmse;  // after each frame (time and spp cumulative)
  double ms_per_spp = 0, intersect = 0, shading = 0, shadow = 0;  // ms per spp
  double mrays_per_s = 0;
  double bias = 0;  // RMSE vs the unbiased render with the same random numbers; 0 if unbiased
  double rmse_at_budget = 0;    // RMSE at exactly frames x frame budget (rmse_at)
  double time_over_budget = 0;  // wall time of the frames / (frames x frame budget)
};

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
  return film.resolve();
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

// One frame-budget run of a configuration: cumulative time, spp and RMSE after each frame.
struct FrameRun {
  std::vector<double> time_ms, spp, rmse;
  double mrays_per_s = 0;
};

FrameRun run_frames(const Scene& scene, const Accel& accel, const CameraDesc& camera,
                    const RenderSettings& settings, double frame_ms, int frames, uint64_t seed,
                    const Image& truth) {
  std::unique_ptr<Sampler> sampler = make_sampler(settings.quality.sampler, seed);
  TileRenderer renderer(scene, accel, camera, settings, *sampler);
  Film film(settings.width, settings.height);
  FrameBudgetRenderer budget(renderer, frame_ms);
  FrameRun run;
  double t = 0, spp = 0;
  PassStats total;
  for (int f = 0; f < frames; ++f) {
    FrameResult frame = budget.render_frame(film);
    total.accumulate(frame.stats);
    t += frame.ms;
    spp += frame.spp;
    run.time_ms.push_back(t);
    run.spp.push_back(spp);
    run.rmse.push_back(rmse(film.resolve(), truth));
  }
  run.mrays_per_s = total.mrays_per_s();
  return run;
}

// Medians over the repeats, frame by frame; `budget_ms` is frames x frame budget.
ConfigResult summarize(const std::string& name, const std::vector<FrameRun>& runs,
                       double budget_ms) {
  ConfigResult r;
  r.name = name;
  const size_t frames = runs.front().rmse.size();
  auto per_frame = [&](std::vector<double> FrameRun::*field, size_t f) {
    std::vector<double> v;
    for (const FrameRun& run : runs) v.push_back((run.*field)[f]);
    return median(v);
  };
  for (size_t f = 0; f < frames; ++f) {
    r.time_ms.push_back(per_frame(&FrameRun::time_ms, f));
    r.spp.push_back(per_frame(&FrameRun::spp, f));
    r.rmse.push_back(per_frame(&FrameRun::rmse, f));
  }
  std::vector<double> ms_per_spp, mrays, at_budget, over;
  for (const FrameRun& run : runs) {
    ms_per_spp.push_back(run.time_ms.back() / std::max(run.spp.back(), 1e-9));
    mrays.push_back(run.mrays_per_s);
    at_budget.push_back(rmse_at_time(run.time_ms, run.rmse, budget_ms));
    over.push_back(run.time_ms.back() / budget_ms);
  }
  r.ms_per_spp = median(ms_per_spp);
  r.mrays_per_s = median(mrays);
  r.rmse_at_budget = median(at_budget);
  r.time_over_budget = median(over);
  return r;
}

const char* kHeader = "{:<11} {:>8} {:>7} {:>7} {:>7} {:>7} {:>6} {:>6} {:>9} {:>7} {:>8}\n";

void print_header() {
  fmt::print(fmt::runtime(kHeader), "config", "ms/spp", "isect", "shade", "shadow", "Mray/s", "spp",
             "t/T", "RMSE@T", "vs base", "bias");
}

void print_row(const ConfigResult& r, double base_rmse) {
  std::string ratio = base_rmse > 0 ? fmt::format("{:.3f}", r.rmse_at_budget / base_rmse) : "-";
  fmt::print(fmt::runtime(kHeader), r.name, fmt::format("{:.2f}", r.ms_per_spp),
             fmt::format("{:.2f}", r.intersect), fmt::format("{:.2f}", r.shading),
             fmt::format("{:.2f}", r.shadow), fmt::format("{:.2f}", r.mrays_per_s),
             fmt::format("{:.1f}", r.spp.back()), fmt::format("{:.2f}", r.time_over_budget),
             fmt::format("{:.5f}", r.rmse_at_budget), ratio, fmt::format("{:.5f}", r.bias));
  std::fflush(stdout);
}

nlohmann::ordered_json run_scene(const BenchQualityArgs& a, const std::string& spec,
                                 std::ostream& plot_data) {
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

  GroundTruthKey key{spec, camera, width, height, a.max_bounces, a.truth_spp, a.truth_until_rmse};
  const std::string truth_path = ground_truth_path(a.truth_dir, key);
  fmt::print("{}: {} triangles, one-texel {} of {} candidates\n", scene.name,
             scene.triangles.size(), texel_stats.collapsed, texel_stats.candidates);
  std::fflush(stdout);
  GroundTruthInfo truth_info;
  Image truth = ground_truth(a.truth_dir, key, scene, *accel, &truth_info);
  if (truth_info.rendered)
    fmt::print("truth {} (rendered: {} spp in {:.1f} s, estimated RMSE {:.5f})\n", truth_path,
               truth_info.spp, truth_info.render_ms / 1e3, truth_info.estimated_rmse);
  else
    fmt::print("truth {} (cached)\n", truth_path);

  RenderSettings base;
  base.width = width;
  base.height = height;
  base.max_bounces = a.max_bounces;
  base.quality = QualityOptions::reference();
  const double threads = tbb::this_task_arena::max_concurrency();
  double frame_ms = a.frame_ms;
  if (a.target_spp > 0)  // budget from the baseline's speed on this scene and machine
    frame_ms = a.target_spp * measure_ms_per_spp(scene, *accel, camera, base);
  fmt::print("frame budget {:.1f} ms, {} frames\n", frame_ms, a.frames);
  print_header();
  std::fflush(stdout);

  struct Chosen {
    std::string name;
    RenderSettings settings;
    const Scene* scene;
  };
  std::vector<Chosen> chosen;
  for (const Config& config : configurations()) {
    if (!a.only.empty() && std::find(a.only.begin(), a.only.end(), config.name) == a.only.end())
      continue;
    RenderSettings s = base;
    Switches switches{s.quality, false};
    config.apply(switches, a);
    s.quality = switches.quality;
    chosen.push_back({config.name, s, switches.one_texel ? &collapsed : &scene});
  }

  // Repeats run round-robin over the configurations, so a change in the machine's load
  // affects every row alike; each repeat has its own seed.
  std::vector<std::vector<FrameRun>> runs(chosen.size());
  for (int rep = 0; rep < a.repeats; ++rep) {
    for (size_t i = 0; i < chosen.size(); ++i)
      runs[i].push_back(run_frames(*chosen[i].scene, *accel, camera, chosen[i].settings, frame_ms,
                                   a.frames, 1 + 1000 * static_cast<uint64_t>(rep), truth));
    if (a.repeats > 1) {
      fmt::print(stderr, "{}: repeat {}/{} done\n", scene.name, rep + 1, a.repeats);
      std::fflush(stderr);
    }
  }

  double base_rmse = 0;
  nlohmann::ordered_json rows = nlohmann::ordered_json::array();
  for (size_t i = 0; i < chosen.size(); ++i) {
    const RenderSettings& s = chosen[i].settings;
    const Scene& used = *chosen[i].scene;
    ConfigResult r = summarize(chosen[i].name, runs[i], frame_ms * a.frames);
    {  // phase times from a separate profiled pass (the clocks cost a little)
      RenderSettings p = s;
      p.quality.profile_phases = true;
      p.quality.adaptive = false;
      std::unique_ptr<Sampler> sampler = make_sampler(p.quality.sampler, 3);
      TileRenderer renderer(used, *accel, camera, p, *sampler);
      Film film(width, height);
      PassStats ps = renderer.render_pass(film, 0, 2);
      r.intersect = ps.intersect_ms / threads / 2;
      r.shading = ps.shading_ms / threads / 2;
      r.shadow = ps.shadow_ms / threads / 2;
    }
    if (s.quality.biased()) {  // same sampler, seed and unbiased switches: only the bias differs
      RenderSettings biased = s;
      biased.quality.adaptive = false;
      RenderSettings unbiased = biased;
      unbiased.quality = biased.quality.without_bias();
      r.bias = rmse(render_fixed(used, *accel, camera, biased, 2, a.bias_spp),
                    render_fixed(used, *accel, camera, unbiased, 2, a.bias_spp));
    }
    if (r.name == "baseline") base_rmse = r.rmse_at_budget;
    print_row(r, base_rmse);
    plot_data << "\"" << scene.name << " " << r.name << "\"\n";
    for (size_t f = 0; f < r.time_ms.size(); ++f)
      plot_data << r.time_ms[f] << " " << r.rmse[f] << "\n";
    plot_data << "\n\n";
    std::vector<double> final_rmse;
    for (const FrameRun& run : runs[i]) final_rmse.push_back(run.rmse.back());
    rows.push_back({{"config", r.name},
                    {"ms_per_spp", r.ms_per_spp},
                    {"intersect_ms_per_spp", r.intersect},
                    {"shading_ms_per_spp", r.shading},
                    {"shadow_ms_per_spp", r.shadow},
                    {"mrays_per_s", r.mrays_per_s},
                    {"spp", r.spp},
                    {"time_ms", r.time_ms},
                    {"rmse", r.rmse},
                    {"rmse_repeats", final_rmse},
                    {"rmse_at_budget", r.rmse_at_budget},
                    {"time_over_budget", r.time_over_budget},
                    {"rmse_vs_baseline", base_rmse > 0 ? r.rmse_at_budget / base_rmse : 0.0},
                    {"bias", r.bias}});
  }

  nlohmann::ordered_json sweep = nlohmann::ordered_json::array();
  if (a.sweep) {
    for (int tile : {8, 16, 32, 64}) {
      RenderSettings s = base;
      s.tile_size = tile;
      double ms = measure_ms_per_spp(scene, *accel, camera, s);
      fmt::print("sweep tile {:>5}: {:.2f} ms/spp\n", tile, ms);
      sweep.push_back({{"mode", "tile"}, {"size", tile}, {"ms_per_spp", ms}});
    }
    for (int batch : {256, 1024, 4096, 16384, 65536}) {
      RenderSettings s = base;
      s.quality.wavefront = true;
      s.quality.batch_size = batch;
      double ms = measure_ms_per_spp(scene, *accel, camera, s);
      fmt::print("sweep batch {:>5}: {:.2f} ms/spp\n", batch, ms);
      sweep.push_back({{"mode", "wavefront"}, {"size", batch}, {"ms_per_spp", ms}});
    }
  }
  return {{"scene", spec},
          {"name", scene.name},
          {"triangles", scene.triangles.size()},
          {"one_texel_candidates", texel_stats.candidates},
          {"one_texel_collapsed", texel_stats.collapsed},
          {"truth", truth_path},
          {"truth_spp", truth_info.rendered ? truth_info.spp : a.truth_spp},
          {"frame_ms", frame_ms},
          {"configs", rows},
          {"sweep", sweep}};
}

// One panel per scene (RMSE vs time, log y), a line per configuration: the data file's block
// index and the configuration's name.
struct PlotScene {
  std::string name;
  std::vector<std::pair<int, std::string>> lines;
};

void write_plot_script(const std::string& prefix, const std::vector<PlotScene>& scenes) {
  std::ofstream gp(prefix + ".gp");
  std::string data = std::filesystem::path(prefix + ".dat").filename().string();
  const int cols = scenes.size() > 1 ? 2 : 1;
  const int rows = static_cast<int>((scenes.size() + cols - 1) / cols);
  gp << "# gnuplot " << std::filesystem::path(prefix + ".gp").filename().string()
     << ": RMSE against the ground truth vs time, one panel per scene\n"
     << "set terminal pngcairo size " << 700 * cols << "," << 420 * rows << " font ',9'\n"
     << "set output '" << std::filesystem::path(prefix + ".png").filename().string() << "'\n"
     << "set multiplot layout " << rows << "," << cols << "\n"
     << "set xlabel 'time (ms)'\nset ylabel 'RMSE'\nset logscale y\nset key outside right\n";
  for (const PlotScene& scene : scenes) {
    gp << "set title '" << scene.name << "'\nplot ";
    for (size_t i = 0; i < scene.lines.size(); ++i)
      gp << (i ? ", \\\n     " : "") << "'" << data << "' index " << scene.lines[i].first
         << " using 1:2 with linespoints title '" << scene.lines[i].second << "'";
    gp << "\n";
  }
  gp << "unset multiplot\n";
}

// Markdown: one row per scene, one column per configuration, `config[field]` / the baseline's;
// a last row with the geometric mean over scenes.
void print_ratio_matrix(const std::string& title, const nlohmann::ordered_json& scenes,
                        const char* field) {
  std::vector<std::string> names;
  for (const auto& scene : scenes)
    for (const auto& c : scene["configs"]) {
      std::string n = c["config"];
      if (n != "baseline" && std::find(names.begin(), names.end(), n) == names.end())
        names.push_back(n);
    }
  if (names.empty()) return;
  fmt::print("\n{}\n\n| scene |", title);
  for (const std::string& n : names) fmt::print(" {} |", n);
  fmt::print("\n|---|");
  for (size_t i = 0; i < names.size(); ++i) fmt::print("---|");
  fmt::print("\n");
  std::vector<std::vector<double>> ratios(names.size());
  for (const auto& scene : scenes) {
    double base = 0;
    for (const auto& c : scene["configs"])
      if (c["config"] == "baseline") base = c[field].get<double>();
    fmt::print("| {} |", scene["name"].get<std::string>());
    for (size_t i = 0; i < names.size(); ++i) {
      std::string cell = " - |";
      for (const auto& c : scene["configs"]) {
        if (c["config"] != names[i] || !(base > 0)) continue;
        ratios[i].push_back(c[field].get<double>() / base);
        cell = fmt::format(" {:.2f} |", ratios[i].back());
      }
      fmt::print("{}", cell);
    }
    fmt::print("\n");
  }
  fmt::print("| geo-mean |");
  for (const std::vector<double>& r : ratios)
    fmt::print("{}", r.empty() ? " - |" : fmt::format(" {:.2f} |", geometric_mean(r)));
  fmt::print("\n");
}

}  // namespace

std::vector<std::string> bench_quality_configurations() {
  std::vector<std::string> names;
  for (const Config& c : configurations()) names.push_back(c.name);
  return names;
}

int run_bench_quality(const BenchQualityArgs& a) {
  const std::vector<std::string> known = bench_quality_configurations();
  for (const std::string& name : a.only)
    if (std::find(known.begin(), known.end(), name) == known.end()) {
      std::string list;
      for (const std::string& k : known) list += (list.empty() ? "" : ", ") + k;
      throw std::invalid_argument("bad --only '" + name + "': expected one of " + list);
    }
  std::vector<std::string> scenes = a.scenes;
  if (scenes.empty()) scenes = all_scene_json_files();
  if (scenes.empty()) throw std::invalid_argument("bench quality: no scenes given or found");
  nlohmann::ordered_json out = {{"size", a.size},
                                {"frame_ms", a.frame_ms},
                                {"frames", a.frames},
                                {"repeats", a.repeats},
                                {"target_spp", a.target_spp},
                                {"max_bounces", a.max_bounces},
                                {"clamp", a.clamp},
                                {"clamp_relative", a.clamp_relative},
                                {"truth_spp", a.truth_spp},
                                {"truth_until_rmse", a.truth_until_rmse},
                                {"threads", tbb::this_task_arena::max_concurrency()},
                                {"scenes", nlohmann::ordered_json::array()}};
  std::ofstream plot_data;
  if (!a.plot.empty()) {
    std::filesystem::path parent = std::filesystem::path(a.plot).parent_path();
    if (!parent.empty()) std::filesystem::create_directories(parent);
    plot_data.open(a.plot + ".dat");
  }
  auto write_json = [&] {  // after every scene, so an interrupted run keeps what it measured
    if (a.json.empty()) return;
    std::filesystem::path parent = std::filesystem::path(a.json).parent_path();
    if (!parent.empty()) std::filesystem::create_directories(parent);
    std::ofstream f(a.json);
    if (!(f << out.dump(2) << "\n")) throw std::runtime_error("cannot write " + a.json);
  };
  std::vector<PlotScene> panels;
  int block = 0;
  for (const std::string& spec : scenes) {
    const nlohmann::ordered_json& scene = out["scenes"].emplace_back(run_scene(a, spec, plot_data));
    plot_data << std::flush;
    PlotScene panel{scene["name"].get<std::string>(), {}};
    for (const auto& c : scene["configs"]) panel.lines.emplace_back(block++, c["config"]);
    panels.push_back(panel);
    write_json();
    fmt::print("\n");
  }
  if (!a.plot.empty()) write_plot_script(a.plot, panels);
  print_ratio_matrix("RMSE at equal time (frames x budget) / baseline's (median over repeats):",
                     out["scenes"], "rmse_at_budget");
  print_ratio_matrix("Time per spp / baseline's:", out["scenes"], "ms_per_spp");
  return 0;
}

}  // namespace tuneray
