// Which accelerator a frame is rendered with: our tuned BVH with its 11 build parameters, or
// Embree's own BVH with only its build quality to choose. The tuner picks among both
// (make_backend_space), so a tuning session can settle on native Embree where our trees lose,
// and the database records where they win. BvhConfig stays the tuned BVH's own type; this one
// only wraps it.
#pragma once

#include <string>

#include "accel/bvh_config.h"
#include "accel/embree_native.h"

namespace tuneray {

enum class Backend { kTuned, kNative };

const char* to_string(Backend backend);

struct AccelChoice {
  Backend backend = Backend::kTuned;
  BvhQuality native_quality = BvhQuality::kMedium;  // read only when native
  BvhConfig bvh;                                    // read only when tuned

  static AccelChoice tuned(const BvhConfig& bvh) {
    return {Backend::kTuned, BvhQuality::kMedium, bvh};
  }
  // Medium is what `render --accel native` builds.
  static AccelChoice native(BvhQuality quality = BvhQuality::kMedium) {
    return {Backend::kNative, quality, BvhConfig{}};
  }

  bool is_native() const { return backend == Backend::kNative; }
  // The options `render --accel native` uses, with this build quality.
  NativeOptions native_options() const;

  // `backend=native,quality=medium` or `backend=tuned,` followed by all 11 BVH parameters;
  // parse_accel_choice() reads it back.
  std::string to_string() const;

  // Equal when they build the same tree: the other backend's fields are ignored.
  bool operator==(const AccelChoice& other) const;
};

// Parses to_string()'s form. Without `backend=` the text is a tuned BVH configuration (the
// `--bvh` syntax); the native backend takes only `quality=low|medium|high`. Throws
// std::invalid_argument naming what is wrong.
AccelChoice parse_accel_choice(const std::string& text);

}  // namespace tuneray
