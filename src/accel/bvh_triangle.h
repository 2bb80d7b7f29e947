// Ray-triangle tests of the tuned BVH.
//  - Möller-Trumbore over a pack of 4 precomputed triangles (v0, e1, e2) with SSE, divisions
//    only for the lanes that hit;
//  - the watertight test of Woop, Benthin and Wald (JCGT 2013): shear into ray space, edge
//    functions from float coordinates evaluated in double, where every product is exact, so the
//    two triangles of a shared edge see exactly opposite values whatever the compiler contracts.
// u and v are the weights of vertices 1 and 2 (Embree's convention).
#pragma once

#include <immintrin.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <type_traits>
#include <utility>

#include "math/vec.h"

namespace tuneray::bvh {

struct TraversalRay {
  Vec3f org, dir;
  float tnear = 0, tfar = kInf;
  float inv[3];      // 1 / dir, tiny components replaced by ±1e-18 to avoid 0 * inf
  float org_inv[3];  // org * inv (the fast box test is one fmsub per plane)
  int near_row[3];   // row of the near plane per axis: a (dir >= 0) or a + 3
  int far_row[3];    // the other row of the axis (set once per ray, not at every node)
  // Watertight test: ray-space axes and shear.
  int kx = 0, ky = 1, kz = 2;
  float sx = 0, sy = 0, sz = 1;
};

// `watertight`: also set up the shear of the watertight test (three more divisions, which the
// fast test does not need). Always inlined, as the pack tests below: each copy of the single-ray
// kernels (AVX2, AVX-512) then computes them in its own instruction set, where GCC, with both
// copies in one file, called one out-of-line AVX2 copy from both.
[[gnu::always_inline]] inline TraversalRay make_traversal_ray(const Vec3f& org, const Vec3f& dir,
                                                              float tnear, float tfar,
                                                              bool watertight = true) {
  TraversalRay r;
  r.org = org;
  r.dir = dir;
  // Negative (or NaN) starts are clamped to +0, as Embree requires tnear >= 0: the box test's
  // integer order is exact only for a non-negative entry.
  r.tnear = tnear > 0.0f ? tnear : 0.0f;
  r.tfar = tfar;
  for (int a = 0; a < 3; ++a) {
    float d = dir[a];
    if (std::fabs(d) < 1e-18f) d = std::signbit(d) ? -1e-18f : 1e-18f;
    r.inv[a] = 1.0f / d;
    r.org_inv[a] = org[a] * r.inv[a];
    r.near_row[a] = d >= 0 ? a : a + 3;
    r.far_row[a] = d >= 0 ? a + 3 : a;
  }
  if (!watertight) return r;
  Vec3f ad{std::fabs(dir.x), std::fabs(dir.y), std::fabs(dir.z)};
  r.kz = ad.x > ad.y ? (ad.x > ad.z ? 0 : 2) : (ad.y > ad.z ? 1 : 2);
  r.kx = (r.kz + 1) % 3;
  r.ky = (r.kx + 1) % 3;
  if (dir[r.kz] < 0) std::swap(r.kx, r.ky);
  r.sx = dir[r.kx] / dir[r.kz];
  r.sy = dir[r.ky] / dir[r.kz];
  r.sz = 1.0f / dir[r.kz];
  return r;
}

struct TriangleHit {
  float t, u, v;
};

// t, u, v of the lanes a pack test hit, one row each: the test stores its vectors as they are
// (handing out one {t, u, v} per lane cost a transposition of three vectors on every hit).
struct LaneHits {
  alignas(32) float t[8], u[8], v[8];
};

// The Möller-Trumbore test is written once over a SIMD width: 4 lanes (SSE, one pack) or 8 lanes
// (AVX2, two packs side by side). Each lane computes exactly the same operations at either width,
// so a triangle gives the same t, u, v whichever path tests it. The traversal's box test of 4- and
// 8-wide nodes uses the same lanes.
// max_bits, min_bits and le_bits order floats by their bits read as signed integers (Embree's
// AVX2 node test does the same). That is the float order among non-negative values, and every
// negative value orders below them, so a box test whose entry includes tnear >= +0 gets the exact
// entry distance and the exact answer (an exit below +0 misses either way). On Intel cores the
// integer forms take 1 cycle where vmaxps, vminps and vcmpps take 4, and they sit on the chain
// from one node's planes to the next node's address.
struct Lanes4 {
  using V = __m128;
  static constexpr int kWidth = 4;
  static V set1(float x) { return _mm_set1_ps(x); }
  static V add(V a, V b) { return _mm_add_ps(a, b); }
  static V sub(V a, V b) { return _mm_sub_ps(a, b); }
  static V mul(V a, V b) { return _mm_mul_ps(a, b); }
  static V div(V a, V b) { return _mm_div_ps(a, b); }
  static V fmadd(V a, V b, V c) { return _mm_fmadd_ps(a, b, c); }
  static V fmsub(V a, V b, V c) { return _mm_fmsub_ps(a, b, c); }
  static V min(V a, V b) { return _mm_min_ps(a, b); }
  static V max(V a, V b) { return _mm_max_ps(a, b); }
  static V and_(V a, V b) { return _mm_and_ps(a, b); }
  static V xor_(V a, V b) { return _mm_xor_ps(a, b); }
  static V gt(V a, V b) { return _mm_cmpgt_ps(a, b); }
  static V ge(V a, V b) { return _mm_cmpge_ps(a, b); }
  static V le(V a, V b) { return _mm_cmple_ps(a, b); }
  static V lt(V a, V b) { return _mm_cmplt_ps(a, b); }
  static V eq(V a, V b) { return _mm_cmpeq_ps(a, b); }
  static int movemask(V a) { return _mm_movemask_ps(a); }
  static V max_bits(V a, V b) { return _mm_castsi128_ps(_mm_max_epi32(bits(a), bits(b))); }
  static V min_bits(V a, V b) { return _mm_castsi128_ps(_mm_min_epi32(bits(a), bits(b))); }
  static int le_bits(V a, V b) {
    return movemask(_mm_castsi128_ps(_mm_cmpgt_epi32(bits(a), bits(b)))) ^ 0xf;
  }
  static __m128i bits(V a) { return _mm_castps_si128(a); }
  static void store(float* p, V a) { _mm_store_ps(p, a); }
  static V load(const float* p) { return _mm_load_ps(p); }
  // 4 bytes as origin + q * scale (the compact node planes).
  static V decode_u8(const uint8_t* q, V scale, V origin) {
    int32_t packed;
    std::memcpy(&packed, q, 4);
    const __m128 f = _mm_cvtepi32_ps(_mm_cvtepu8_epi32(_mm_cvtsi32_si128(packed)));
    return _mm_fmadd_ps(f, scale, origin);
  }
};

struct Lanes8 {
  using V = __m256;
  static constexpr int kWidth = 8;
  static V set1(float x) { return _mm256_set1_ps(x); }
  static V add(V a, V b) { return _mm256_add_ps(a, b); }
  static V sub(V a, V b) { return _mm256_sub_ps(a, b); }
  static V mul(V a, V b) { return _mm256_mul_ps(a, b); }
  static V div(V a, V b) { return _mm256_div_ps(a, b); }
  static V fmadd(V a, V b, V c) { return _mm256_fmadd_ps(a, b, c); }
  static V fmsub(V a, V b, V c) { return _mm256_fmsub_ps(a, b, c); }
  static V min(V a, V b) { return _mm256_min_ps(a, b); }
  static V max(V a, V b) { return _mm256_max_ps(a, b); }
  static V and_(V a, V b) { return _mm256_and_ps(a, b); }
  static V xor_(V a, V b) { return _mm256_xor_ps(a, b); }
  static V gt(V a, V b) { return _mm256_cmp_ps(a, b, _CMP_GT_OQ); }
  static V ge(V a, V b) { return _mm256_cmp_ps(a, b, _CMP_GE_OQ); }
  static V le(V a, V b) { return _mm256_cmp_ps(a, b, _CMP_LE_OQ); }
  static V lt(V a, V b) { return _mm256_cmp_ps(a, b, _CMP_LT_OQ); }
  static V eq(V a, V b) { return _mm256_cmp_ps(a, b, _CMP_EQ_OQ); }
  static int movemask(V a) { return _mm256_movemask_ps(a); }
  static V max_bits(V a, V b) { return _mm256_castsi256_ps(_mm256_max_epi32(bits(a), bits(b))); }
  static V min_bits(V a, V b) { return _mm256_castsi256_ps(_mm256_min_epi32(bits(a), bits(b))); }
  static int le_bits(V a, V b) {
    return movemask(_mm256_castsi256_ps(_mm256_cmpgt_epi32(bits(a), bits(b)))) ^ 0xff;
  }
  static __m256i bits(V a) { return _mm256_castps_si256(a); }
  static void store(float* p, V a) { _mm256_storeu_ps(p, a); }
  static V load(const float* p) { return _mm256_load_ps(p); }
  // 8 bytes as origin + q * scale (the compact node planes).
  static V decode_u8(const uint8_t* q, V scale, V origin) {
    const __m128i bytes = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(q));
    return _mm256_fmadd_ps(_mm256_cvtepi32_ps(_mm256_cvtepu8_epi32(bytes)), scale, origin);
  }
};

