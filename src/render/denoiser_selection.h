// How strongly to filter, chosen per pixel by cross-validation between the two half films
// (Rousselle et al., "Adaptive Rendering with Non-Local Means Filtering", 2012; Bitterli et
// al., "Nonlinearly Weighted First-order Regression for Denoising Monte Carlo Renderings",
// 2016). The halves A and B hold independent samples of the same pixels, so
// E|filter(A) - B|^2 = MSE(filter(A)) + var(B): between two strengths, the difference of these
// errors estimates the difference of their MSE without knowing the true image. A fixed strength
// keeps its bias while the noise falls; the chosen one weakens as the samples grow, so the
// filter's bias falls with the noise.
#pragma once

#include <cstdint>
#include <vector>

#include "image/image.h"
#include "render/denoiser.h"
#include "render/denoiser_features.h"
#include "render/film.h"

namespace tuneray {

struct SelectionParams {
  // The per-pixel error estimates are summed over (2r+1)^2 pixels before choosing: one pixel's
  // estimate is as noisy as the pixel itself.
  int window_radius = 6;
};

// One half film (0: even sample indices, 1: odd) as the filter's input. Its variance of the
// mean comes from the whole pixel's sample variance (twice the samples, a steadier estimate)
// over the half's count.
NoisyImage noisy_half_image(const Film& film, int half);

// Per pixel, the index k of the level (levels_a[k]: half A filtered to strength k, likewise B)
// whose windowed cross-validation error sum |levels_a[k] - B|^2 + |levels_b[k] - A|^2 is lowest;
// ties go to the weaker level. Pixels where either half has no estimate add nothing; where the
// whole window has none, the strongest level is chosen (what the filter alone would show).
// Throws std::invalid_argument when the sizes or level counts disagree or a level count is
// outside [1, 256].
std::vector<uint8_t> select_levels(const std::vector<Image>& levels_a, const NoisyImage& a,
                                   const std::vector<Image>& levels_b, const NoisyImage& b,
                                   const SelectionParams& params = {});

// Each pixel from the level the choice names, levels[choice - first] (levels start at level
// `first`). Throws std::invalid_argument when a choice has no level or the sizes disagree.
Image compose_levels(const std::vector<Image>& levels, const std::vector<uint8_t>& choice,
                     int first = 0);

// Per pixel, the strength (0: raw, to params.iterations) the halves choose: select_levels on
// their filter levels. Throws as denoise and select_levels do.
// `guides`, when given, as in denoise.
std::vector<uint8_t> choose_strength(const NoisyImage& half_a, const NoisyImage& half_b,
                                     const DenoiseFeatures& features,
                                     const DenoiseParams& params = {},
                                     const SelectionParams& selection = {},
                                     const GuideWeights* guides = nullptr);

// denoise_chosen (render/denoiser.h) shows the full image at the chosen strengths.

// Both steps: the full image filtered per pixel to the strength its halves choose.
Image denoise_cross_validated(const NoisyImage& full, const NoisyImage& half_a,
                              const NoisyImage& half_b, const DenoiseFeatures& features,
                              const DenoiseParams& params = {},
                              const SelectionParams& selection = {});

}  // namespace tuneray
