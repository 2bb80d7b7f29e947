#include "render/denoiser.h"

#include <immintrin.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "render/denoiser_kernel.h"
#include "render/staggered_allocator.h"

namespace tuneray {

using namespace denoise_detail;

namespace {

// Albedo below this is treated as this when dividing, so black surfaces do not blow up noise.
constexpr float kMinAlbedo = 0.01f;

float demodulator(float albedo) {
  return 1.0f / std::max(albedo, kMinAlbedo);
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
  for_rows(h, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y)
      for (int x = 0; x < w; ++x) {
        bool near = false;
        for (int yy = std::max(0, y - 1); yy <= std::min(h - 1, y + 1); ++yy)
          for (int xx = std::max(0, x - 1); xx <= std::min(w - 1, x + 1); ++xx)
            near = near || f.emitter[static_cast<size_t>(yy) * w + xx];
        kept[static_cast<size_t>(y) * w + x] = near;
      }
  });
  return kept;
}

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

// The sums over one row of a chunk's taps, eight pixels to a vector: values, weights and
// variances, and the first-order moments along x (times the tap's offset in steps, and for the
// weights and variances its square). The moments along y are the row sums times the row's
// offset, added once per row (TapSums::add_row): fewer live accumulators in the tap loop.
struct RowSums {
  __m256 r, g, b, weight, variance, rx, gx, bx, wx, wxx, vx, vxx;
};

// A chunk's sums over all its taps.
struct TapSums {
  __m256 r, g, b, weight, variance;
  // First-order moments: the same sums times the tap's offset (in steps) along x and y, and for
  // the weights and variances also times the offsets' products.
  __m256 rx, ry, gx, gy, bx, by, wx, wy, wxx, wyy, wxy, vx, vy, vxx, vyy, vxy;

  void add_row(const RowSums& row, int ky, bool first_order) {
    r = _mm256_add_ps(r, row.r);
    g = _mm256_add_ps(g, row.g);
    b = _mm256_add_ps(b, row.b);
    weight = _mm256_add_ps(weight, row.weight);
    variance = _mm256_add_ps(variance, row.variance);
    if (!first_order) return;
    rx = _mm256_add_ps(rx, row.rx);
    gx = _mm256_add_ps(gx, row.gx);
    bx = _mm256_add_ps(bx, row.bx);
    wx = _mm256_add_ps(wx, row.wx);
    wxx = _mm256_add_ps(wxx, row.wxx);
    vx = _mm256_add_ps(vx, row.vx);
    vxx = _mm256_add_ps(vxx, row.vxx);
    if (ky == 0) return;
    const __m256 d = _mm256_set1_ps(static_cast<float>(ky));
    const __m256 dd = _mm256_set1_ps(static_cast<float>(ky * ky));
    ry = _mm256_fmadd_ps(row.r, d, ry);
    gy = _mm256_fmadd_ps(row.g, d, gy);
    by = _mm256_fmadd_ps(row.b, d, by);
    wy = _mm256_fmadd_ps(row.weight, d, wy);
    wyy = _mm256_fmadd_ps(row.weight, dd, wyy);
    vy = _mm256_fmadd_ps(row.variance, d, vy);
    vyy = _mm256_fmadd_ps(row.variance, dd, vyy);
    wxy = _mm256_fmadd_ps(row.wx, d, wxy);
    vxy = _mm256_fmadd_ps(row.vx, d, vxy);
  }
};