// The lanes of an N-wide node's box test (N = 4 or 8).
template <int N>
using LanesOf = std::conditional_t<N == 8, Lanes8, Lanes4>;

// rows: v0.xyz, e1.xyz, e2.xyz of kWidth triangles. Returns the lanes hit in (tnear, tfar) and
// fills t/u/v of those lanes.
template <class L>
[[gnu::always_inline]] inline int intersect_lanes_mt(const typename L::V (&rows)[9],
                                                     const TraversalRay& r, float tfar,
                                                     LaneHits& out) {
  using V = typename L::V;
  const V ox = L::set1(r.org.x), oy = L::set1(r.org.y), oz = L::set1(r.org.z);
  const V dx = L::set1(r.dir.x), dy = L::set1(r.dir.y), dz = L::set1(r.dir.z);
  const V e1x = rows[3], e1y = rows[4], e1z = rows[5];
  const V e2x = rows[6], e2y = rows[7], e2z = rows[8];
  // P = D x E2, det = E1 . P
  const V px = L::fmsub(dy, e2z, L::mul(dz, e2y));
  const V py = L::fmsub(dz, e2x, L::mul(dx, e2z));
  const V pz = L::fmsub(dx, e2y, L::mul(dy, e2x));
  const V det = L::fmadd(e1x, px, L::fmadd(e1y, py, L::mul(e1z, pz)));
  // T = O - v0, u = T . P, Q = T x E1, v = D . Q, t = E2 . Q
  const V tx = L::sub(ox, rows[0]);
  const V ty = L::sub(oy, rows[1]);
  const V tz = L::sub(oz, rows[2]);
  const V sign = L::and_(det, L::set1(-0.0f));
  const V abs_det = L::xor_(det, sign);
  const V u = L::xor_(L::fmadd(tx, px, L::fmadd(ty, py, L::mul(tz, pz))), sign);
  const V qx = L::fmsub(ty, e1z, L::mul(tz, e1y));
  const V qy = L::fmsub(tz, e1x, L::mul(tx, e1z));
  const V qz = L::fmsub(tx, e1y, L::mul(ty, e1x));
  const V v = L::xor_(L::fmadd(dx, qx, L::fmadd(dy, qy, L::mul(dz, qz))), sign);
  const V t = L::xor_(L::fmadd(e2x, qx, L::fmadd(e2y, qy, L::mul(e2z, qz))), sign);
  const V zero = L::set1(0.0f);
  V valid = L::gt(abs_det, zero);
  valid = L::and_(valid, L::ge(u, zero));
  valid = L::and_(valid, L::ge(v, zero));
  valid = L::and_(valid, L::le(L::add(u, v), abs_det));
  valid = L::and_(valid, L::gt(t, L::mul(abs_det, L::set1(r.tnear))));
  valid = L::and_(valid, L::lt(t, L::mul(abs_det, L::set1(tfar))));
  const int mask = L::movemask(valid);
  if (mask) {
    const V rcp = L::div(L::set1(1.0f), abs_det);
    L::store(out.t, L::mul(t, rcp));
    L::store(out.u, L::mul(u, rcp));
    L::store(out.v, L::mul(v, rcp));
  }
  return mask;
}

