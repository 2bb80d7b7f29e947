#include "render/denoiser.h"

#include "render/staggered_allocator.h"

#include <immintrin.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace tuneray {

namespace {

// The B3-spline kernel (1, 4, 6, 4, 1) / 16 by distance from the centre.
constexpr float kB3[3] = {3.0f / 8.0f, 1.0f / 4.0f, 1.0f / 16.0f};
// Albedo below this is treated as this when dividing, so black surfaces do not blow up noise.
constexpr float kMinAlbedo = 0.01f;
// Exponents beyond this give weights below 1e-34: zero for our purposes.
constexpr float kMaxExponent = 80.0f;
// Taps 2^15 pixels apart reach beyond any image we render.
constexpr int kMostIterations = 16;
// Added to the noise variance: without noise only an (almost) equal luminance passes.
constexpr float kTinyNoise = 1e-20f;

float demodulator(float albedo) {
  return 1.0f / std::max(albedo, kMinAlbedo);
}

// e^-x for x in [0, kMaxExponent], to ~2e-4 relative: 2^(integer part) from the exponent bits
// times a polynomial for 2^(fraction). A weight needs no more precision, and the library exp
// would be most of the filter's time.
inline float exp_neg(float x) {
  // log2(e^-x) + 127, in [11, 127]: positive, so truncation is the floor, and the integer part
  // is the biased exponent of a normal float.
  const float t = 127.0f - x * 1.44269504f;
  const int32_t i = static_cast<int32_t>(t);
  const float f = t - static_cast<float>(i);
  const float p =
      1.0f +
      f * (0.693147f + f * (0.240227f + f * (0.0555041f + f * (0.00961813f + f * 1.33336e-3f))));
  return p * std::bit_cast<float>(i << 23);
}

// exp_neg on eight lanes.
inline __m256 exp_neg8(__m256 x) {
  const __m256 t = _mm256_fnmadd_ps(x, _mm256_set1_ps(1.44269504f), _mm256_set1_ps(127.0f));
  const __m256i i = _mm256_cvttps_epi32(t);
  const __m256 f = _mm256_sub_ps(t, _mm256_cvtepi32_ps(i));
  __m256 p = _mm256_set1_ps(1.33336e-3f);
  for (float c : {0.00961813f, 0.0555041f, 0.240227f, 0.693147f, 1.0f})
    p = _mm256_fmadd_ps(p, f, _mm256_set1_ps(c));
  return _mm256_mul_ps(p, _mm256_castsi256_ps(_mm256_slli_epi32(i, 23)));
}

template <class F>
void for_rows(int height, F&& rows) {
  tbb::parallel_for(tbb::blocked_range<int>(0, height),
                    [&](const tbb::blocked_range<int>& r) { rows(r.begin(), r.end()); });
}

// Unknown variances (pixels with one sample): the spread of the 3x3 neighbourhood's
// luminance, as a one-sample pixel's variance is that of a single sample.
FloatPlane completed_variance(const NoisyImage& in) {
  const int w = in.color.width(), h = in.color.height();
  FloatPlane v(in.variance.begin(), in.variance.end());
  for_rows(h, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y)
      for (int x = 0; x < w; ++x) {
        size_t p = static_cast<size_t>(y) * w + x;
        if (v[p] >= 0) continue;
        double sum = 0, square_sum = 0;
        int n = 0;
        for (int yy = std::max(0, y - 1); yy <= std::min(h - 1, y + 1); ++yy)
          for (int xx = std::max(0, x - 1); xx <= std::min(w - 1, x + 1); ++xx) {
            if (!in.has_estimate[static_cast<size_t>(yy) * w + xx]) continue;
            double l = luminance(in.color.at(xx, yy));
            sum += l;
            square_sum += l * l;
            ++n;
          }
        v[p] = n >= 2 ? static_cast<float>(std::max(0.0, (square_sum - sum * sum / n) / (n - 1)))
                      : 0.0f;
      }
  });
  return v;
}

