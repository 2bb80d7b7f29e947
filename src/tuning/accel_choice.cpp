#include "tuning/accel_choice.h"

#include <map>
#include <stdexcept>

#include "accel/factory.h"

namespace tuneray {

namespace {

BvhQuality parse_quality(const std::string& value) {
  if (value == "low") return BvhQuality::kLow;
  if (value == "medium") return BvhQuality::kMedium;
  if (value == "high") return BvhQuality::kHigh;
  throw std::invalid_argument("native backend: quality must be low, medium or high, got '" + value +
                              "'");
}

}  // namespace

const char* to_string(Backend backend) {
  return backend == Backend::kNative ? "native" : "tuned";
}

NativeOptions AccelChoice::native_options() const {
  NativeOptions o;
  o.quality = native_quality == BvhQuality::kLow    ? RTC_BUILD_QUALITY_LOW
              : native_quality == BvhQuality::kHigh ? RTC_BUILD_QUALITY_HIGH
                                                    : RTC_BUILD_QUALITY_MEDIUM;
  return o;
}

std::string AccelChoice::to_string() const {
  if (is_native())
    return std::string("backend=native,quality=") + tuneray::to_string(native_quality);
  return "backend=tuned," + bvh.to_string();
}

bool AccelChoice::operator==(const AccelChoice& other) const {
  if (backend != other.backend) return false;
  return is_native() ? native_quality == other.native_quality : bvh == other.bvh;
}

AccelChoice parse_accel_choice(const std::string& text) {
  std::map<std::string, std::string> kv = parse_key_values(text);
  std::string backend = "tuned";
  if (auto it = kv.find("backend"); it != kv.end()) {
    backend = it->second;
    kv.erase(it);
  }
  if (backend == "native") {
    AccelChoice choice = AccelChoice::native();
    for (const auto& [key, value] : kv) {
      if (key != "quality")
        throw std::invalid_argument("native backend: unknown parameter '" + key +
                                    "' (it takes only quality=low|medium|high)");
      choice.native_quality = parse_quality(value);
    }
    return choice;
  }
  if (backend != "tuned")
    throw std::invalid_argument("bad backend '" + backend + "': expected tuned or native");
  std::string rest;
  for (const auto& [key, value] : kv) rest += (rest.empty() ? "" : ",") + key + "=" + value;
  return AccelChoice::tuned(parse_bvh_config(rest));
}

}  // namespace tuneray