// Adds the tap at offset kx steps along the row, pixel index `q` for the chunk's first lane, to
// the chunk's row sums: its guides' weight `guide` times the luminance weight. `mask` marks
// lanes whose pixel and tap exist. The whole chunk's taps inside the image (kFull) and the
// first-order sums are known when the loop is compiled, so the hot path has no masks.
template <bool kFull, bool kFirstOrder>
inline void add_tap(const Layer& in, const FloatPlane& lum, const FloatPlane& noise,
                    __m256 centre_lum, __m256 centre_spread, __m256 guide, ptrdiff_t q,
                    __m256i mask, int kx, __m256 base_r, __m256 base_g, __m256 base_b,
                    __m256 counts, RowSums& s) {
  auto tap = [&](const FloatPlane& v) { return load8<kFull>(v, q, mask); };
  const __m256 dl = _mm256_andnot_ps(_mm256_set1_ps(-0.0f), _mm256_sub_ps(centre_lum, tap(lum)));
  const __m256 spread = _mm256_add_ps(centre_spread, tap(noise));
  // min() also turns NaN (inf - inf) into the largest exponent: it returns its second operand.
  const __m256 luminance =
      _mm256_min_ps(_mm256_mul_ps(_mm256_mul_ps(dl, counts), _mm256_rsqrt_ps(spread)),
                    _mm256_set1_ps(kMaxExponent));
  const __m256 wq = _mm256_mul_ps(guide, _mm256_mul_ps(tap(in.valid), exp_neg8(luminance)));
  const __m256 cr = _mm256_mul_ps(wq, _mm256_sub_ps(tap(in.r), base_r));
  const __m256 cg = _mm256_mul_ps(wq, _mm256_sub_ps(tap(in.g), base_g));
  const __m256 cb = _mm256_mul_ps(wq, _mm256_sub_ps(tap(in.b), base_b));
  const __m256 vq = _mm256_mul_ps(_mm256_mul_ps(wq, wq), tap(in.variance));
  s.r = _mm256_add_ps(s.r, cr);
  s.g = _mm256_add_ps(s.g, cg);
  s.b = _mm256_add_ps(s.b, cb);
  s.weight = _mm256_add_ps(s.weight, wq);
  s.variance = _mm256_add_ps(s.variance, vq);
  if constexpr (!kFirstOrder) return;
  if (kx == 0) return;
  const __m256 d = _mm256_set1_ps(static_cast<float>(kx));
  const __m256 dd = _mm256_set1_ps(static_cast<float>(kx * kx));
  s.rx = _mm256_fmadd_ps(cr, d, s.rx);
  s.gx = _mm256_fmadd_ps(cg, d, s.gx);
  s.bx = _mm256_fmadd_ps(cb, d, s.bx);
  s.wx = _mm256_fmadd_ps(wq, d, s.wx);
  s.wxx = _mm256_fmadd_ps(wq, dd, s.wxx);
  s.vx = _mm256_fmadd_ps(vq, d, s.vx);
  s.vxx = _mm256_fmadd_ps(vq, dd, s.vxx);
}

// The estimate's weights per tap are l_q = w_q (e0 + e1 dx + e2 dy), eight pixels to a vector:
// the weighted mean has e = (1/W, 0, 0); the first-order fit the plane's value at the centre.
struct Coefficients {
  __m256 e0, e1, e2;
};

// The variance of sum of l_q value_q: sum of w_q^2 var_q (e0 + e1 dx + e2 dy)^2.
inline __m256 variance_of(const TapSums& s, const Coefficients& e) {
  __m256 square = _mm256_mul_ps(_mm256_mul_ps(e.e0, e.e0), s.variance);
  square = _mm256_fmadd_ps(_mm256_mul_ps(e.e1, e.e1), s.vxx, square);
  square = _mm256_fmadd_ps(_mm256_mul_ps(e.e2, e.e2), s.vyy, square);
  __m256 cross = _mm256_mul_ps(_mm256_mul_ps(e.e0, e.e1), s.vx);
  cross = _mm256_fmadd_ps(_mm256_mul_ps(e.e0, e.e2), s.vy, cross);
  cross = _mm256_fmadd_ps(_mm256_mul_ps(e.e1, e.e2), s.vxy, cross);
  return _mm256_fmadd_ps(_mm256_set1_ps(2.0f), cross, square);
}