// Pixels the filter leaves alone and never reads: those within one pixel of where the camera
// sees a light. Their radiance is the light's, over part of the pixel (the feature rays may
// miss a light that the samples hit), so blending them either dims the light's edge or
// spreads it over the ceiling; at 64x48 the light's rim was 96% of the Cornell box's error.
std::vector<uint8_t> near_emitters(const DenoiseFeatures& f) {
  const int w = f.width, h = f.height;
  std::vector<uint8_t> kept(static_cast<size_t>(w) * h, 0);
  if (f.emitter.empty()) return kept;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (!f.emitter[static_cast<size_t>(y) * w + x]) continue;
      for (int yy = std::max(0, y - 1); yy <= std::min(h - 1, y + 1); ++yy)
        for (int xx = std::max(0, x - 1); xx <= std::min(w - 1, x + 1); ++xx)
          kept[static_cast<size_t>(yy) * w + xx] = 1;
    }
  return kept;
}

// The guides as planes of floats (the tap loop reads them with unit stride).
struct GuidePlanes {
  FloatPlane nx, ny, nz, ar, ag, ab;
  // Visibility, and its noise (deviations^2 x variance); 1 and 0 without the guide.
  FloatPlane vis, vis_noise;
  GuidePlanes(const DenoiseFeatures& f, const DenoiseParams& params) {
    for (const Vec3f& n : f.normal) {
      nx.push_back(n.x);
      ny.push_back(n.y);
      nz.push_back(n.z);
    }
    for (const Color& a : f.albedo) {
      ar.push_back(a.x);
      ag.push_back(a.y);
      ab.push_back(a.z);
    }
    const size_t pixels = f.albedo.size();
    const float k2 = params.visibility_noise_deviations * params.visibility_noise_deviations;
    vis.assign(pixels, 1.0f);
    vis_noise.assign(pixels, 0.0f);
    if (f.visibility.empty()) return;
    for (size_t p = 0; p < pixels; ++p) {
      vis[p] = f.visibility[p];
      vis_noise[p] = k2 * f.visibility_variance[p];
    }
  }
};

// One iteration's state: light at the surface (the image divided by the albedo), its
// variance, and which pixels have a value (1 or 0).
struct Layer {
  FloatPlane r, g, b, variance, valid;
  explicit Layer(size_t n) : r(n), g(n), b(n), variance(n), valid(n) {}
};

// SVGF's 3x3 Gaussian of the variance, times `scale`: a steadier noise level for the
// luminance weight. Separable (rows, then columns of the row sums), with pixels without a value
// weighted 0: the kernel is a product and the mask a per-pixel factor.
void blur_variance(const Layer& in, int w, int h, float scale, FloatPlane& out) {
  const size_t pixels = static_cast<size_t>(w) * h;
  FloatPlane sum(pixels), weight(pixels);
  for_rows(h, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      const size_t row = static_cast<size_t>(y) * w;
      const float* __restrict v = in.variance.data() + row;
      const float* __restrict m = in.valid.data() + row;
      float* __restrict s = sum.data() + row;
      float* __restrict k = weight.data() + row;
      for (int x = 0; x < w; ++x) {
        float vs = 0.5f * m[x] * v[x], ks = 0.5f * m[x];
        if (x > 0) {
          vs += 0.25f * m[x - 1] * v[x - 1];
          ks += 0.25f * m[x - 1];
        }
        if (x + 1 < w) {
          vs += 0.25f * m[x + 1] * v[x + 1];
          ks += 0.25f * m[x + 1];
        }
        s[x] = vs;
        k[x] = ks;
      }
    }
  });
  for_rows(h, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      const size_t row = static_cast<size_t>(y) * w;
      const size_t up = y > 0 ? row - w : row, down = y + 1 < h ? row + w : row;
      const float up_k = y > 0 ? 0.25f : 0.0f, down_k = y + 1 < h ? 0.25f : 0.0f;
      for (int x = 0; x < w; ++x) {
        const float vs = 0.5f * sum[row + x] + up_k * sum[up + x] + down_k * sum[down + x];
        const float ks = 0.5f * weight[row + x] + up_k * weight[up + x] + down_k * weight[down + x];
        out[row + x] = ks > 0 ? scale * vs / ks : 0.0f;
      }
    }
  });
}

