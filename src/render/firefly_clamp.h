// Firefly clamp thresholds for one pass: a path sample whose indirect part is longer than its
// pixel's m is scaled to length m (PathIntegrator::finish).
#pragma once

#include <cstddef>
#include <vector>

#include "render/film.h"

namespace tuneray {

class ClampThresholds {
 public:
  ClampThresholds() = default;  // no clamp
  static ClampThresholds uniform(float m);
  // m_i = k x max(mean length of the pixel values in i's 3x3 neighbourhood, mean over the
  // image), from the pixels that have samples; no clamp while the film is empty. Relative to
  // the neighbourhood because a threshold from the whole image cuts real light where a scene's
  // dynamic range is high (surfaces next to small lamps); never below k x the image mean so
  // that dark regions, where fireflies show most, are still clamped.
  static ClampThresholds relative(const Film& film, float k);

  float at(size_t pixel) const { return per_pixel_.empty() ? uniform_ : per_pixel_[pixel]; }
  bool active() const { return uniform_ > 0 || !per_pixel_.empty(); }

 private:
  float uniform_ = 0;
  std::vector<float> per_pixel_;
};

}  // namespace tuneray