// Lanes (bits 0..3) of one pack hit in (tnear, tfar); fills t/u/v of those lanes.
[[gnu::always_inline]] inline int intersect_pack_mt(const float (*p)[4], const TraversalRay& r,
                                                    float tfar, LaneHits& out) {
  __m128 rows[9];
  for (int k = 0; k < 9; ++k) rows[k] = _mm_load_ps(p[k]);
  return intersect_lanes_mt<Lanes4>(rows, r, tfar, out);
}

// Two packs in one AVX2 pass: lanes 0..3 are pack a, 4..7 pack b.
[[gnu::always_inline]] inline int intersect_two_packs_mt(const float (*a)[4], const float (*b)[4],
                                                         const TraversalRay& r, float tfar,
                                                         LaneHits& out) {
  __m256 rows[9];
  for (int k = 0; k < 9; ++k)
    rows[k] = _mm256_insertf128_ps(_mm256_castps128_ps256(_mm_load_ps(a[k])), _mm_load_ps(b[k]), 1);
  return intersect_lanes_mt<Lanes8>(rows, r, tfar, out);
}

// Scalar Möller-Trumbore on raw vertices (compact layout, non-robust).
inline bool intersect_mt(const Vec3f& a, const Vec3f& b, const Vec3f& c, const TraversalRay& r,
                         float tfar, TriangleHit& out) {
  const Vec3f e1 = b - a, e2 = c - a;
  const Vec3f p = cross(r.dir, e2);
  const float det = dot(e1, p);
  if (det == 0.0f) return false;
  const float inv_det = 1.0f / det;
  const Vec3f tv = r.org - a;
  const float u = dot(tv, p) * inv_det;
  if (!(u >= 0.0f)) return false;
  const Vec3f q = cross(tv, e1);
  const float v = dot(r.dir, q) * inv_det;
  if (!(v >= 0.0f) || u + v > 1.0f) return false;
  const float t = dot(e2, q) * inv_det;
  if (!(t > r.tnear && t < tfar)) return false;
  out = {t, u, v};
  return true;
}

