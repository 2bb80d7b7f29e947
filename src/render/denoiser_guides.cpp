// The guide weights: per chunk and tap, the part of the filter's weight that the features
// decide (denoiser.h, GuideWeights).
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "render/denoiser.h"
#include "render/denoiser_kernel.h"

namespace tuneray {
namespace denoise_detail {
namespace {

// The guide terms' constants.
struct StepConstants {
  float inv_albedo_sigma2, visibility_sigma2, plane_sigma2;
  int normal_squarings;
};

StepConstants step_constants(const DenoiseParams& params) {
  return {1.0f / (params.sigma_albedo * params.sigma_albedo),
          params.sigma_visibility * params.sigma_visibility,
          params.sigma_plane * params.sigma_plane, params.normal_squarings};
}

// A chunk's own guide values, loaded once for its 25 taps (lanes past the row's end read 0;
// a tap's lanes outside its mask weigh 0 whatever the centre holds there). vis_spread is the
// centre's share of the visibility spread with its constant term added.
struct GuideCentre {
  __m256 nx, ny, nz, ar, ag, ab, px, py, pz, vis, vis_spread;
  GuideCentre(const GuidePlanes& g, float visibility_sigma2, ptrdiff_t c, __m256i mask,
              bool whole) {
    auto at = [&](const FloatPlane& v) { return load8(v, c, mask, whole); };
    nx = at(g.nx), ny = at(g.ny), nz = at(g.nz);
    ar = at(g.ar), ag = at(g.ag), ab = at(g.ab);
    px = at(g.px), py = at(g.py), pz = at(g.pz);
    vis = at(g.vis);
    vis_spread = _mm256_add_ps(at(g.vis_noise), _mm256_set1_ps(visibility_sigma2));
  }
};

// The guides' weight of the tap at offset (kx, ky) steps, pixel index `q` for the chunk's first
// lane: the kernel times the normal weight times e^-(albedo + visibility + plane terms). Lanes
// outside `mask` read zeros and weigh 0 (a zero normal).
template <bool kFull>
inline __m256 guide_weight(const GuidePlanes& guide, const GuideCentre& centre,
                           const StepConstants& k, ptrdiff_t q, __m256i mask, int kx, int ky) {
  auto tap = [&](const FloatPlane& v) { return load8<kFull>(v, q, mask); };
  const __m256 zero = _mm256_setzero_ps();
  __m256 wn = _mm256_mul_ps(centre.nx, tap(guide.nx));
  wn = _mm256_fmadd_ps(centre.ny, tap(guide.ny), wn);
  wn = _mm256_max_ps(_mm256_fmadd_ps(centre.nz, tap(guide.nz), wn), zero);
  wn = repeated_squares(wn, k.normal_squarings);
  const __m256 dr = _mm256_sub_ps(centre.ar, tap(guide.ar));
  const __m256 dg = _mm256_sub_ps(centre.ag, tap(guide.ag));
  const __m256 db = _mm256_sub_ps(centre.ab, tap(guide.ab));
  __m256 albedo = _mm256_mul_ps(dr, dr);
  albedo = _mm256_fmadd_ps(dg, dg, albedo);
  albedo = _mm256_mul_ps(_mm256_fmadd_ps(db, db, albedo), _mm256_set1_ps(k.inv_albedo_sigma2));
  const __m256 ex = _mm256_sub_ps(tap(guide.px), centre.px);
  const __m256 ey = _mm256_sub_ps(tap(guide.py), centre.py);
  const __m256 ez = _mm256_sub_ps(tap(guide.pz), centre.pz);
  __m256 off_plane = _mm256_mul_ps(centre.nx, ex);
  off_plane = _mm256_fmadd_ps(centre.ny, ey, off_plane);
  off_plane = _mm256_fmadd_ps(centre.nz, ez, off_plane);
  __m256 chord = _mm256_fmadd_ps(ex, ex, _mm256_set1_ps(kTinyChord));
  chord = _mm256_fmadd_ps(ey, ey, chord);
  chord = _mm256_fmadd_ps(ez, ez, chord);
  const __m256 plane =
      _mm256_mul_ps(_mm256_mul_ps(off_plane, off_plane),
                    _mm256_rcp_ps(_mm256_mul_ps(chord, _mm256_set1_ps(k.plane_sigma2))));
  const __m256 dv = _mm256_sub_ps(centre.vis, tap(guide.vis));
  const __m256 vis_spread = _mm256_add_ps(centre.vis_spread, tap(guide.vis_noise));
  const __m256 visibility = _mm256_mul_ps(_mm256_mul_ps(dv, dv), _mm256_rcp_ps(vis_spread));
  // min() also turns NaN into the largest exponent: it returns its second operand.
  const __m256 exponent = _mm256_min_ps(_mm256_add_ps(albedo, _mm256_add_ps(visibility, plane)),
                                        _mm256_set1_ps(kMaxExponent));
  const float kernel = kB3[std::abs(ky)] * kB3[std::abs(kx)];
  return _mm256_mul_ps(_mm256_mul_ps(_mm256_set1_ps(kernel), wn), exp_neg8(exponent));
}

}  // namespace

void build_guide_table(const GuidePlanes& guide, int w, int h, int step,
                       const DenoiseParams& params, uint16_t* table) {
  const StepConstants k = step_constants(params);
  for_chunks(w, h, [&](const Chunk& chunk) {
    const GuideCentre centre(guide, k.visibility_sigma2, chunk.c, chunk.mask, chunk.whole);
    uint16_t* weights = table + chunk_table_offset(w, chunk);
    std::fill_n(weights, kTaps * 8, uint16_t{0});
    for_taps(
        chunk, w, h, step,
        [&](int kx, int ky, ptrdiff_t q, __m256i mask, bool full) {
          const __m256 g = full ? guide_weight<true>(guide, centre, k, q, mask, kx, ky)
                                : guide_weight<false>(guide, centre, k, q, mask, kx, ky);
          _mm_storeu_si128(reinterpret_cast<__m128i*>(weights + tap_index(kx, ky) * 8),
                           _mm256_cvtps_ph(g, _MM_FROUND_TO_NEAREST_INT));
        },
        [](int) {});
  });
}

// Throws std::invalid_argument unless the features are w x h.
void check_features(const DenoiseFeatures& f, int w, int h) {
  const size_t pixels = static_cast<size_t>(w) * h;
  if (f.width != w || f.height != h || f.albedo.size() != pixels || f.normal.size() != pixels ||
      (!f.emitter.empty() && f.emitter.size() != pixels) ||
      (!f.position.empty() && f.position.size() != pixels) ||
      (!f.visibility.empty() &&
       (f.visibility.size() != pixels || f.visibility_variance.size() != pixels)))
    throw std::invalid_argument("denoise: image, variance and features differ in size");
}

void check_params(const DenoiseParams& params) {
  if (params.iterations < 0 || params.iterations > kMostIterations)
    throw std::invalid_argument("denoise: iterations must be in [0, " +
                                std::to_string(kMostIterations) + "]");
  // Past 32 squarings (an exponent of 2^32) every pair of distinct normals weighs 0 anyway.
  if (params.normal_squarings < 0 || params.normal_squarings > 32)
    throw std::invalid_argument("denoise: normal_squarings must be in [0, 32]");
  if (!(params.sigma_plane > 0) || !std::isfinite(params.sigma_plane))
    throw std::invalid_argument("denoise: sigma_plane must be positive and finite");
  if (!(params.slope_ridge >= 0) || !std::isfinite(params.slope_ridge) ||
      !(params.first_order_shrinkage >= 0) || !std::isfinite(params.first_order_shrinkage))
    throw std::invalid_argument(
        "denoise: slope_ridge and first_order_shrinkage must be non-negative and finite");
  if (!(params.sigma_visibility > 0) || !std::isfinite(params.sigma_visibility) ||
      !(params.visibility_noise_deviations >= 0))
    throw std::invalid_argument(
        "denoise: sigma_visibility must be positive and finite, "
        "visibility_noise_deviations non-negative");
}

}  // namespace denoise_detail

namespace {

// Whether two parameter sets give the same guide weights.
bool same_guide_terms(const DenoiseParams& a, const DenoiseParams& b) {
  return a.normal_squarings == b.normal_squarings && a.sigma_albedo == b.sigma_albedo &&
         a.sigma_visibility == b.sigma_visibility &&
         a.visibility_noise_deviations == b.visibility_noise_deviations &&
         a.sigma_plane == b.sigma_plane;
}

}  // namespace

using namespace denoise_detail;

GuideWeights::GuideWeights(const DenoiseFeatures& f, const DenoiseParams& params)
    : width_(f.width), height_(f.height), params_(params) {
  check_params(params);
  if (f.width < 0 || f.height < 0)
    throw std::invalid_argument("denoise: the features have a negative size");
  check_features(f, f.width, f.height);
  const GuidePlanes guide(f, params);
  const size_t per_iteration = table_halves(width_, height_);
  halves_.resize(per_iteration * static_cast<size_t>(params.iterations));
  for (int i = 0; i < params.iterations; ++i)
    build_guide_table(guide, width_, height_, 1 << i, params, halves_.data() + per_iteration * i);
}

size_t GuideWeights::bytes_for(int width, int height, int iterations) {
  return table_halves(width, height) * static_cast<size_t>(std::max(0, iterations)) *
         sizeof(uint16_t);
}

bool GuideWeights::fits(int width, int height, const DenoiseParams& params) const {
  return width == width_ && height == height_ && params.iterations <= params_.iterations &&
         same_guide_terms(params, params_);
}

const uint16_t* GuideWeights::table(int iteration) const {
  return halves_.data() + table_halves(width_, height_) * static_cast<size_t>(iteration);
}

}  // namespace tuneray