// Sums over a row's taps, one entry per pixel of the row.
struct RowSums {
  std::vector<float> r, g, b, weight, variance;
  std::vector<float> base_r, base_g, base_b;
  // The centre's noise (sigma_luminance^2 x variance) and whether its luminance counts (1/0).
  std::vector<float> noise, luminance_counts;
  explicit RowSums(int w)
      : r(w),
        g(w),
        b(w),
        weight(w),
        variance(w),
        base_r(w),
        base_g(w),
        base_b(w),
        noise(w),
        luminance_counts(w) {}
};

// One row's worth of the planes, from some first pixel on.
struct Planes {
  const float *nx, *ny, *nz, *ar, *ag, *ab, *vis, *vis_noise, *lum, *noise, *r, *g, *b, *variance,
      *valid;
};

// Adds one tap to the sums of pixels [x0, x1) of a row; `q` starts at pixel x0's tap.
void accumulate_taps(int x0, int x1, float kernel, float inv_albedo_sigma2, float visibility_sigma2,
                     int normal_squarings, const Planes& c, const Planes& q, RowSums& s) {
  const int n = x1 - x0;
  const float* __restrict cnx = c.nx + x0;
  const float* __restrict cny = c.ny + x0;
  const float* __restrict cnz = c.nz + x0;
  const float* __restrict car = c.ar + x0;
  const float* __restrict cag = c.ag + x0;
  const float* __restrict cab = c.ab + x0;
  const float* __restrict clum = c.lum + x0;
  const float* __restrict cvis = c.vis + x0;
  const float* __restrict cvn = c.vis_noise + x0;
  const float* __restrict qvis = q.vis;
  const float* __restrict qvn = q.vis_noise;
  const float* __restrict qnx = q.nx;
  const float* __restrict qny = q.ny;
  const float* __restrict qnz = q.nz;
  const float* __restrict qar = q.ar;
  const float* __restrict qag = q.ag;
  const float* __restrict qab = q.ab;
  const float* __restrict qlum = q.lum;
  const float* __restrict qr = q.r;
  const float* __restrict qg = q.g;
  const float* __restrict qb = q.b;
  const float* __restrict qvar = q.variance;
  const float* __restrict qvalid = q.valid;
  const float* __restrict br = s.base_r.data() + x0;
  const float* __restrict bg = s.base_g.data() + x0;
  const float* __restrict bb = s.base_b.data() + x0;
  const float* __restrict cnoise = s.noise.data() + x0;
  const float* __restrict counts = s.luminance_counts.data() + x0;
  const float* __restrict qnoise = q.noise;
  float* __restrict sr = s.r.data() + x0;
  float* __restrict sg = s.g.data() + x0;
  float* __restrict sb = s.b.data() + x0;
  float* __restrict sw = s.weight.data() + x0;
  float* __restrict sv = s.variance.data() + x0;
  // Eight pixels at a time (the project targets AVX2), then the rest one by one.
  const __m256 zero = _mm256_setzero_ps(), max_exponent = _mm256_set1_ps(kMaxExponent);
  const __m256 sign = _mm256_set1_ps(-0.0f), k = _mm256_set1_ps(kernel);
  const __m256 inv_a2 = _mm256_set1_ps(inv_albedo_sigma2), tiny = _mm256_set1_ps(kTinyNoise);
  const __m256 vis_s2 = _mm256_set1_ps(visibility_sigma2);
  int x = 0;
  for (; x + 8 <= n; x += 8) {
    auto at = [x](const float* p) { return _mm256_loadu_ps(p + x); };
    __m256 wn = _mm256_mul_ps(at(cnx), at(qnx));
    wn = _mm256_fmadd_ps(at(cny), at(qny), wn);
    wn = _mm256_max_ps(_mm256_fmadd_ps(at(cnz), at(qnz), wn), zero);
    for (int i = 0; i < normal_squarings; ++i) wn = _mm256_mul_ps(wn, wn);
    const __m256 dr = _mm256_sub_ps(at(car), at(qar)), dg = _mm256_sub_ps(at(cag), at(qag)),
                 db = _mm256_sub_ps(at(cab), at(qab));
    __m256 albedo = _mm256_mul_ps(dr, dr);
    albedo = _mm256_fmadd_ps(dg, dg, albedo);
    albedo = _mm256_mul_ps(_mm256_fmadd_ps(db, db, albedo), inv_a2);
    const __m256 dv = _mm256_sub_ps(at(cvis), at(qvis));
    const __m256 vis_spread = _mm256_add_ps(_mm256_add_ps(at(cvn), at(qvn)), vis_s2);
    const __m256 visibility = _mm256_mul_ps(_mm256_mul_ps(dv, dv), _mm256_rcp_ps(vis_spread));
    const __m256 dl = _mm256_andnot_ps(sign, _mm256_sub_ps(at(clum), at(qlum)));
    const __m256 noise = _mm256_add_ps(_mm256_add_ps(at(cnoise), at(qnoise)), tiny);
    const __m256 luminance = _mm256_mul_ps(_mm256_mul_ps(dl, _mm256_rsqrt_ps(noise)), at(counts));
    const __m256 exponent =
        _mm256_min_ps(_mm256_add_ps(_mm256_add_ps(luminance, albedo), visibility), max_exponent);
    const __m256 wq =
        _mm256_mul_ps(_mm256_mul_ps(k, wn), _mm256_mul_ps(at(qvalid), exp_neg8(exponent)));
    auto add = [x](float* sum, __m256 v) {
      _mm256_storeu_ps(sum + x, _mm256_add_ps(_mm256_loadu_ps(sum + x), v));
    };
    add(sr, _mm256_mul_ps(wq, _mm256_sub_ps(at(qr), at(br))));
    add(sg, _mm256_mul_ps(wq, _mm256_sub_ps(at(qg), at(bg))));
    add(sb, _mm256_mul_ps(wq, _mm256_sub_ps(at(qb), at(bb))));
    add(sw, wq);
    add(sv, _mm256_mul_ps(_mm256_mul_ps(wq, wq), at(qvar)));
  }
  for (; x < n; ++x) {
    float wn = std::max(0.0f, cnx[x] * qnx[x] + cny[x] * qny[x] + cnz[x] * qnz[x]);
    for (int i = 0; i < normal_squarings; ++i) wn *= wn;
    const float dr = car[x] - qar[x], dg = cag[x] - qag[x], db = cab[x] - qab[x];
    const float dv = cvis[x] - qvis[x];
    const float exponent =
        (dr * dr + dg * dg + db * db) * inv_albedo_sigma2 +
        dv * dv / (cvn[x] + qvn[x] + visibility_sigma2) +
        std::abs(clum[x] - qlum[x]) / std::sqrt(cnoise[x] + qnoise[x] + kTinyNoise) * counts[x];
    // Written so that NaN (inf - inf) also becomes the largest exponent, as in the lanes above.
    const float bounded = exponent < kMaxExponent ? exponent : kMaxExponent;
    const float wq = kernel * wn * qvalid[x] * exp_neg(bounded);
    sr[x] += wq * (qr[x] - br[x]);
    sg[x] += wq * (qg[x] - bg[x]);
    sb[x] += wq * (qb[x] - bb[x]);
    sw[x] += wq;
    sv[x] += wq * wq * qvar[x];
  }
}

