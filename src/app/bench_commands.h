// `tuneray bench ...` subcommands.
#pragma once

#include <string>
#include <vector>

namespace tuneray {

struct BenchRenderArgs {
  std::vector<std::string> scenes;  // empty: cornell + every shared scene found
  std::string size = "640x360";
  int spp = 4;
  int repeats = 5;
  int max_bounces = 3;
  bool embree_reference = true;
  std::string json;
  std::string scenes_dir;
};

int run_bench_render(const BenchRenderArgs& args);

}  // namespace tuneray