// Lanes whose weight is 0 come out as inf or NaN: the caller keeps their input.
Coefficients fit(const TapSums& s, const DenoiseParams& params) {
  const __m256 zero = _mm256_setzero_ps(), one = _mm256_set1_ps(1.0f);
  const __m256 e0 = _mm256_div_ps(one, s.weight);
  if (!params.first_order) return {e0, zero, zero};
  // The plane through the taps' weighted centroid m with the fitted slope, at the centre:
  // mean - slope . m, the slope solving C slope = sum of w (o - m) value over offsets o, C their
  // weighted covariance (ridged). So e = (1/W + u . m, -u) with u = C^-1 m.
  const __m256 mx = _mm256_mul_ps(s.wx, e0), my = _mm256_mul_ps(s.wy, e0);
  const __m256 ridge = _mm256_mul_ps(_mm256_set1_ps(params.slope_ridge), s.weight);
  const __m256 cxx = _mm256_add_ps(_mm256_fnmadd_ps(s.wx, mx, s.wxx), ridge);
  const __m256 cyy = _mm256_add_ps(_mm256_fnmadd_ps(s.wy, my, s.wyy), ridge);
  const __m256 cxy = _mm256_fnmadd_ps(s.wx, my, s.wxy);
  const __m256 det = _mm256_fmsub_ps(cxx, cyy, _mm256_mul_ps(cxy, cxy));
  // Where the covariance is singular the slope is 0 (and-ing also clears the NaNs of 0/0).
  const __m256 solvable = _mm256_cmp_ps(det, zero, _CMP_GT_OQ);
  const __m256 inverse_det = _mm256_div_ps(one, det);
  const __m256 ux = _mm256_and_ps(
      _mm256_mul_ps(_mm256_fmsub_ps(cyy, mx, _mm256_mul_ps(cxy, my)), inverse_det), solvable);
  const __m256 uy = _mm256_and_ps(
      _mm256_mul_ps(_mm256_fmsub_ps(cxx, my, _mm256_mul_ps(cxy, mx)), inverse_det), solvable);
  const __m256 a = _mm256_fmadd_ps(ux, mx, _mm256_mul_ps(uy, my));  // e0 - 1/W
  const Coefficients first{_mm256_add_ps(e0, a), _mm256_sub_ps(zero, ux), _mm256_sub_ps(zero, uy)};
  if (params.first_order_shrinkage <= 0) return first;
  // The correction over the mean, d = sum of w (a + e1 dx + e2 dy) value, is kept in the share
  // d^2 / (d^2 + k var(d)): where the slope is lost in the noise the mean is the better
  // estimate.
  auto correction = [&](__m256 v, __m256 vx, __m256 vy) {
    return _mm256_fmadd_ps(a, v, _mm256_fmadd_ps(first.e1, vx, _mm256_mul_ps(first.e2, vy)));
  };
  const __m256 dr = correction(s.r, s.rx, s.ry);
  const __m256 dg = correction(s.g, s.gx, s.gy);
  const __m256 db = correction(s.b, s.bx, s.by);
  const __m256 d2 =
      _mm256_mul_ps(_mm256_fmadd_ps(dr, dr, _mm256_fmadd_ps(dg, dg, _mm256_mul_ps(db, db))),
                    _mm256_set1_ps(1.0f / 3.0f));
  // max() with 0 second also turns a NaN variance into 0.
  const __m256 var_d = _mm256_max_ps(variance_of(s, {a, first.e1, first.e2}), zero);
  const __m256 denominator =
      _mm256_fmadd_ps(_mm256_set1_ps(params.first_order_shrinkage), var_d, d2);
  const __m256 t =
      _mm256_and_ps(_mm256_div_ps(d2, denominator), _mm256_cmp_ps(denominator, zero, _CMP_GT_OQ));
  return {_mm256_fmadd_ps(t, a, e0), _mm256_mul_ps(t, first.e1), _mm256_mul_ps(t, first.e2)};
}

