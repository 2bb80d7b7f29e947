#include "render/blue_noise_error.h"

#include <cmath>
#include <complex>
#include <numbers>

#include "math/rng.h"

namespace tuneray::blue_noise {

namespace {
double half_plane_integral(const HalfPlane& f) {
  constexpr int kGrid = 1024;
  int64_t inside = 0;
  for (int i = 0; i < kGrid; ++i)
    for (int j = 0; j < kGrid; ++j) {
      float x = (i + 0.5f) / kGrid, y = (j + 0.5f) / kGrid;
      inside += f.nx * x + f.ny * y < f.c;
    }
  return static_cast<double>(inside) / (static_cast<double>(kGrid) * kGrid);
}
}  // namespace

std::vector<HalfPlane> random_half_planes(uint64_t seed, int count) {
  Pcg32 rng(mix_seed(seed), 3);
  std::vector<HalfPlane> out;
  for (int i = 0; i < count; ++i) {
    HalfPlane f;
    int pair = i % 2;  // alternate between the quadruple's two pairs
    f.a = 2 * pair;
    f.b = 2 * pair + 1;
    float angle = 2.0f * 3.14159265f * rng.next_float();
    f.nx = std::cos(angle);
    f.ny = std::sin(angle);
    // Through a random point of the middle of the square, so the integral is not tiny.
    float px = 0.2f + 0.6f * rng.next_float(), py = 0.2f + 0.6f * rng.next_float();
    f.c = f.nx * px + f.ny * py;
    f.integral = half_plane_integral(f);
    out.push_back(f);
  }
  return out;
}

float pixel_error(const BlueNoiseTables& tables, const PixelKeys& keys, int q, uint32_t spp,
                  const HalfPlane& f) {
  int inside = 0;
  for (uint32_t i = 0; i < spp; ++i) {
    float x = bits_to_unit_float(BlueNoiseTables::value_bits(tables, keys, i, 4 * q + f.a));
    float y = bits_to_unit_float(BlueNoiseTables::value_bits(tables, keys, i, 4 * q + f.b));
    inside += f.nx * x + f.ny * y < f.c;
  }
  return static_cast<float>(inside / static_cast<double>(spp) - f.integral);
}

std::vector<float> error_image(const BlueNoiseTables& tables, int q, uint32_t spp,
                               const HalfPlane& f) {
  std::vector<float> img(kTilePixels);
  for (int y = 0; y < kTileSize; ++y)
    for (int x = 0; x < kTileSize; ++x)
      img[y * kTileSize + x] = pixel_error(tables, tables.keys(x, y), q, spp, f);
  return img;
}

double low_frequency_share(const std::vector<float>& image) {
  const int n = kTileSize;
  double mean = 0;
  for (float v : image) mean += v;
  mean /= image.size();
  // Separable DFT: rows, then columns (n^3 work).
  std::vector<std::complex<double>> twiddle(n), a(static_cast<size_t>(n) * n), b(a.size());
  for (int k = 0; k < n; ++k) twiddle[k] = std::polar(1.0, -2.0 * std::numbers::pi * k / n);
  for (int y = 0; y < n; ++y)
    for (int k = 0; k < n; ++k) {
      std::complex<double> s = 0;
      for (int x = 0; x < n; ++x) s += (image[y * n + x] - mean) * twiddle[(k * x) % n];
      a[y * n + k] = s;
    }
  for (int kx = 0; kx < n; ++kx)
    for (int ky = 0; ky < n; ++ky) {
      std::complex<double> s = 0;
      for (int y = 0; y < n; ++y) s += a[y * n + kx] * twiddle[(ky * y) % n];
      b[ky * n + kx] = s;
    }
  double low = 0, total = 0;
  const double radius = n / 8.0;
  for (int ky = 0; ky < n; ++ky)
    for (int kx = 0; kx < n; ++kx) {
      int fx = kx <= n / 2 ? kx : kx - n, fy = ky <= n / 2 ? ky : ky - n;
      double p = std::norm(b[ky * n + kx]);
      total += p;
      if (fx * fx + fy * fy < radius * radius) low += p;
    }
  return total > 0 ? low / total : 0.0;
}

}  // namespace tuneray::blue_noise
