// The build statistics as the traversal and build reports write them.
#pragma once

#include <nlohmann/json.hpp>

#include "accel/accel.h"

namespace tuneray {

inline nlohmann::json build_stats_json(const BuildStats& s) {
  return {{"build_ms", s.build_ms},
          {"memory_bytes", s.memory_bytes},
          {"node_count", s.node_count},
          {"leaf_count", s.leaf_count},
          {"depth", s.depth},
          {"sah_cost", s.sah_cost},
          {"notes", s.notes}};
}

}  // namespace tuneray