void atrous_step(const Layer& in, Layer& out, const FloatPlane& lum, const FloatPlane& noise,
                 const GuidePlanes& guide, int w, int h, int step, const DenoiseParams& params) {
  const float inv_albedo_sigma2 = 1.0f / (params.sigma_albedo * params.sigma_albedo);
  const float visibility_sigma2 = params.sigma_visibility * params.sigma_visibility;
  for_rows(h, [&](int y0, int y1) {
    RowSums s(w);
    for (int y = y0; y < y1; ++y) {
      const size_t row = static_cast<size_t>(y) * w;
      for (int x = 0; x < w; ++x) {
        const size_t p = row + x;
        const bool valid = in.valid[p] > 0;
        // Differences are taken from the centre, so a constant neighbourhood stays exactly
        // constant; a pixel without a value takes its neighbours' weighted mean.
        s.base_r[x] = valid ? in.r[p] : 0.0f;
        s.base_g[x] = valid ? in.g[p] : 0.0f;
        s.base_b[x] = valid ? in.b[p] : 0.0f;
        s.noise[x] = noise[p];
        s.luminance_counts[x] = valid ? 1.0f : 0.0f;  // no value: its luminance means nothing
        s.r[x] = s.g[x] = s.b[x] = s.weight[x] = s.variance[x] = 0;
      }
      const Planes centre{guide.nx.data() + row,
                          guide.ny.data() + row,
                          guide.nz.data() + row,
                          guide.ar.data() + row,
                          guide.ag.data() + row,
                          guide.ab.data() + row,
                          guide.vis.data() + row,
                          guide.vis_noise.data() + row,
                          lum.data() + row,
                          noise.data() + row,
                          nullptr,
                          nullptr,
                          nullptr,
                          nullptr,
                          nullptr};
      for (int ky = -2; ky <= 2; ++ky) {
        const int yy = y + ky * step;
        if (yy < 0 || yy >= h) continue;
        for (int kx = -2; kx <= 2; ++kx) {
          const int off = kx * step;
          const int x0 = std::max(0, -off), x1 = std::min(w, w - off);
          const float kernel = kB3[std::abs(ky)] * kB3[std::abs(kx)];
          const size_t q0 = static_cast<size_t>(yy) * w + (off + x0);  // pixel x0's tap
          const Planes tap{guide.nx.data() + q0,  guide.ny.data() + q0,
                           guide.nz.data() + q0,  guide.ar.data() + q0,
                           guide.ag.data() + q0,  guide.ab.data() + q0,
                           guide.vis.data() + q0, guide.vis_noise.data() + q0,
                           lum.data() + q0,       noise.data() + q0,
                           in.r.data() + q0,      in.g.data() + q0,
                           in.b.data() + q0,      in.variance.data() + q0,
                           in.valid.data() + q0};
          accumulate_taps(x0, x1, kernel, inv_albedo_sigma2, visibility_sigma2,
                          params.normal_squarings, centre, tap, s);
        }
      }
      for (int x = 0; x < w; ++x) {
        const size_t p = row + x;
        const float weight = s.weight[x];
        if (weight > 0) {
          const float inv = 1.0f / weight;
          out.r[p] = s.base_r[x] + s.r[x] * inv;
          out.g[p] = s.base_g[x] + s.g[x] * inv;
          out.b[p] = s.base_b[x] + s.b[x] * inv;
          out.variance[p] = s.variance[x] * inv * inv;
          out.valid[p] = 1;
        } else {
          out.r[p] = in.r[p];
          out.g[p] = in.g[p];
          out.b[p] = in.b[p];
          out.variance[p] = in.variance[p];
          out.valid[p] = in.valid[p];
        }
      }
    }
  });
}

}  // namespace