// Watertight test (Woop, Benthin, Wald 2013).
inline bool intersect_watertight(const Vec3f& a, const Vec3f& b, const Vec3f& c,
                                 const TraversalRay& r, float tfar, TriangleHit& out) {
  const Vec3f A = a - r.org, B = b - r.org, C = c - r.org;
  // Shear in double then round: the product of two floats is exact in double, so the result
  // does not depend on whether the compiler fuses the multiply-add.
  auto shear = [](float p, float s, float pz) {
    return static_cast<float>(static_cast<double>(p) - static_cast<double>(s) * pz);
  };
  const float ax = shear(A[r.kx], r.sx, A[r.kz]), ay = shear(A[r.ky], r.sy, A[r.kz]);
  const float bx = shear(B[r.kx], r.sx, B[r.kz]), by = shear(B[r.ky], r.sy, B[r.kz]);
  const float cx = shear(C[r.kx], r.sx, C[r.kz]), cy = shear(C[r.ky], r.sy, C[r.kz]);
  const double U = static_cast<double>(cx) * by - static_cast<double>(cy) * bx;
  const double V = static_cast<double>(ax) * cy - static_cast<double>(ay) * cx;
  const double W = static_cast<double>(bx) * ay - static_cast<double>(by) * ax;
  if ((U < 0 || V < 0 || W < 0) && (U > 0 || V > 0 || W > 0)) return false;
  const double det = U + V + W;
  if (det == 0.0) return false;
  const double az = static_cast<double>(r.sz) * A[r.kz];
  const double bz = static_cast<double>(r.sz) * B[r.kz];
  const double cz = static_cast<double>(r.sz) * C[r.kz];
  const double inv_det = 1.0 / det;
  const float t = static_cast<float>((U * az + V * bz + W * cz) * inv_det);
  if (!(t > r.tnear && t < tfar)) return false;
  out = {t, static_cast<float>(V * inv_det), static_cast<float>(W * inv_det)};
  return true;
}

}  // namespace tuneray::bvh