void atrous_step(const Layer& in, Layer& out, const FloatPlane& lum, const FloatPlane& noise,
                 const uint16_t* guide_table, int w, int h, int step, const DenoiseParams& params) {
  for_chunks(w, h, [&](const Chunk& chunk) {
    auto at_centre = [&](const FloatPlane& v) {
      return load8(v, chunk.c, chunk.mask, chunk.whole);
    };
    // Differences are taken from the centre, so a constant neighbourhood stays exactly
    // constant; a pixel without a value takes its neighbours' weighted mean, and its
    // luminance means nothing.
    const __m256 valid = at_centre(in.valid);
    const __m256 has = _mm256_cmp_ps(valid, _mm256_setzero_ps(), _CMP_GT_OQ);
    const __m256 counts = _mm256_and_ps(has, _mm256_set1_ps(1.0f));
    const __m256 r = at_centre(in.r), g = at_centre(in.g), b = at_centre(in.b);
    const __m256 base_r = _mm256_and_ps(r, has);
    const __m256 base_g = _mm256_and_ps(g, has);
    const __m256 base_b = _mm256_and_ps(b, has);
    const __m256 centre_lum = at_centre(lum);
    const __m256 centre_spread = _mm256_add_ps(at_centre(noise), _mm256_set1_ps(kTinyNoise));
    const uint16_t* weights = guide_table + chunk_table_offset(w, chunk);
    TapSums s{};
    RowSums row_sums{};
    for_taps(
        chunk, w, h, step,
        [&](int kx, int ky, ptrdiff_t q, __m256i mask, bool full) {
          const __m256 guide = _mm256_cvtph_ps(
              _mm_loadu_si128(reinterpret_cast<const __m128i*>(weights + tap_index(kx, ky) * 8)));
          // Both flags as types, so each combination gets its own compiled loop body.
          auto add = [&](auto whole_chunk, auto first_order) {
            add_tap<decltype(whole_chunk)::value, decltype(first_order)::value>(
                in, lum, noise, centre_lum, centre_spread, guide, q, mask, kx, base_r, base_g,
                base_b, counts, row_sums);
          };
          using Yes = std::true_type;
          using No = std::false_type;
          if (full)
            params.first_order ? add(Yes{}, Yes{}) : add(Yes{}, No{});
          else
            params.first_order ? add(No{}, Yes{}) : add(No{}, No{});
        },
        [&](int ky) {
          s.add_row(row_sums, ky, params.first_order);
          row_sums = RowSums{};
        });
    // Pixels whose taps all weigh 0 keep their input.
    const __m256 filtered = _mm256_cmp_ps(s.weight, _mm256_setzero_ps(), _CMP_GT_OQ);
    const Coefficients e = fit(s, params);
    auto estimate = [&](__m256 base, __m256 sum, __m256 sum_x, __m256 sum_y) {
      return _mm256_add_ps(
          base,
          _mm256_fmadd_ps(e.e0, sum, _mm256_fmadd_ps(e.e1, sum_x, _mm256_mul_ps(e.e2, sum_y))));
    };
    auto put = [&](FloatPlane& plane, __m256 kept, __m256 value) {
      store8(plane, chunk.c, chunk.mask, chunk.whole, _mm256_blendv_ps(kept, value, filtered));
    };
    put(out.r, r, estimate(base_r, s.r, s.rx, s.ry));
    put(out.g, g, estimate(base_g, s.g, s.gx, s.gy));
    put(out.b, b, estimate(base_b, s.b, s.bx, s.by));
    put(out.variance, at_centre(in.variance),
        _mm256_max_ps(variance_of(s, e), _mm256_setzero_ps()));
    put(out.valid, valid, _mm256_set1_ps(1.0f));
  });
}

}  // namespace

NoisyImage noisy_image(const Film& film) {
  NoisyImage in{film.resolve(), {}, {}};
  const size_t pixels = static_cast<size_t>(film.width()) * film.height();
  in.variance.resize(pixels);
  in.has_estimate.resize(pixels);
  for_rows(film.height(), [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y)
      for (int x = 0; x < film.width(); ++x) {
        size_t p = static_cast<size_t>(y) * film.width() + x;
        uint32_t n = film.samples(x, y);
        in.has_estimate[p] = n > 0;
        in.variance[p] = n >= 2 ? static_cast<float>(film.variance_of_mean(x, y)) : -1.0f;
      }
  });
  return in;
}

