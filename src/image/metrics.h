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

// A reference rendered from finitely many samples has an error of its own, and an image of
// independent samples compared with it reads E|x - ref|^2 = E|x - truth|^2 + E|ref - truth|^2.
// The reference's share, E|ref - truth|^2 (mean over pixels and channels), estimated from its two
// halves of equally many independent samples: E|half_a - half_b|^2 = 4 E|ref - truth|^2. Throws
// as compare_images does.
double reference_noise_mse(const Image& half_a, const Image& half_b);

// The RMSE against the truth behind a noisy reference: sqrt(max(0, rmse^2 - noise_mse)). Only for
// an image whose noise is independent of the reference's. Throws std::invalid_argument for a
// negative or non-finite argument.
double rmse_without_reference_noise(double rmse, double noise_mse);

}  // namespace tuneray
