#include "render/denoiser.h"

#include "render/staggered_allocator.h"

#include <immintrin.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <type_traits>

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
// Added to a tap's squared distance from the centre's point, so a tap at the same point (the
// centre itself) lies on its plane, not at 0/0.
constexpr float kTinyChord = 1e-30f;

float demodulator(float albedo) {
  return 1.0f / std::max(albedo, kMinAlbedo);
}

// e^-x for x in [0, kMaxExponent] on eight lanes, to ~2e-4 relative: 2^(integer part) from
// the exponent bits times a polynomial for 2^(fraction). A weight needs no more precision,
// and the library exp would be most of the filter's time. log2(e^-x) + 127 is in [11, 127]:
// positive, so truncation is the floor, and the integer part is the biased exponent of a
// normal float.
// The polynomial is evaluated in Estrin's scheme (pairs, then powers of f): it lies on every
// tap's critical path, and this halves its chain of dependent multiplies.
inline __m256 exp_neg8(__m256 x) {
  const __m256 t = _mm256_fnmadd_ps(x, _mm256_set1_ps(1.44269504f), _mm256_set1_ps(127.0f));
  const __m256 whole = _mm256_round_ps(t, _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC);
  const __m256 f = _mm256_sub_ps(t, whole);
  const __m256i i = _mm256_cvttps_epi32(whole);
  auto pair = [&](float c0, float c1) {
    return _mm256_fmadd_ps(f, _mm256_set1_ps(c1), _mm256_set1_ps(c0));
  };
  const __m256 f2 = _mm256_mul_ps(f, f);
  const __m256 low = _mm256_fmadd_ps(f2, pair(0.240227f, 0.0555041f), pair(1.0f, 0.693147f));
  const __m256 p = _mm256_fmadd_ps(_mm256_mul_ps(f2, f2), pair(0.00961813f, 1.33336e-3f), low);
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
  // Position; 0 everywhere without the guide (every tap then lies on the centre's plane).
  FloatPlane px, py, pz;
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
    px.assign(pixels, 0.0f);
    py.assign(pixels, 0.0f);
    pz.assign(pixels, 0.0f);
    for (size_t p = 0; p < f.position.size(); ++p) {
      px[p] = f.position[p].x;
      py[p] = f.position[p].y;
      pz[p] = f.position[p].z;
    }
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

// The filter's per-step constants.
struct StepConstants {
  float inv_albedo_sigma2, visibility_sigma2, plane_sigma2;
  int normal_squarings;
  bool first_order;
};

// Plane `v` at pixels [i, i + 8) where `mask` is set, 0 elsewhere (never read there); kFull:
// every lane is set.
template <bool kFull>
inline __m256 load8(const FloatPlane& v, ptrdiff_t i, __m256i mask) {
  if constexpr (kFull) {
    return _mm256_loadu_ps(v.data() + i);
  } else {
    // Lanes outside the mask may lie before the plane or past it; maskload does not touch them.
    return _mm256_maskload_ps(v.data() + i, mask);
  }
}

inline __m256 load8(const FloatPlane& v, ptrdiff_t i, __m256i mask, bool full) {
  return full ? load8<true>(v, i, mask) : load8<false>(v, i, mask);
}

inline void store8(FloatPlane& v, ptrdiff_t i, __m256i mask, bool full, __m256 value) {
  if (full)
    _mm256_storeu_ps(v.data() + i, value);
  else
    _mm256_maskstore_ps(v.data() + i, mask, value);
}

// v^(2^n). The default's squarings are unrolled: a counted loop around one multiply costs as
// much again in loop instructions, and this sits on every tap's critical path.
inline __m256 repeated_squares(__m256 v, int n) {
  constexpr int kDefault = DenoiseParams{}.normal_squarings;
  if (n == kDefault) {
#pragma GCC unroll 8
    for (int i = 0; i < kDefault; ++i) v = _mm256_mul_ps(v, v);
    return v;
  }
  for (int i = 0; i < n; ++i) v = _mm256_mul_ps(v, v);
  return v;
}

// The chunk's own guide values, loaded once for its 25 taps (lanes past the row's end read 0;
// a tap's lanes outside its mask weigh 0 whatever the centre holds there). The spreads are the
// centre's share of the visibility and luminance spreads with their constant terms added.
struct CentreGuide {
  __m256 nx, ny, nz, ar, ag, ab, px, py, pz, vis, vis_spread, lum, spread;
  CentreGuide(const GuidePlanes& g, const FloatPlane& luminance, const FloatPlane& noise,
              float visibility_sigma2, ptrdiff_t c, __m256i mask, bool whole) {
    auto at = [&](const FloatPlane& v) { return load8(v, c, mask, whole); };
    nx = at(g.nx), ny = at(g.ny), nz = at(g.nz);
    ar = at(g.ar), ag = at(g.ag), ab = at(g.ab);
    px = at(g.px), py = at(g.py), pz = at(g.pz);
    vis = at(g.vis), lum = at(luminance);
    vis_spread = _mm256_add_ps(at(g.vis_noise), _mm256_set1_ps(visibility_sigma2));
    spread = _mm256_add_ps(at(noise), _mm256_set1_ps(kTinyNoise));
  }
};

// Adds the tap at offset (kx, ky) steps, pixel index `q` for the chunk's first lane, to the
// row sums of the eight pixels from index `c` on. `mask` marks lanes whose pixel and tap exist.
// The whole chunk's taps inside the image (kFull) and the first-order sums are known when the
// loop is compiled, so the hot path has neither masks nor branches.
template <bool kFull, bool kFirstOrder>
inline void add_tap(const Layer& in, const FloatPlane& lum, const FloatPlane& noise,
                    const GuidePlanes& guide, const CentreGuide& centre, const StepConstants& k,
                    ptrdiff_t q, __m256i mask, int kx, int ky, __m256 base_r, __m256 base_g,
                    __m256 base_b, __m256 counts, RowSums& s) {
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
  const __m256 dl = _mm256_andnot_ps(_mm256_set1_ps(-0.0f), _mm256_sub_ps(centre.lum, tap(lum)));
  const __m256 spread = _mm256_add_ps(centre.spread, tap(noise));
  const __m256 luminance = _mm256_mul_ps(_mm256_mul_ps(dl, counts), _mm256_rsqrt_ps(spread));
  // min() also turns NaN (inf - inf) into the largest exponent: it returns its second operand.
  const __m256 exponent = _mm256_min_ps(
      _mm256_add_ps(_mm256_add_ps(luminance, albedo), _mm256_add_ps(visibility, plane)),
      _mm256_set1_ps(kMaxExponent));
  const float kernel = kB3[std::abs(ky)] * kB3[std::abs(kx)];
  const __m256 wq = _mm256_mul_ps(_mm256_mul_ps(_mm256_set1_ps(kernel), wn),
                                  _mm256_mul_ps(tap(in.valid), exp_neg8(exponent)));
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
                 const GuidePlanes& guide, int w, int h, int step, const DenoiseParams& params) {
  const StepConstants k{1.0f / (params.sigma_albedo * params.sigma_albedo),
                        params.sigma_visibility * params.sigma_visibility,
                        params.sigma_plane * params.sigma_plane, params.normal_squarings,
                        params.first_order};
  const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
  // Lanes [lo, hi) of a chunk.
  auto lanes_between = [&](int lo, int hi) {
    const __m256i from = _mm256_cmpgt_epi32(_mm256_set1_epi32(lo), lane);  // lane < lo
    return _mm256_andnot_si256(from, _mm256_cmpgt_epi32(_mm256_set1_epi32(hi), lane));
  };
  for_rows(h, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      const ptrdiff_t row = static_cast<ptrdiff_t>(y) * w;
      for (int x0 = 0; x0 < w; x0 += 8) {
        const int lanes = std::min(8, w - x0);
        const ptrdiff_t c = row + x0;
        const __m256i centre_mask = lanes_between(0, lanes);
        const bool whole = lanes == 8;
        auto at_centre = [&](const FloatPlane& v) { return load8(v, c, centre_mask, whole); };
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
        const CentreGuide centre(guide, lum, noise, k.visibility_sigma2, c, centre_mask, whole);
        TapSums s{};
        for (int ky = -2; ky <= 2; ++ky) {
          const int yy = y + ky * step;
          if (yy < 0 || yy >= h) continue;
          RowSums row_sums{};
          for (int kx = -2; kx <= 2; ++kx) {
            const int off = kx * step;
            // Lanes whose tap lies inside the row.
            const int lo = std::max(0, -off - x0), hi = std::min(lanes, w - off - x0);
            if (lo >= hi) continue;
            const ptrdiff_t q = static_cast<ptrdiff_t>(yy) * w + x0 + off;
            const __m256i mask = lanes_between(lo, hi);
            const bool full = lo == 0 && hi == 8;
            // Both flags as types, so each combination gets its own compiled loop body.
            auto add = [&](auto whole_chunk, auto first_order) {
              add_tap<decltype(whole_chunk)::value, decltype(first_order)::value>(
                  in, lum, noise, guide, centre, k, q, mask, kx, ky, base_r, base_g, base_b, counts,
                  row_sums);
            };
            using Yes = std::true_type;
            using No = std::false_type;
            if (full)
              k.first_order ? add(Yes{}, Yes{}) : add(Yes{}, No{});
            else
              k.first_order ? add(No{}, Yes{}) : add(No{}, No{});
          }
          s.add_row(row_sums, ky, k.first_order);
        }
        // Pixels whose taps all weigh 0 keep their input.
        const __m256 filtered = _mm256_cmp_ps(s.weight, _mm256_setzero_ps(), _CMP_GT_OQ);
        const Coefficients e = fit(s, params);
        auto estimate = [&](__m256 base, __m256 sum, __m256 sum_x, __m256 sum_y) {
          return _mm256_add_ps(
              base,
              _mm256_fmadd_ps(e.e0, sum, _mm256_fmadd_ps(e.e1, sum_x, _mm256_mul_ps(e.e2, sum_y))));
        };
        auto put = [&](FloatPlane& plane, __m256 kept, __m256 value) {
          store8(plane, c, centre_mask, whole, _mm256_blendv_ps(kept, value, filtered));
        };
        put(out.r, r, estimate(base_r, s.r, s.rx, s.ry));
        put(out.g, g, estimate(base_g, s.g, s.gx, s.gy));
        put(out.b, b, estimate(base_b, s.b, s.bx, s.by));
        put(out.variance, at_centre(in.variance),
            _mm256_max_ps(variance_of(s, e), _mm256_setzero_ps()));
        put(out.valid, valid, _mm256_set1_ps(1.0f));
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
      (!f.position.empty() && f.position.size() != pixels) ||
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
