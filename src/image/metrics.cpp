#include "image/metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace tuneray {

namespace {

std::string size_text(const Image& img) {
  return std::to_string(img.width()) + "x" + std::to_string(img.height());
}

void check_finite(const Image& img, const char* which) {
  for (int y = 0; y < img.height(); ++y) {
    for (int x = 0; x < img.width(); ++x) {
      if (!is_finite(img.at(x, y))) {
        throw std::invalid_argument(std::string(which) +
                                    " image has a non-finite value at pixel (" + std::to_string(x) +
                                    ", " + std::to_string(y) + ")");
      }
    }
  }
}

}  // namespace

ErrorMetrics compare_images(const Image& a, const Image& b) {
  if (a.width() != b.width() || a.height() != b.height()) {
    throw std::invalid_argument("image sizes differ: " + size_text(a) + " vs " + size_text(b));
  }
  if (a.empty()) throw std::invalid_argument("cannot compare empty images");
  check_finite(a, "first");
  check_finite(b, "second");

  double squared = 0, relative = 0, max_abs = 0;
  for (size_t i = 0; i < a.pixel_count(); ++i) {
    for (int k = 0; k < 3; ++k) {
      const double reference = b.data()[i][k];
      const double d = static_cast<double>(a.data()[i][k]) - reference;
      squared += d * d;
      relative += d * d / (reference * reference + 1e-2);
      max_abs = std::max(max_abs, std::abs(d));
    }
  }
  const double count = 3.0 * static_cast<double>(a.pixel_count());
  ErrorMetrics m;
  m.mse = squared / count;
  m.rmse = std::sqrt(m.mse);
  m.psnr = m.mse > 0 ? 10.0 * std::log10(1.0 / m.mse) : std::numeric_limits<double>::infinity();
  m.relmse = relative / count;
  m.max_abs = max_abs;
  return m;
}

double reference_noise_mse(const Image& half_a, const Image& half_b) {
  return compare_images(half_a, half_b).mse / 4.0;
}

double rmse_without_reference_noise(double rmse, double noise_mse) {
  if (!(rmse >= 0) || !(noise_mse >= 0) || !std::isfinite(rmse) || !std::isfinite(noise_mse))
    throw std::invalid_argument("rmse_without_reference_noise: needs finite non-negative values");
  return std::sqrt(std::max(0.0, rmse * rmse - noise_mse));
}

}  // namespace tuneray
