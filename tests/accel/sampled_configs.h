// A sample of configurations covering every quality, every branching factor, compact on/off,
// robust on/off, static on/off, collapse on/off (greedy or by the SAH-optimal plan), reinsert
// on/off, extreme leaf sizes and cost ratios.
#pragma once

#include <string>
#include <vector>

namespace tuneray::test {

inline std::vector<std::string> sampled_configs() {
  return {
      "",
      "quality=low,branching=4",
      "quality=low,branching=8,min_leaf=8,max_leaf=8",
      "quality=high,branching=2",
      "quality=high,branching=8,max_leaf=1",
      "quality=high,branching=4,compact=1,robust=1",
      "branching=4,compact=1",
      "branching=8,compact=1,robust=1",
      "branching=2,robust=1,static=1",
      "branching=8,max_leaf=1",
      "branching=8,min_leaf=8,max_leaf=32,sah_block_size=16",
      "branching=4,static=1,max_leaf=4",
      "branching=8,static=1,compact=1",
      "branching=8,cost_ratio=20",
      "branching=8,cost_ratio=0.05,max_depth=64",
      "branching=2,compact=1,min_leaf=4",
      "branching=2,collapse=1",
      "quality=high,branching=4,collapse=1,static=1",
      "branching=2,compact=1,robust=1,collapse=1",
      "branching=2,sah_block_size=4,min_leaf=4,max_leaf=28,reinsert=1",
      "quality=high,branching=2,reinsert=1,static=1",
      "branching=2,compact=1,robust=1,collapse=0,reinsert=1",
      "branching=2,sah_block_size=4,min_leaf=4,max_leaf=28,reinsert=1,optimal_collapse=1",
      "branching=4,optimal_collapse=1",
      "quality=high,branching=2,compact=1,optimal_collapse=1",
  };
}

}  // namespace tuneray::test