NoisyImage noisy_image(const Film& film) {
  NoisyImage in{film.resolve(), {}, {}};
  const size_t pixels = static_cast<size_t>(film.width()) * film.height();
  in.variance.resize(pixels);
  in.has_estimate.resize(pixels);
  for (int y = 0; y < film.height(); ++y)
    for (int x = 0; x < film.width(); ++x) {
      size_t p = static_cast<size_t>(y) * film.width() + x;
      uint32_t n = film.samples(x, y);
      in.has_estimate[p] = n > 0;
      in.variance[p] = n >= 2 ? static_cast<float>(film.variance_of_mean(x, y)) : -1.0f;
    }
  return in;
}

std::vector<Image> denoise_levels(const NoisyImage& in, const DenoiseFeatures& f,
                                  const DenoiseParams& params, int first_kept) {
  const int w = in.color.width(), h = in.color.height();
  const size_t pixels = static_cast<size_t>(w) * h;
  if (f.width != w || f.height != h || f.albedo.size() != pixels || f.normal.size() != pixels ||
      (!f.emitter.empty() && f.emitter.size() != pixels) ||
      (!f.visibility.empty() &&
       (f.visibility.size() != pixels || f.visibility_variance.size() != pixels)) ||
      in.variance.size() != pixels || in.has_estimate.size() != pixels)
    throw std::invalid_argument("denoise: image, variance and features differ in size");
  if (params.iterations < 0 || params.iterations > kMostIterations)
    throw std::invalid_argument("denoise: iterations must be in [0, " +
                                std::to_string(kMostIterations) + "]");
  // Past 32 squarings (an exponent of 2^32) every pair of distinct normals weighs 0 anyway.
  if (params.normal_squarings < 0 || params.normal_squarings > 32)
    throw std::invalid_argument("denoise: normal_squarings must be in [0, 32]");
  if (!(params.sigma_visibility > 0) || !std::isfinite(params.sigma_visibility) ||
      !(params.visibility_noise_deviations >= 0))
    throw std::invalid_argument(
        "denoise: sigma_visibility must be positive and finite, "
        "visibility_noise_deviations non-negative");

  const FloatPlane variance = completed_variance(in);
  const std::vector<uint8_t> kept = near_emitters(f);
  const GuidePlanes guide(f, params);
  Layer a(pixels);
  for (size_t p = 0; p < pixels; ++p) {
    const Color& c = in.color.data()[p];
    const float d = demodulator(luminance(f.albedo[p]));
    a.r[p] = c.x * demodulator(f.albedo[p].x);
    a.g[p] = c.y * demodulator(f.albedo[p].y);
    a.b[p] = c.z * demodulator(f.albedo[p].z);
    a.variance[p] = variance[p] * d * d;
    a.valid[p] = in.has_estimate[p] && !kept[p] ? 1.0f : 0.0f;
  }
  // The change, remodulated: a pixel the filter left alone keeps its exact value; one without
  // an estimate gets the filtered light times its albedo.
  auto remodulated = [&](const Layer& filtered_layer) {
    Image out(w, h);
    for (size_t p = 0; p < pixels; ++p) {
      const Color& c = in.color.data()[p];
      const Color& albedo = f.albedo[p];
      const Color filtered(filtered_layer.r[p], filtered_layer.g[p], filtered_layer.b[p]);
      const Color scale(std::max(albedo.x, kMinAlbedo), std::max(albedo.y, kMinAlbedo),
                        std::max(albedo.z, kMinAlbedo));
      const Color original(c.x * demodulator(albedo.x), c.y * demodulator(albedo.y),
                           c.z * demodulator(albedo.z));
      if (kept[p])
        out.data()[p] = c;
      else
        out.data()[p] = in.has_estimate[p] ? c + (filtered - original) * scale : filtered * scale;
    }
    return out;
  };

  std::vector<Image> levels;
  if (first_kept <= 0) levels.push_back(in.color);
  Layer b(pixels);
  FloatPlane lum(pixels), noise(pixels);
  for (int i = 0; i < params.iterations; ++i) {
    for (size_t p = 0; p < pixels; ++p) lum[p] = luminance(Color(a.r[p], a.g[p], a.b[p]));
    blur_variance(a, w, h, params.sigma_luminance * params.sigma_luminance, noise);
    atrous_step(a, b, lum, noise, guide, w, h, 1 << i, params);
    std::swap(a, b);
    if (i + 1 >= first_kept) levels.push_back(remodulated(a));
  }
  if (levels.empty()) levels.push_back(in.color);  // no iterations: the input itself
  return levels;
}

Image denoise(const NoisyImage& in, const DenoiseFeatures& f, const DenoiseParams& params) {
  return std::move(denoise_levels(in, f, params, params.iterations).back());
}

}  // namespace tuneray
