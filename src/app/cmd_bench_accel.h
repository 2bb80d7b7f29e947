// `tuneray bench traversal` and `tuneray bench build`: the tuned BVH against Embree's native BVH
// on the same rays (primary, incoherent bounce, shadow), all cores, median of repeats.
#pragma once

#include <string>
#include <vector>

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
};

int run_bench_traversal(const BenchAccelArgs& args);
int run_bench_build(const BenchAccelArgs& args);

}  // namespace tuneray