namespace {

// Runs the filter's iterations on `in`, calling level(i, remodulate) after iteration i (1 to
// params.iterations), where remodulate(p) is pixel p of that level's image. Callers keep whole
// levels or only the pixels they show.
template <class Level>
void run_iterations(const NoisyImage& in, const DenoiseFeatures& f, const DenoiseParams& params,
                    const GuideWeights* guides, Level&& level) {
  const int w = in.color.width(), h = in.color.height();
  const size_t pixels = static_cast<size_t>(w) * h;
  check_features(f, w, h);
  if (in.variance.size() != pixels || in.has_estimate.size() != pixels)
    throw std::invalid_argument("denoise: image, variance and features differ in size");
  check_params(params);
  if (guides && !guides->fits(w, h, params))
    throw std::invalid_argument(
        "denoise: the guide weights were computed for another size, fewer iterations or other "
        "guide parameters");

  const FloatPlane variance = completed_variance(in);
  const std::vector<uint8_t> kept = near_emitters(f);
  // Without shared guide weights each iteration's are computed into one buffer in turn.
  std::optional<GuidePlanes> guide;
  std::vector<uint16_t> own_table;
  if (!guides) {
    guide.emplace(f, params);
    own_table.resize(table_halves(w, h));
  }
  Layer a(pixels);
  for_pixels(w, h, [&](size_t p) {
    const Color& c = in.color.data()[p];
    const float d = demodulator(luminance(f.albedo[p]));
    a.r[p] = c.x * demodulator(f.albedo[p].x);
    a.g[p] = c.y * demodulator(f.albedo[p].y);
    a.b[p] = c.z * demodulator(f.albedo[p].z);
    a.variance[p] = variance[p] * d * d;
    a.valid[p] = in.has_estimate[p] && !kept[p] ? 1.0f : 0.0f;
  });
  // The change, remodulated: a pixel the filter left alone keeps its exact value; one without
  // an estimate gets the filtered light times its albedo.
  auto remodulated = [&](size_t p) {
    const Color& c = in.color.data()[p];
    if (kept[p]) return c;
    const Color& albedo = f.albedo[p];
    const Color filtered(a.r[p], a.g[p], a.b[p]);
    const Color scale(std::max(albedo.x, kMinAlbedo), std::max(albedo.y, kMinAlbedo),
                      std::max(albedo.z, kMinAlbedo));
    const Color original(c.x * demodulator(albedo.x), c.y * demodulator(albedo.y),
                         c.z * demodulator(albedo.z));
    return in.has_estimate[p] ? c + (filtered - original) * scale : filtered * scale;
  };

  Layer b(pixels);
  FloatPlane lum(pixels), noise(pixels);
  for (int i = 0; i < params.iterations; ++i) {
    for_pixels(w, h, [&](size_t p) { lum[p] = luminance(Color(a.r[p], a.g[p], a.b[p])); });
    blur_variance(a, w, h, params.sigma_luminance * params.sigma_luminance, noise);
    const uint16_t* table = guides ? guides->table(i) : own_table.data();
    if (!guides) build_guide_table(*guide, w, h, 1 << i, params, own_table.data());
    atrous_step(a, b, lum, noise, table, w, h, 1 << i, params);
    std::swap(a, b);
    level(i + 1, remodulated);
  }
}

}  // namespace

std::vector<Image> denoise_levels(const NoisyImage& in, const DenoiseFeatures& f,
                                  const DenoiseParams& params, int first_kept,
                                  const GuideWeights* guides) {
  const int w = in.color.width(), h = in.color.height();
  std::vector<Image> levels;
  if (first_kept <= 0) levels.push_back(in.color);
  run_iterations(in, f, params, guides, [&](int i, auto&& remodulated) {
    if (i < first_kept) return;
    Image& out = levels.emplace_back(w, h);
    for_pixels(w, h, [&](size_t p) { out.data()[p] = remodulated(p); });
  });
  if (levels.empty()) levels.push_back(in.color);  // no iterations: the input itself
  return levels;
}

Image denoise_chosen(const NoisyImage& in, const DenoiseFeatures& f, const DenoiseParams& params,
                     const std::vector<uint8_t>& strength, const GuideWeights* guides) {
  const int w = in.color.width(), h = in.color.height();
  if (strength.size() != static_cast<size_t>(w) * h)
    throw std::invalid_argument("denoise: the strengths differ in size from the image");
  Image out = in.color;  // strength 0
  const uint8_t strongest =
      strength.empty() ? 0 : *std::max_element(strength.begin(), strength.end());
  if (strongest > params.iterations)
    throw std::invalid_argument("denoise: strength " + std::to_string(strongest) +
                                " is beyond the filter's iterations");
  if (strongest == 0) return out;
  DenoiseParams only_needed = params;
  only_needed.iterations = strongest;
  run_iterations(in, f, only_needed, guides, [&](int i, auto&& remodulated) {
    for_pixels(w, h, [&](size_t p) {
      if (strength[p] == i) out.data()[p] = remodulated(p);
    });
  });
  return out;
}

Image denoise(const NoisyImage& in, const DenoiseFeatures& f, const DenoiseParams& params,
              const GuideWeights* guides) {
  return std::move(denoise_levels(in, f, params, params.iterations, guides).back());
}

}  // namespace tuneray
