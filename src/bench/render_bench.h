// `tuneray bench render`: whole-frame rendering speed per scene, and side by side in the same
// run Embree's own tutorial path tracer on its Cornell box (the reference most people know).
#pragma once

#include <string>
#include <vector>

#include "scene/scene.h"

namespace tuneray {

struct RenderBenchOptions {
  std::vector<std::string> scenes;  // empty: cornell + every shared scene found
  int width = 640, height = 360;
  int spp = 4;
  int repeats = 5;
  int max_bounces = 3;
  // Our backend and its parameters, as `render --accel/--bvh` take them; native is the render
  // command's default.
  std::string accel = "native";
  std::string bvh;
  bool embree_reference = true;
  std::string json;
  std::string scenes_dir;
};

// The scenes to run: the given ones, or cornell and every shared JSON scene when none is given.
std::vector<std::string> render_bench_scenes(const RenderBenchOptions& options);

struct RenderSpeed {
  std::string scene;
  std::string accel;  // the backend's name and configuration as it describes itself
  size_t triangles = 0;
  double build_ms = 0;
  double ms_per_spp = 0;  // median over repeats
  double mrays = 0;       // closest-hit + shadow rays per second, median over repeats
};

// The options' backend, PCG samples, the default (wavefront) scheduler: one warm-up pass, then
// `repeats` passes of `spp` samples. Throws std::invalid_argument on an unknown backend or
// parameter.
RenderSpeed measure_render_speed(const std::string& name, const Scene& scene,
                                 const RenderBenchOptions& options, int spp);

// Our renderer and Embree's pathtracer on Embree's Cornell box, same camera, light, size, spp
// and path length; `ok` false (with `error`) when the pathtracer or its scene is missing.
struct EmbreeComparison {
  bool ok = false;
  std::string error;
  int spp = 16;
  std::string our_accel;  // RenderSpeed::accel of our run
  double our_frame_ms = 0, embree_frame_ms = 0;
  double our_mrays = 0, embree_mrays = 0;  // each program counts rays its own way
  double speed_ratio() const { return embree_frame_ms / our_frame_ms; }
};
EmbreeComparison compare_with_embree(const RenderBenchOptions& options);

}  // namespace tuneray
