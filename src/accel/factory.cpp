#include "accel/factory.h"

#include <stdexcept>

#include "accel/embree_native.h"
#include "accel/tuned_bvh.h"

namespace tuneray {

namespace {
bool parse_bool(const std::string& key, const std::string& value) {
  if (value == "1" || value == "true" || value == "on" || value == "yes") return true;
  if (value == "0" || value == "false" || value == "off" || value == "no") return false;
  throw std::invalid_argument("parameter '" + key +
                              "': expected a boolean (0/1/true/false), got '" + value + "'");
}

NativeOptions parse_native_options(const std::map<std::string, std::string>& kv) {
  NativeOptions o;
  for (const auto& [key, value] : kv) {
    if (key == "quality") {
      if (value == "low")
        o.quality = RTC_BUILD_QUALITY_LOW;
      else if (value == "medium")
        o.quality = RTC_BUILD_QUALITY_MEDIUM;
      else if (value == "high")
        o.quality = RTC_BUILD_QUALITY_HIGH;
      else
        throw std::invalid_argument("parameter 'quality': expected low|medium|high, got '" + value +
                                    "'");
    } else if (key == "robust") {
      o.robust = parse_bool(key, value);
    } else if (key == "compact") {
      o.compact = parse_bool(key, value);
    } else if (key == "dynamic") {
      o.dynamic = parse_bool(key, value);
    } else if (key == "tri_accel") {
      o.tri_accel = value;  // checked with the rest by NativeOptions::problem() below
    } else if (key == "tri_builder") {
      o.tri_builder = value;
    } else {
      throw std::invalid_argument("unknown parameter '" + key +
                                  "' for the native backend; valid: quality=low|medium|high, "
                                  "robust=0|1, compact=0|1, dynamic=0|1, tri_accel=NAME, "
                                  "tri_builder=NAME");
    }
  }
  if (const std::string problem = o.problem(); !problem.empty())
    throw std::invalid_argument("native backend: " + problem);
  return o;
}
}  // namespace

std::map<std::string, std::string> parse_key_values(const std::string& text) {
  std::map<std::string, std::string> out;
  size_t pos = 0;
  while (pos < text.size()) {
    size_t end = text.find(',', pos);
    if (end == std::string::npos) end = text.size();
    std::string item = text.substr(pos, end - pos);
    pos = end + 1;
    if (item.empty()) continue;
    size_t eq = item.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == item.size())
      throw std::invalid_argument("malformed parameter '" + item + "' (expected key=value)");
    std::string key = item.substr(0, eq);
    if (!out.emplace(key, item.substr(eq + 1)).second)
      throw std::invalid_argument("parameter '" + key + "' given twice");
  }
  return out;
}

std::vector<std::string> accel_backend_names() {
  return {"native", "tuned"};
}

std::unique_ptr<Accel> make_accel(const std::string& backend, const std::string& params) {
  auto kv = parse_key_values(params);
  if (backend == "native") return std::make_unique<EmbreeNativeAccel>(parse_native_options(kv));
  if (backend == "tuned") return std::make_unique<TunedBvhAccel>(parse_bvh_config(params));
  std::string names;
  for (const auto& n : accel_backend_names()) names += (names.empty() ? "" : ", ") + n;
  throw std::invalid_argument("unknown accelerator '" + backend + "' (valid: " + names + ")");
}

}  // namespace tuneray
