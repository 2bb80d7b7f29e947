// `tuneray bench traversal` and `tuneray bench build`: the tuned BVH against Embree's native BVH
// on the same rays (primary, incoherent bounce, shadow), all cores, median of repeats; then
// (traversal) a rendered frame, native against the best configuration found
// (tuning/render_vs_native.h).
#pragma once

#include <string>
#include <vector>

#include "render/render_settings.h"

namespace tuneray {

struct BenchAccelArgs {
  std::vector<std::string> scenes;  // scene specs; empty: every shared scene found
  std::string scenes_dir;           // where the shared scenes live (empty: search)
  size_t rays = 200000;             // per ray set
  std::string bvh;                  // tuned configuration (`--bvh`); empty: defaults
  bool sweep = true;                // also run the small sweep (branching 4/8, leaf sizes, high)
  std::string json;                 // write results here when not empty
  int repeats = 5;                  // median of this many timings (>= 1)
  int threads = 0;                  // 0: all cores
  bool cpu_time = false;            // process CPU time instead of wall time
  // The render-level run of `bench traversal` (defaults: tune's, so a --db it wrote matches).
  bool render = true;
  std::string size = "320x180";
  uint32_t spp = 1;
  std::string scheduler = QualityOptions{}.wavefront ? "wavefront" : "tile";
  std::string db;  // the configuration to render: the database's best; empty: the table's best
};

int run_bench_traversal(const BenchAccelArgs& args);
int run_bench_build(const BenchAccelArgs& args);

}  // namespace tuneray
