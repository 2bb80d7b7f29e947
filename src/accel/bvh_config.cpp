#include "accel/bvh_config.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

#include "accel/factory.h"

namespace tuneray {

namespace {
constexpr float kMaxCost = 20.0f;

[[noreturn]] void reject(const std::string& what) {
  throw std::invalid_argument("--bvh: " + what + "\nvalid parameters:\n" + bvh_config_ranges());
}

int parse_int(const std::string& key, const std::string& value) {
  size_t used = 0;
  int out = 0;
  try {
    out = std::stoi(value, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != value.size())
    reject("parameter '" + key + "': expected an integer, got '" + value + "'");
  return out;
}

float parse_float(const std::string& key, const std::string& value) {
  size_t used = 0;
  float out = 0;
  try {
    out = std::stof(value, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != value.size() || !std::isfinite(out))
    reject("parameter '" + key + "': expected a number, got '" + value + "'");
  return out;
}

bool parse_flag(const std::string& key, const std::string& value) {
  if (value == "1" || value == "true" || value == "on" || value == "yes") return true;
  if (value == "0" || value == "false" || value == "off" || value == "no") return false;
  reject("parameter '" + key + "': expected 0/1/true/false, got '" + value + "'");
}

void check_range(const char* key, int value, int lo, int hi) {
  if (value < lo || value > hi)
    reject(std::string("parameter '") + key + "' = " + std::to_string(value) + " is outside " +
           std::to_string(lo) + ".." + std::to_string(hi));
}

// The shortest %g text that reads back as the same float: "1" for 1, but all the digits of
// 1.000002 (six significant digits alone printed it as "1": found by fuzz/fuzz_config_text).
std::string format_float(float f) {
  char buffer[32];
  for (int digits = 6; digits <= 9; ++digits) {
    std::snprintf(buffer, sizeof(buffer), "%.*g", digits, static_cast<double>(f));
    if (std::strtof(buffer, nullptr) == f) break;
  }
  return buffer;
}
}  // namespace

const char* to_string(BvhQuality quality) {
  switch (quality) {
    case BvhQuality::kLow:
      return "low";
    case BvhQuality::kHigh:
      return "high";
    default:
      return "medium";
  }
}

std::string bvh_config_ranges() {
  return "  quality=low|medium|high (default medium)\n"
         "  branching=2|4|8 (default 2)\n"
         "  max_depth=8..64 (default 32)\n"
         "  sah_block_size=1|2|4|8|16 (default 1)\n"
         "  min_leaf=1..32 (default 1)\n"
         "  max_leaf=1..32 (default 32; min_leaf > max_leaf lowers min_leaf)\n"
         "  trav_cost=(0,20] (default 1)\n"
         "  int_cost=(0,20] (default 1)\n"
         "  cost_ratio=[0.05,20] (sets trav_cost=ratio, int_cost=1)\n"
         "  static=0|1 (default 0)\n"
         "  compact=0|1 (default 0)\n"
         "  robust=0|1 (default 0)\n"
         "  collapse=0|1 (default 1; branching 2 or 4 stored as 8-wide nodes)\n"
         "  optimal_collapse=0|1 (default 0; the collapse's wide nodes chosen by an SAH-optimal "
         "plan)\n"
         "  reinsert=0|1 (default 0; branching 2 optimised by subtree reinsertion)\n"
         "  ray_weight=[0,1] (default 0; reinsertion and optimal collapse price boxes by a "
         "view's sampled rays)";
}

void BvhConfig::set_cost_ratio(float ratio) {
  trav_cost = std::clamp(ratio, 1.0f / kMaxCost, kMaxCost);
  int_cost = 1.0f;
}

std::string BvhConfig::validate() {
  if (branching != 2 && branching != 4 && branching != 8)
    reject("parameter 'branching' = " + std::to_string(branching) + " is not one of 2, 4, 8");
  check_range("max_depth", max_depth, 8, 64);
  if (sah_block_size < 1 || sah_block_size > 16 || (sah_block_size & (sah_block_size - 1)) != 0)
    reject("parameter 'sah_block_size' = " + std::to_string(sah_block_size) +
           " is not one of 1, 2, 4, 8, 16");
  check_range("min_leaf", min_leaf, 1, 32);
  check_range("max_leaf", max_leaf, 1, 32);
  for (auto [key, cost] : {std::pair{"trav_cost", trav_cost}, std::pair{"int_cost", int_cost}}) {
    if (!(cost > 0.0f && cost <= kMaxCost))
      reject(std::string("parameter '") + key + "' = " + format_float(cost) +
             " is outside (0, 20]");
  }
  if (!(ray_weight >= 0.0f && ray_weight <= 1.0f))
    reject("parameter 'ray_weight' = " + format_float(ray_weight) + " is outside [0, 1]");
  if (min_leaf > max_leaf) {
    std::string note = "min_leaf " + std::to_string(min_leaf) + " > max_leaf " +
                       std::to_string(max_leaf) + ": min_leaf lowered to " +
                       std::to_string(max_leaf);
    min_leaf = max_leaf;
    return note;
  }
  return {};
}

std::string BvhConfig::to_string() const {
  return std::string("quality=") + tuneray::to_string(quality) +
         ",branching=" + std::to_string(branching) + ",max_depth=" + std::to_string(max_depth) +
         ",sah_block_size=" + std::to_string(sah_block_size) +
         ",min_leaf=" + std::to_string(min_leaf) + ",max_leaf=" + std::to_string(max_leaf) +
         ",trav_cost=" + format_float(trav_cost) + ",int_cost=" + format_float(int_cost) +
         ",static=" + (is_static ? "1" : "0") + ",compact=" + (compact ? "1" : "0") +
         ",robust=" + (robust ? "1" : "0") + ",collapse=" + (collapse ? "1" : "0") +
         ",optimal_collapse=" + (optimal_collapse ? "1" : "0") +
         ",reinsert=" + (reinsert ? "1" : "0") +
         (ray_weight != 0.0f ? ",ray_weight=" + format_float(ray_weight) : std::string());
}

BvhConfig parse_bvh_config(const std::string& text) {
  std::map<std::string, std::string> kv;
  try {
    kv = parse_key_values(text);
  } catch (const std::invalid_argument& e) {
    reject(e.what());
  }
  BvhConfig c;
  bool explicit_costs = false;
  for (const auto& [key, value] : kv) {
    if (key == "quality") {
      if (value == "low")
        c.quality = BvhQuality::kLow;
      else if (value == "medium")
        c.quality = BvhQuality::kMedium;
      else if (value == "high")
        c.quality = BvhQuality::kHigh;
      else
        reject("parameter 'quality': expected low|medium|high, got '" + value + "'");
    } else if (key == "branching") {
      c.branching = parse_int(key, value);
    } else if (key == "max_depth") {
      c.max_depth = parse_int(key, value);
    } else if (key == "sah_block_size") {
      c.sah_block_size = parse_int(key, value);
    } else if (key == "min_leaf") {
      c.min_leaf = parse_int(key, value);
    } else if (key == "max_leaf") {
      c.max_leaf = parse_int(key, value);
    } else if (key == "trav_cost") {
      c.trav_cost = parse_float(key, value);
      explicit_costs = true;
    } else if (key == "int_cost") {
      c.int_cost = parse_float(key, value);
      explicit_costs = true;
    } else if (key == "cost_ratio") {
      float ratio = parse_float(key, value);
      if (!(ratio >= 1.0f / kMaxCost && ratio <= kMaxCost))
        reject("parameter 'cost_ratio' = " + value + " is outside [0.05, 20]");
      c.set_cost_ratio(ratio);
    } else if (key == "static") {
      c.is_static = parse_flag(key, value);
    } else if (key == "compact") {
      c.compact = parse_flag(key, value);
    } else if (key == "robust") {
      c.robust = parse_flag(key, value);
    } else if (key == "collapse") {
      c.collapse = parse_flag(key, value);
    } else if (key == "optimal_collapse") {
      c.optimal_collapse = parse_flag(key, value);
    } else if (key == "reinsert") {
      c.reinsert = parse_flag(key, value);
    } else if (key == "ray_weight") {
      c.ray_weight = parse_float(key, value);
    } else {
      reject("unknown parameter '" + key + "'");
    }
  }
  if (explicit_costs && kv.count("cost_ratio"))
    reject("give either cost_ratio or trav_cost/int_cost, not both");
  c.validate();
  return c;
}

}  // namespace tuneray
