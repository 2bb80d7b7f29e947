// An edge-avoiding à-trous wavelet filter (Dammertz et al., "Edge-Avoiding À-Trous Wavelet
// Transform for fast Global Illumination Filtering", HPG 2010) with the variance guidance of
// SVGF (Schied et al., HPG 2017): iterations of a 5x5 B3-spline kernel whose taps spread
// 1, 2, 4, ... pixels apart, each tap weighted down where the first-hit normal, albedo, direct
// light's visibility or plane differs or where the luminance differs by more than the noise
// explains. The noise level is the pixel's variance of its mean, filtered along with the
// image. Each iteration fits a plane to its weighted taps (local linear regression in screen
// space, as in Bitterli et al.'s first-order regression, with the pixel offset as the only
// feature) instead of taking their mean. The filter works on the image divided by the albedo
// (the light arriving at the surface), so textures stay sharp.
// Biased (it trades noise for blur); QualityOptions::denoise switches it on.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "image/image.h"
#include "render/denoiser_features.h"
#include "render/film.h"

namespace tuneray {

struct DenoiseParams {
  // Kernel taps 1, 2, 4, ..., 2^(iterations-1) pixels apart. 4 since the twenty-seventh session
  // (5 before): a fifth of each filtering and choice saved outweighs the widest level at equal
  // time in `bench quality` and `bench peers` (docs/quality.md).
  int iterations = 4;
  float sigma_luminance = 4;  // luminance difference allowed, in standard deviations
  int normal_squarings = 7;   // normal weight max(0, n.n')^(2^this): 128 as in SVGF
  float sigma_albedo = 0.1f;  // RGB distance at which the albedo weight is 1/e
  // Direct-light visibility difference at which its weight is 1/e when the guide is noise-free;
  // the guide's own noise (this many standard deviations of both pixels) widens it, since in
  // soft shadows a pixel's few light samples make visibility noisy.
  float sigma_visibility = 0.2f;
  float visibility_noise_deviations = 4.0f;
  // How far a tap's surface point may lie off the centre's tangent plane, as the sine of the
  // angle between the plane and the line joining them, for a weight of 1/e: 0 on one plane,
  // about 1 across a step in depth (a box's face before a wall, which albedo and normal miss).
  float sigma_plane = 0.5f;
  // Each iteration fits a plane in screen space to its weighted taps (local linear regression)
  // rather than taking their mean: where the weights are one-sided (at an edge) a mean is
  // pulled towards the side the taps lie on whenever the light has a gradient.
  bool first_order = true;
  // Added to the slope terms' moments, times the sum of weights: keeps the fit from
  // extrapolating a slope out of two or three taps.
  float slope_ridge = 0.1f;
  // The fit's correction over the mean, c, is kept in the share c^2 / (c^2 + this x var(c)):
  // where the slope is lost in the noise, the mean is the better estimate. 0: always the fit.
  float first_order_shrinkage = 1.0f;
};

// The filter's input: an estimate per pixel and how noisy it is.
struct NoisyImage {
  Image color;
  // Variance of each pixel's estimate (of its mean over samples, r, g and b averaged); < 0:
  // unknown (under 2 samples), then estimated from the 3x3 neighbourhood's spread.
  std::vector<float> variance;
  std::vector<uint8_t> has_estimate;  // 0: no samples yet; the filter fills it from neighbours
};

// The film's current estimate and its per-pixel variance of the mean.
NoisyImage noisy_image(const Film& film);

// The guides' share of the filter's weights (the kernel, normal, albedo, visibility and plane
// terms) for every pixel, tap and iteration, as half floats. It depends only on the features and
// the parameters, so the frames of one view can share it (FrameResolver keeps one) and each
// filtering computes only the luminance term: 50 bytes per pixel and iteration.
class GuideWeights {
 public:
  // For params.iterations iterations. Throws std::invalid_argument as denoise does for bad
  // features or parameters.
  GuideWeights(const DenoiseFeatures& features, const DenoiseParams& params);
  static size_t bytes_for(int width, int height, int iterations);
  // Whether it serves a filter of this size and these parameters (no more iterations, the same
  // guide terms).
  bool fits(int width, int height, const DenoiseParams& params) const;
  // Iteration i's weights, in the filter's internal layout.
  const uint16_t* table(int iteration) const;

 private:
  int width_, height_;
  DenoiseParams params_;
  std::vector<uint16_t> halves_;
};

// The filtered image, with `guides` when given (it must fit the image and parameters). Throws
// std::invalid_argument when the sizes disagree or `guides` does not fit.
Image denoise(const NoisyImage& in, const DenoiseFeatures& features,
              const DenoiseParams& params = {}, const GuideWeights* guides = nullptr);

// The image after 0 (the input), 1, ..., params.iterations iterations: filters of rising
// strength (each iteration doubles the reach) for the price of the strongest. Only levels from
// `first_kept` on are returned (the strongest alone when first_kept = iterations). Throws as
// denoise does.
std::vector<Image> denoise_levels(const NoisyImage& in, const DenoiseFeatures& features,
                                  const DenoiseParams& params, int first_kept = 0,
                                  const GuideWeights* guides = nullptr);

// The image filtered per pixel to the strength `choice` names (0: the input, up to
// params.iterations), the filter run only to the strongest chosen; each level's pixels are
// written as the level is made, so no level is kept (render/denoiser_selection.h chooses).
// Throws std::invalid_argument as denoise does, and when the choice differs in size from the
// image or names a strength beyond the iterations.
Image denoise_chosen(const NoisyImage& in, const DenoiseFeatures& features,
                     const DenoiseParams& params, const std::vector<uint8_t>& choice,
                     const GuideWeights* guides = nullptr);

}  // namespace tuneray
