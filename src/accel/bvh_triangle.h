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
#include <utility>

#include "math/vec.h"

namespace tuneray::bvh {

struct TraversalRay {
  Vec3f org, dir;
  float tnear = 0, tfar = kInf;
  float inv[3];      // 1 / dir, tiny components replaced by ±1e-18 to avoid 0 * inf
  float org_inv[3];  // org * inv (the fast box test is one fmsub per plane)
  int near_row[3];   // row of the near plane per axis: a (dir >= 0) or a + 3
  // Watertight test: ray-space axes and shear.
  int kx = 0, ky = 1, kz = 2;
  float sx = 0, sy = 0, sz = 1;
};

inline TraversalRay make_traversal_ray(const Vec3f& org, const Vec3f& dir, float tnear,
                                       float tfar) {
  TraversalRay r;
  r.org = org;
  r.dir = dir;
  r.tnear = tnear;
  r.tfar = tfar;
  for (int a = 0; a < 3; ++a) {
    float d = dir[a];
    if (std::fabs(d) < 1e-18f) d = std::signbit(d) ? -1e-18f : 1e-18f;
    r.inv[a] = 1.0f / d;
    r.org_inv[a] = org[a] * r.inv[a];
    r.near_row[a] = d >= 0 ? a : a + 3;
  }
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

// Lanes (bits 0..3) of the pack hit in (tnear, tfar); fills t/u/v of those lanes.
inline int intersect_pack_mt(const float (*p)[4], const TraversalRay& r, float tfar,
                             TriangleHit out[4]) {
  const __m128 ox = _mm_set1_ps(r.org.x), oy = _mm_set1_ps(r.org.y), oz = _mm_set1_ps(r.org.z);
  const __m128 dx = _mm_set1_ps(r.dir.x), dy = _mm_set1_ps(r.dir.y), dz = _mm_set1_ps(r.dir.z);
  const __m128 e1x = _mm_load_ps(p[3]), e1y = _mm_load_ps(p[4]), e1z = _mm_load_ps(p[5]);
  const __m128 e2x = _mm_load_ps(p[6]), e2y = _mm_load_ps(p[7]), e2z = _mm_load_ps(p[8]);
  // P = D x E2, det = E1 . P
  const __m128 px = _mm_fmsub_ps(dy, e2z, _mm_mul_ps(dz, e2y));
  const __m128 py = _mm_fmsub_ps(dz, e2x, _mm_mul_ps(dx, e2z));
  const __m128 pz = _mm_fmsub_ps(dx, e2y, _mm_mul_ps(dy, e2x));
  const __m128 det = _mm_fmadd_ps(e1x, px, _mm_fmadd_ps(e1y, py, _mm_mul_ps(e1z, pz)));
  // T = O - v0, u = T . P, Q = T x E1, v = D . Q, t = E2 . Q
  const __m128 tx = _mm_sub_ps(ox, _mm_load_ps(p[0]));
  const __m128 ty = _mm_sub_ps(oy, _mm_load_ps(p[1]));
  const __m128 tz = _mm_sub_ps(oz, _mm_load_ps(p[2]));
  const __m128 sign = _mm_and_ps(det, _mm_set1_ps(-0.0f));
  const __m128 abs_det = _mm_xor_ps(det, sign);
  const __m128 u = _mm_xor_ps(_mm_fmadd_ps(tx, px, _mm_fmadd_ps(ty, py, _mm_mul_ps(tz, pz))), sign);
  const __m128 qx = _mm_fmsub_ps(ty, e1z, _mm_mul_ps(tz, e1y));
  const __m128 qy = _mm_fmsub_ps(tz, e1x, _mm_mul_ps(tx, e1z));
  const __m128 qz = _mm_fmsub_ps(tx, e1y, _mm_mul_ps(ty, e1x));
  const __m128 v = _mm_xor_ps(_mm_fmadd_ps(dx, qx, _mm_fmadd_ps(dy, qy, _mm_mul_ps(dz, qz))), sign);
  const __m128 t =
      _mm_xor_ps(_mm_fmadd_ps(e2x, qx, _mm_fmadd_ps(e2y, qy, _mm_mul_ps(e2z, qz))), sign);
  const __m128 zero = _mm_setzero_ps();
  __m128 valid = _mm_cmpgt_ps(abs_det, zero);
  valid = _mm_and_ps(valid, _mm_cmpge_ps(u, zero));
  valid = _mm_and_ps(valid, _mm_cmpge_ps(v, zero));
  valid = _mm_and_ps(valid, _mm_cmple_ps(_mm_add_ps(u, v), abs_det));
  valid = _mm_and_ps(valid, _mm_cmpgt_ps(t, _mm_mul_ps(abs_det, _mm_set1_ps(r.tnear))));
  valid = _mm_and_ps(valid, _mm_cmplt_ps(t, _mm_mul_ps(abs_det, _mm_set1_ps(tfar))));
  int mask = _mm_movemask_ps(valid);
  if (mask) {
    const __m128 rcp = _mm_div_ps(_mm_set1_ps(1.0f), abs_det);
    alignas(16) float ts[4], us[4], vs[4];
    _mm_store_ps(ts, _mm_mul_ps(t, rcp));
    _mm_store_ps(us, _mm_mul_ps(u, rcp));
    _mm_store_ps(vs, _mm_mul_ps(v, rcp));
    for (int i = 0; i < 4; ++i) out[i] = {ts[i], us[i], vs[i]};
  }
  return mask;
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
