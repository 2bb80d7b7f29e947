// Embree's tutorial path tracer (package embree-tools) as the peer our renders are measured
// against: finding it, timing its frames with its --benchmark mode, rendering its images with
// -o, on its Cornell box (cornell_box.ecs).
#pragma once

#include <string>

#include "image/image.h"

namespace tuneray {

struct EmbreePeer {
  std::string binary = "/usr/bin/pathtracer";
  // Its scene file; load_scene reads it as the pathtracer does (scene/ecs_loader.cpp).
  std::string scene = "/usr/share/doc/embree3/models/cornell_box.ecs";
  int width = 320, height = 240;
  int max_path_length = 8;  // equals our max_bounces (the converged images agree at equal values)
};

// Why the peer cannot run (binary or scene missing), or an empty string when it can.
std::string embree_peer_missing(const EmbreePeer& peer);

struct EmbreePeerTiming {
  double frame_ms = 0;  // 1000 / BENCHMARK_RENDER_AVG: render time of one frame of `spp`
  double mrays = 0;     // BENCHMARK_RENDER_MRAYPS_AVG (the pathtracer counts rays its own way)
};

// Runs `--benchmark 1 frames` (one warm-up frame) with `spp` samples per pixel per frame.
// Throws std::runtime_error with the command's output when it fails.
EmbreePeerTiming embree_peer_benchmark(const EmbreePeer& peer, int spp, int frames);

// One frame of `spp` samples per pixel written with -o: the pathtracer's own output, clamped to
// [0,1] and quantised to 8 bits even in PFM. `path` must end in .pfm; it is written aside and
// renamed, so an interrupted render never leaves a partial file. Throws std::runtime_error.
void embree_peer_render(const EmbreePeer& peer, int spp, const std::string& path);

// The pathtracer's output transform on our linear image, for a like-for-like comparison:
// each channel clamped to [0,1], then floor(255.01 x) / 255.
Image embree_output_transform(const Image& linear);

}  // namespace tuneray
