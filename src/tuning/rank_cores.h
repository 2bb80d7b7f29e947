// Cores for the ranks that share one node. mpirun starts ranks on one machine as processes
// that would each use every core, so two measuring ranks would time each other's threads: each
// measuring rank gets its own slice of the node's cores instead. Rank 0 only coordinates (it
// waits without spinning) and gets no slice of its own.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace tuneray {

// Splits `cores` into contiguous disjoint slices, one per measuring rank of `node_ranks` (world
// ranks on this node; rank 0 is left out). More measuring ranks than cores: each gets one core,
// shared round-robin (describe says so).
std::map<int, std::vector<int>> split_node_cores(const std::vector<int>& node_ranks,
                                                 const std::vector<int>& cores);

// "2 ranks on this node share 2 cores: rank 0 coordinates (no core of its own), rank 1 on cores
// 0-1".
std::string describe_node_cores(const std::vector<int>& node_ranks, const std::vector<int>& cores,
                                const std::map<int, std::vector<int>>& split);

// "0-3,6" for {0,1,2,3,6}.
std::string core_list_text(const std::vector<int>& cores);

// The cores this process may run on (sched_getaffinity), ascending.
std::vector<int> process_cores();
// Restricts this process to `cores`; throws std::runtime_error naming the reason.
void pin_process(const std::vector<int>& cores);

}  // namespace tuneray
