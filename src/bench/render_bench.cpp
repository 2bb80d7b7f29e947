#include "bench/render_bench.h"

#include <fmt/core.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>

#include "accel/factory.h"
#include "bench/scene_paths.h"
#include "render/film.h"
#include "render/tile_renderer.h"
#include "scene/load.h"
#include "tuning/stats.h"

namespace tuneray {

namespace {

constexpr const char* kEmbreeCornell = "/usr/share/doc/embree3/models/cornell_box.obj";

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

std::vector<std::string> render_bench_scenes(const RenderBenchOptions& options) {
  if (!options.scenes.empty()) return options.scenes;
  std::vector<std::string> scenes = {"cornell"};
  if (!find_shared_scenes_dir(options.scenes_dir).empty())
    for (const std::string& f : shared_scene_json_files()) scenes.push_back(f);
  return scenes;
}

RenderSpeed measure_render_speed(const std::string& name, const Scene& scene,
                                 const RenderBenchOptions& a, int spp) {
  std::unique_ptr<Accel> accel = make_accel("native", "");
  BuildStats build = accel->build({scene.positions.data(), scene.positions.size(),
                                   scene.triangles.data(), scene.triangles.size()});
  RenderSettings settings;
  settings.width = a.width;
  settings.height = a.height;
  settings.max_bounces = a.max_bounces;
  PcgSampler sampler(1);
  TileRenderer renderer(scene, *accel, scene.cameras.at(0), settings, sampler);
  Film film(a.width, a.height);
  renderer.render_pass(film, 0, 1);  // warm-up: caches, page faults, TBB threads
  std::vector<double> ms, mrays;
  for (int r = 0; r < a.repeats; ++r) {
    PassStats p = renderer.render_pass(film, 1 + r * spp, spp);
    ms.push_back(p.render_ms / spp);
    mrays.push_back(p.mrays_per_s());
  }
  return {name, scene.triangles.size(), build.build_ms, median(ms), median(mrays)};
}

EmbreeComparison compare_with_embree(const RenderBenchOptions& a) {
  EmbreeComparison c;
  EmbreeReference ref = run_embree_pathtracer(a.width, a.height, c.spp, a.max_bounces, a.repeats);
  if (!std::filesystem::exists(kEmbreeCornell) || !ref.ok) {
    c.error = ref.error.empty() ? "scene missing" : ref.error;
    return c;
  }
  RenderSpeed ours = measure_render_speed("embree-cornell", embree_cornell_scene(), a, c.spp);
  c.ok = true;
  c.our_frame_ms = ours.ms_per_spp * c.spp;
  c.embree_frame_ms = 1000.0 / ref.fps;
  c.our_mrays = ours.mrays;
  c.embree_mrays = ref.mrays;
  return c;
}

}  // namespace tuneray
