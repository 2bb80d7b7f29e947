// Internal to the denoiser (denoiser.cpp and denoiser_guides.cpp): its constants, the
// eight-lane helpers, the walk over a row's chunks of eight pixels and their 5x5 taps, the
// guides as float planes and the layout of the guide-weight tables (GuideWeights).
#pragma once

#include <immintrin.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>

#include "render/denoiser.h"
#include "render/staggered_allocator.h"

namespace tuneray::denoise_detail {

// The B3-spline kernel (1, 4, 6, 4, 1) / 16 by distance from the centre.
inline constexpr float kB3[3] = {3.0f / 8.0f, 1.0f / 4.0f, 1.0f / 16.0f};
// Exponents beyond this give weights below 1e-34: zero for our purposes.
inline constexpr float kMaxExponent = 80.0f;
// Taps 2^15 pixels apart reach beyond any image we render.
inline constexpr int kMostIterations = 16;
// Added to the noise variance: without noise only an (almost) equal luminance passes.
inline constexpr float kTinyNoise = 1e-20f;
// Added to a tap's squared distance from the centre's point, so a tap at the same point (the
// centre itself) lies on its plane, not at 0/0.
inline constexpr float kTinyChord = 1e-30f;

// e^-x for x in [0, kMaxExponent] on eight lanes, to ~2e-4 relative: 2^(integer part) from
// the exponent bits times a polynomial for 2^(fraction). A weight needs no more precision,
// and the library exp would be most of the filter's time. log2(e^-x) + 127 is in [11, 127], so
// its floor is the biased exponent of a normal float. The polynomial is evaluated in Estrin's
// scheme (pairs, then powers of f): it lies on every tap's critical path, and this halves its
// chain of dependent multiplies.
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
inline void for_rows(int height, F&& rows) {
  tbb::parallel_for(tbb::blocked_range<int>(0, height),
                    [&](const tbb::blocked_range<int>& r) { rows(r.begin(), r.end()); });
}

// Calls visit(p) for every pixel, rows spread over all cores: every shown frame filters afresh,
// and the per-pixel passes around the iterations, run serially, left the other core idle.
template <class F>
inline void for_pixels(int w, int h, F&& visit) {
  for_rows(h, [&](int y0, int y1) {
    for (size_t p = static_cast<size_t>(y0) * w; p < static_cast<size_t>(y1) * w; ++p) visit(p);
  });
}

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
// much again in loop instructions, and this sits on each guide weight's critical path.
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

// Lanes [lo, hi) of a chunk.
inline __m256i lanes_between(int lo, int hi) {
  const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
  const __m256i from = _mm256_cmpgt_epi32(_mm256_set1_epi32(lo), lane);  // lane < lo
  return _mm256_andnot_si256(from, _mm256_cmpgt_epi32(_mm256_set1_epi32(hi), lane));
}

// A chunk: up to eight pixels of a row from (x0, y), index c = y * w + x0.
struct Chunk {
  int x0, y, lanes;
  ptrdiff_t c;
  __m256i mask;  // its lanes
  bool whole;    // all eight
};

// Calls visit(chunk) for every chunk of the image, rows spread over the threads.
template <class F>
inline void for_chunks(int w, int h, F&& visit) {
  for_rows(h, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y)
      for (int x0 = 0; x0 < w; x0 += 8) {
        const int lanes = std::min(8, w - x0);
        visit(Chunk{x0, y, lanes, static_cast<ptrdiff_t>(y) * w + x0, lanes_between(0, lanes),
                    lanes == 8});
      }
  });
}

// Calls tap(kx, ky, q, mask, full) for each of the chunk's 5x5 taps, `step` pixels apart, that
// some lane's tap lies inside the image for (q: the first lane's tap's index, mask: the lanes
// whose tap exists, full: all eight), and row_done(ky) after each row of taps inside it.
template <class Tap, class RowDone>
inline void for_taps(const Chunk& k, int w, int h, int step, Tap&& tap, RowDone&& row_done) {
  for (int ky = -2; ky <= 2; ++ky) {
    const int yy = k.y + ky * step;
    if (yy < 0 || yy >= h) continue;
    const ptrdiff_t row = static_cast<ptrdiff_t>(yy) * w + k.x0;
    for (int kx = -2; kx <= 2; ++kx) {
      const int off = kx * step;
      const int lo = std::max(0, -off - k.x0), hi = std::min(k.lanes, w - off - k.x0);
      if (lo >= hi) continue;
      tap(kx, ky, row + off, lanes_between(lo, hi), lo == 0 && hi == 8);
    }
    row_done(ky);
  }
}

// One iteration's guide weights as half floats: per chunk, in row order, its 25 taps' weights
// one after another (eight lanes each, tap (kx, ky) at index (ky + 2) * 5 + kx + 2), so the tap
// loop reads them as one stream. Taps outside the image weigh 0.
inline constexpr int kTaps = 25;
inline size_t chunks_per_row(int w) {
  return (static_cast<size_t>(w) + 7) / 8;
}
inline size_t table_halves(int w, int h) {
  return chunks_per_row(w) * h * kTaps * 8;
}
inline size_t chunk_table_offset(int w, const Chunk& k) {
  return (static_cast<size_t>(k.y) * chunks_per_row(w) + static_cast<size_t>(k.x0 / 8)) * kTaps * 8;
}
inline int tap_index(int kx, int ky) {
  return (ky + 2) * 5 + kx + 2;
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

// Fills `table` (table_halves(w, h) halves) with the guide weights of the iteration whose taps
// are `step` pixels apart.
void build_guide_table(const GuidePlanes& guide, int w, int h, int step,
                       const DenoiseParams& params, uint16_t* table);

// Throw std::invalid_argument naming what is wrong: features that are not w x h, parameters
// out of their ranges.
void check_features(const DenoiseFeatures& f, int w, int h);
void check_params(const DenoiseParams& params);

}  // namespace tuneray::denoise_detail
