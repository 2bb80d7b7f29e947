#include "render/denoiser_selection.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <stdexcept>
#include <string>

#include "render/denoiser_kernel.h"

namespace tuneray {

namespace {

constexpr size_t kMostLevels = 256;  // choices are bytes

void fail(const std::string& what) {
  throw std::invalid_argument("denoiser selection: " + what);
}

void check_levels(const std::vector<Image>& levels, int w, int h, const char* name) {
  if (levels.empty() || levels.size() > kMostLevels)
    fail(std::string(name) + " needs 1 to 256 levels");
  for (const Image& level : levels)
    if (level.width() != w || level.height() != h)
      fail(std::string(name) + ": a level differs in size from the halves");
}

double squared_distance(const Color& p, const Color& q) {
  const double dx = p.x - q.x, dy = p.y - q.y, dz = p.z - q.z;
  return dx * dx + dy * dy + dz * dz;
}

// Sums over the (2r+1)^2 window around each pixel (the part inside the image), in place.
void window_sums(std::vector<double>& v, int w, int h, int r) {
  std::vector<double> row(static_cast<size_t>(w));
  for (int y = 0; y < h; ++y) {
    double* line = v.data() + static_cast<size_t>(y) * w;
    double running = 0;
    for (int x = 0; x < std::min(r, w); ++x) running += line[x];
    for (int x = 0; x < w; ++x) {
      if (x + r < w) running += line[x + r];
      if (x - r - 1 >= 0) running -= line[x - r - 1];
      row[static_cast<size_t>(x)] = running;
    }
    std::copy(row.begin(), row.end(), line);
  }
  // Columns a whole row at a time (the same additions per column, in the same order): walking
  // each column down the image touched a new cache line at every step.
  std::vector<double> out(v.size()), running(static_cast<size_t>(w), 0.0);
  auto add_row = [&](int y, double sign) {
    const double* line = v.data() + static_cast<size_t>(y) * w;
    for (int x = 0; x < w; ++x) running[static_cast<size_t>(x)] += sign * line[x];
  };
  for (int y = 0; y < std::min(r, h); ++y) add_row(y, 1.0);
  for (int y = 0; y < h; ++y) {
    if (y + r < h) add_row(y + r, 1.0);
    if (y - r - 1 >= 0) add_row(y - r - 1, -1.0);
    std::copy(running.begin(), running.end(), out.begin() + static_cast<ptrdiff_t>(y) * w);
  }
  v.swap(out);
}

}  // namespace

NoisyImage noisy_half_image(const Film& film, int half) {
  if (half != 0 && half != 1) fail("a film has halves 0 and 1");
  const int w = film.width(), h = film.height();
  NoisyImage out{Image(w, h), std::vector<float>(static_cast<size_t>(w) * h, -1.0f),
                 std::vector<uint8_t>(static_cast<size_t>(w) * h, 0)};
  denoise_detail::for_rows(h, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y)
      for (int x = 0; x < w; ++x) {
        const size_t p = static_cast<size_t>(y) * w + x;
        const uint32_t n = film.samples(x, y), n_half = film.half_samples(half, x, y);
        if (n_half == 0) continue;
        out.color.at(x, y) = film.half_sum(half, x, y) / static_cast<float>(n_half);
        out.has_estimate[p] = 1;
        // variance_of_mean x n is the sample variance; over n_half samples it is this.
        if (n >= 2) out.variance[p] = static_cast<float>(film.variance_of_mean(x, y) * n / n_half);
      }
  });
  return out;
}

std::vector<uint8_t> select_levels(const std::vector<Image>& levels_a, const NoisyImage& a,
                                   const std::vector<Image>& levels_b, const NoisyImage& b,
                                   const SelectionParams& params) {
  const int w = a.color.width(), h = a.color.height();
  const size_t pixels = static_cast<size_t>(w) * h;
  if (b.color.width() != w || b.color.height() != h || a.has_estimate.size() != pixels ||
      b.has_estimate.size() != pixels)
    fail("the halves differ in size");
  check_levels(levels_a, w, h, "half A");
  check_levels(levels_b, w, h, "half B");
  if (levels_a.size() != levels_b.size()) fail("the halves have different numbers of levels");
  if (params.window_radius < 0) fail("the window radius must not be negative");
  const size_t levels = levels_a.size();

  // Per level, each pixel's cross-validation error (0 where a half has no estimate), summed
  // over its window; and how many pixels of the window count.
  std::vector<std::vector<double>> error(levels, std::vector<double>(pixels));
  std::vector<double> counted(pixels);
  for (size_t p = 0; p < pixels; ++p) counted[p] = a.has_estimate[p] && b.has_estimate[p];
  tbb::parallel_for(size_t{0}, levels, [&](size_t k) {
    const Color* fa = levels_a[k].data();
    const Color* fb = levels_b[k].data();
    const Color* ra = a.color.data();
    const Color* rb = b.color.data();
    std::vector<double>& e = error[k];
    for (size_t p = 0; p < pixels; ++p)
      e[p] = counted[p] > 0 ? squared_distance(fa[p], rb[p]) + squared_distance(fb[p], ra[p]) : 0;
    window_sums(e, w, h, params.window_radius);
  });
  window_sums(counted, w, h, params.window_radius);

  std::vector<uint8_t> choice(pixels);
  denoise_detail::for_pixels(w, h, [&](size_t p) {
    if (counted[p] <= 0) {
      choice[p] = static_cast<uint8_t>(levels - 1);
      return;
    }
    size_t best = 0;
    for (size_t k = 1; k < levels; ++k)
      if (error[k][p] < error[best][p]) best = k;
    choice[p] = static_cast<uint8_t>(best);
  });
  return choice;
}

Image compose_levels(const std::vector<Image>& levels, const std::vector<uint8_t>& choice,
                     int first) {
  if (levels.empty()) fail("no levels to compose");
  const int w = levels[0].width(), h = levels[0].height();
  check_levels(levels, w, h, "compose");
  if (choice.size() != static_cast<size_t>(w) * h) fail("the choice differs in size");
  Image out(w, h);
  if (choice.empty()) return out;
  const auto [lowest, highest] = std::minmax_element(choice.begin(), choice.end());
  for (const int k : {int{*lowest}, int{*highest}})
    if (k < first || k - first >= static_cast<int>(levels.size()))
      fail("level " + std::to_string(k) + " was not computed");
  denoise_detail::for_pixels(w, h, [&](size_t p) {
    out.data()[p] = levels[static_cast<size_t>(choice[p] - first)].data()[p];
  });
  return out;
}

std::vector<uint8_t> choose_strength(const NoisyImage& half_a, const NoisyImage& half_b,
                                     const DenoiseFeatures& features, const DenoiseParams& params,
                                     const SelectionParams& selection, const GuideWeights* guides) {
  return select_levels(denoise_levels(half_a, features, params, 0, guides), half_a,
                       denoise_levels(half_b, features, params, 0, guides), half_b, selection);
}

Image denoise_cross_validated(const NoisyImage& full, const NoisyImage& half_a,
                              const NoisyImage& half_b, const DenoiseFeatures& features,
                              const DenoiseParams& params, const SelectionParams& selection) {
  return denoise_chosen(full, features, params,
                        choose_strength(half_a, half_b, features, params, selection));
}

}  // namespace tuneray
