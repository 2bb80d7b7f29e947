// Error of a rendered image against a reference, for equal-time quality comparisons.
#pragma once

#include "image/image.h"

namespace tuneray {

// All means run over pixels and channels alike: r, g and b are three separate values.
struct ErrorMetrics {
  double mse = 0;      // mean of (a - b)^2
  double rmse = 0;     // sqrt(mse)
  double psnr = 0;     // 10 log10(peak^2 / mse) with peak = 1.0 (linear white); +inf if equal
  double relmse = 0;   // mean of (a - b)^2 / (b^2 + 0.01): error relative to the reference b
  double max_abs = 0;  // largest |a - b|
};

// `b` is the reference. Throws std::invalid_argument naming both sizes when they differ, when
// the images are empty, or naming the pixel when either holds a NaN or infinity.
ErrorMetrics compare_images(const Image& a, const Image& b);

}  // namespace tuneray
