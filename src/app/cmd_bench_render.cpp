// tuneray bench render: whole-frame rendering speed on real scenes, and side by side in the
// same run Embree's own tutorial path tracer on its Cornell box (the reference most people know).
#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>

#include "accel/factory.h"
#include "app/bench_commands.h"
#include "app/cli_parse.h"
#include "app/scene_paths.h"
#include "render/film.h"
#include "render/tile_renderer.h"
#include "scene/load.h"
#include "tuning/stats.h"

namespace tuneray {

namespace {

constexpr const char* kEmbreeCornell = "/usr/share/doc/embree3/models/cornell_box.obj";

struct SceneResult {
  std::string scene;
  size_t triangles = 0;
  double build_ms = 0;
  double ms_per_spp = 0;  // median over repeats
  double mrays = 0;       // closest-hit + shadow rays per second, at the median repeat
};

SceneResult bench_scene(const std::string& name, const Scene& scene, const BenchRenderArgs& a,
                        int width, int height, int spp, int max_bounces) {
  std::unique_ptr<Accel> accel = make_accel("native", "");
  BuildStats build = accel->build({scene.positions.data(), scene.positions.size(),
                                   scene.triangles.data(), scene.triangles.size()});
  RenderSettings settings;
  settings.width = width;
  settings.height = height;
  settings.max_bounces = max_bounces;
  PcgSampler sampler(1);
  TileRenderer renderer(scene, *accel, scene.cameras.at(0), settings, sampler);
  Film film(width, height);
  renderer.render_pass(film, 0, 1);  // warm-up: caches, page faults, TBB threads
  std::vector<double> ms, mrays;
  for (int r = 0; r < a.repeats; ++r) {
    PassStats p = renderer.render_pass(film, 1 + r * spp, spp);
    ms.push_back(p.render_ms / spp);
    mrays.push_back(p.mrays_per_s());
  }
  return {name, scene.triangles.size(), build.build_ms, median(ms), median(mrays)};
}

// Runs Embree's tutorial path tracer and reads its benchmark lines.
struct EmbreeReference {
  bool ok = false;
  double fps = 0, mrays = 0;
  std::string error;
};

EmbreeReference run_embree_pathtracer(int width, int height, int spp, int max_path_length,
                                      int repeats) {
  EmbreeReference ref;
  std::string ecs = "/usr/share/doc/embree3/models/cornell_box.ecs";
  if (!std::filesystem::exists(ecs) || !std::filesystem::exists("/usr/bin/pathtracer")) {
    ref.error = "Embree's pathtracer or " + ecs + " not installed (package embree-tools)";
    return ref;
  }
  std::string cmd = fmt::format(
      "/usr/bin/pathtracer -c {} --size {} {} --spp {} --max-path-length {} --benchmark 1 {} "
      "--legacy 2>&1",
      ecs, width, height, spp, max_path_length, repeats);
  FILE* pipe = popen(cmd.c_str(), "r");
  if (!pipe) {
    ref.error = "cannot run " + cmd;
    return ref;
  }
  std::string output;
  std::array<char, 512> buf;
  while (fgets(buf.data(), buf.size(), pipe)) output += buf.data();
  int status = pclose(pipe);
  // The lines look like "BENCHMARK_RENDER_AVG 1.0220".
  auto read_value = [&output](const std::string& key) {
    size_t at = output.find(key + " ");
    return at == std::string::npos ? 0.0 : std::atof(output.c_str() + at + key.size() + 1);
  };
  ref.fps = read_value("BENCHMARK_RENDER_AVG");
  ref.mrays = read_value("BENCHMARK_RENDER_MRAYPS_AVG");
  ref.ok = status == 0 && ref.fps > 0;
  if (!ref.ok) ref.error = "pathtracer failed: " + output.substr(0, 300);
  return ref;
}

// Embree's Cornell box as its pathtracer sees it: the .ecs point light and camera, and no
// emissive materials (its OBJ light material is not emissive there).
Scene embree_cornell_scene() {
  Scene scene = load_scene(kEmbreeCornell);
  for (Material& m : scene.materials) m.emission = Color(0.0f);
  scene.point_lights = {{Vec3f(213, 300, 227), Color(100000.0f)}};
  scene.environment = Environment{};
  CameraDesc cam;
  cam.position = {278, 273, -800};
  cam.target = {278, 273, 0};
  cam.up = {0, 1, 0};
  cam.vfov_deg = 37;
  scene.cameras = {cam};
  return scene;
}

}  // namespace

int run_bench_render(const BenchRenderArgs& a) {
  auto [width, height] = parse_size(a.size);
  std::vector<std::string> scenes = a.scenes;
  LoadOptions load_options;
  load_options.scenes_dir = find_shared_scenes_dir(a.scenes_dir);
  if (scenes.empty()) {
    scenes.push_back("cornell");
    if (!load_options.scenes_dir.empty())
      for (auto& f : shared_scene_json_files()) scenes.push_back(f);
  }
  nlohmann::json json = {{"size", a.size},
                         {"spp", a.spp},
                         {"repeats", a.repeats},
                         {"max_bounces", a.max_bounces},
                         {"scenes", nlohmann::json::array()}};
  fmt::print("{:<28} {:>10} {:>10} {:>11} {:>9}\n", "scene", "triangles", "build ms", "ms per spp",
             "Mrays/s");
  for (const std::string& spec : scenes) {
    Scene scene = load_scene(spec, load_options);
    std::string name = std::filesystem::path(spec).stem().string();
    SceneResult r = bench_scene(name, scene, a, width, height, a.spp, a.max_bounces);
    fmt::print("{:<28} {:>10} {:>10.1f} {:>11.2f} {:>9.2f}\n", r.scene, r.triangles, r.build_ms,
               r.ms_per_spp, r.mrays);
    json["scenes"].push_back({{"scene", r.scene},
                              {"triangles", r.triangles},
                              {"build_ms", r.build_ms},
                              {"ms_per_spp", r.ms_per_spp},
                              {"mrays_per_s", r.mrays}});
  }

  if (a.embree_reference) {
    constexpr int kRefSpp = 16;
    fmt::print(
        "\nEmbree's tutorial pathtracer, same scene/camera/size/spp/path length, same run:\n");
    EmbreeReference ref = run_embree_pathtracer(width, height, kRefSpp, a.max_bounces, a.repeats);
    if (!std::filesystem::exists(kEmbreeCornell) || !ref.ok) {
      fmt::print("  skipped: {}\n", ref.error.empty() ? "scene missing" : ref.error);
    } else {
      Scene scene = embree_cornell_scene();
      SceneResult ours =
          bench_scene("embree-cornell", scene, a, width, height, kRefSpp, a.max_bounces);
      double our_frame_ms = ours.ms_per_spp * kRefSpp;
      double ref_frame_ms = 1000.0 / ref.fps;
      fmt::print("  {:<12} {:>10} {:>12}\n", "", "frame ms", "Mrays/s*");
      fmt::print("  {:<12} {:>10.1f} {:>12.2f}\n", "tuneray", our_frame_ms, ours.mrays);
      fmt::print("  {:<12} {:>10.1f} {:>12.2f}\n", "embree", ref_frame_ms, ref.mrays);
      fmt::print("  speed ratio tuneray/embree (frame time) = {:.2f}\n",
                 ref_frame_ms / our_frame_ms);
      fmt::print("  * each program counts rays its own way; compare frame times.\n");
      json["embree_reference"] = {{"spp", kRefSpp},
                                  {"tuneray_frame_ms", our_frame_ms},
                                  {"embree_frame_ms", ref_frame_ms},
                                  {"tuneray_mrays", ours.mrays},
                                  {"embree_mrays", ref.mrays},
                                  {"speed_ratio", ref_frame_ms / our_frame_ms}};
    }
  }
  if (!a.json.empty()) {
    std::ofstream f(a.json);
    if (!(f << json.dump(2) << "\n")) throw std::runtime_error("cannot write " + a.json);
    fmt::print("wrote {}\n", a.json);
  }
  return 0;
}

}  // namespace tuneray
