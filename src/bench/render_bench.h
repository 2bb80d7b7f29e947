// `tuneray bench render`: whole-frame rendering speed per scene, and side by side in the same
// run Embree's own tutorial path tracer on its Cornell box (the reference most people know).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "accel/accel.h"
#include "render/film.h"
#include "render/sampler.h"
#include "render/tile_renderer.h"
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

// One scene ready to render with the options' backend, PCG samples and the default (wavefront)
// scheduler: built and warmed up (caches, page faults, TBB threads) on construction, then timed
// one pass at a time, so that a caller can interleave its passes with another program's frames.
// Throws std::invalid_argument on an unknown backend or parameter.
class TimedRenderer {
 public:
  TimedRenderer(const Scene& scene, const RenderBenchOptions& options);
  // The next `spp` samples per pixel (sample indices continue from the last pass).
  PassStats pass(int spp);
  std::string accel_description() const;  // the backend's name and configuration
  double build_ms() const { return build_.build_ms; }

 private:
  std::unique_ptr<Accel> accel_;
  BuildStats build_;
  PcgSampler sampler_;
  std::unique_ptr<TileRenderer> renderer_;
  Film film_;
  uint32_t next_sample_ = 0;
};

// A TimedRenderer's `repeats` passes of `spp` samples, medians.
RenderSpeed measure_render_speed(const std::string& name, const Scene& scene,
                                 const RenderBenchOptions& options, int spp);

// Our renderer and Embree's pathtracer on Embree's Cornell box, same camera, light, size, spp
// and path length, interleaved: each repeat times one pathtracer frame (after its own warm-up
// frame), then one pass of ours, so that both see the machine in the same state and a drifting
// host moves both sides of each repeat's ratio. `ok` false (with `error`) when the pathtracer or
// its scene is missing.
struct EmbreeComparison {
  bool ok = false;
  std::string error;
  int spp = 16;
  std::string our_accel;                              // TimedRenderer::accel_description()
  std::vector<double> our_frame_ms, embree_frame_ms;  // per repeat, in the order run
  double our_mrays = 0, embree_mrays = 0;  // medians; each program counts rays its own way
  // embree_frame_ms[r] / our_frame_ms[r]: above 1, we are faster.
  std::vector<double> speed_ratios() const;
  double speed_ratio() const;  // median of speed_ratios()
};
EmbreeComparison compare_with_embree(const RenderBenchOptions& options);

}  // namespace tuneray
