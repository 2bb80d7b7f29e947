#include "accel/bvh_packet.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "accel/bvh_traverse_impl.h"
#include "math/transpose8.h"

namespace tuneray::bvh {

namespace {

using namespace detail;

constexpr int kPacketSize = 8;
// A stream with this many rays or fewer left in a subtree continues ray by ray: 8 lanes of box
// tests for a few rays cost more than their single-ray traversals (Embree's hybrid intersectors
// switch at a similar count).
constexpr int kSwitchThreshold = 3;
// Leaves are tested with SIMD over the packet's rays (one pass per triangle) when more than
// this many rays reach them, else ray by ray over the packs (two packs per pass).
constexpr int kLeafSwitchThreshold = 2;

// Up to 8 rays with a common octant, in SoA for the box and triangle tests. A lane's rays as a
// single ray (for the hand-over to the single-ray traversal and the ray-by-ray leaf test) is
// assembled from the rows when first asked for (lane_ray): most camera rays of an open scene end
// in the stream, and filling eight single rays per packet up front was a third of the camera
// streams' time on bmw-m6.
struct Packet {
  TraversalRay ray[kPacketSize];
  uint32_t ray_made = 0;  // bit i: ray[i] is assembled
  alignas(32) float tfar[kPacketSize];
  Hit hit[kPacketSize];
  __m256 inv[3], org_inv[3], tnear, org[3], dir[3];
  int near_row[3], far_row[3];
  // The rows of the single rays: per axis, and the lanes whose clamped direction is >= 0.
  alignas(32) float org_of[3][kPacketSize], dir_of[3][kPacketSize], inv_of[3][kPacketSize],
      org_inv_of[3][kPacketSize], tnear_of[kPacketSize], tfar_of[kPacketSize];
  int nonnegative[3];
};

void set_packet_terms(int octant, Packet& pk);

// The rays must share the octant `octant` (the packet box test picks one near plane per axis).
// Each lane's terms are those make_traversal_ray gives the ray alone (the same clamp of tiny
// direction components, the same correctly rounded division and product), computed 8 at a time.
void make_packet(const Ray* rays, const uint32_t* index, int count, int octant, Packet& pk) {
  for (int i = 0; i < kPacketSize; ++i) {
    // Padding lanes repeat the first ray (so they widen no frustum) but never enter a box nor
    // hit a triangle.
    const Ray& ray = rays[index[i < count ? i : 0]];
    for (int a = 0; a < 3; ++a) {
      pk.org_of[a][i] = ray.org[a];
      pk.dir_of[a][i] = ray.dir[a];
    }
    pk.tnear_of[i] = ray.tnear;
    pk.tfar_of[i] = ray.tfar;
    pk.tfar[i] = i < count ? ray.tfar : -kInf;
    pk.hit[i] = Hit{};
  }
  set_packet_terms(octant, pk);
}

// The packet's SIMD terms from its rows org_of, dir_of and tnear_of.
void set_packet_terms(int octant, Packet& pk) {
  const __m256 sign_bit = _mm256_set1_ps(-0.0f), tiny = _mm256_set1_ps(1e-18f);
  for (int a = 0; a < 3; ++a) {
    const __m256 d = _mm256_load_ps(pk.dir_of[a]);
    const __m256 small = _mm256_cmp_ps(_mm256_andnot_ps(sign_bit, d), tiny, _CMP_LT_OQ);
    const __m256 clamped =
        _mm256_blendv_ps(d, _mm256_or_ps(_mm256_and_ps(d, sign_bit), tiny), small);
    pk.org[a] = _mm256_load_ps(pk.org_of[a]);
    pk.dir[a] = d;
    pk.inv[a] = _mm256_div_ps(_mm256_set1_ps(1.0f), clamped);
    pk.org_inv[a] = _mm256_mul_ps(pk.org[a], pk.inv[a]);
    _mm256_store_ps(pk.inv_of[a], pk.inv[a]);
    _mm256_store_ps(pk.org_inv_of[a], pk.org_inv[a]);
    pk.nonnegative[a] = _mm256_movemask_ps(_mm256_cmp_ps(clamped, _mm256_setzero_ps(), _CMP_GE_OQ));
  }
  pk.tnear = _mm256_load_ps(pk.tnear_of);
  pk.ray_made = 0;
  near_rows_of_octant(octant, pk.near_row);
  for (int a = 0; a < 3; ++a)
    pk.far_row[a] = pk.near_row[a] < 3 ? pk.near_row[a] + 3 : pk.near_row[a] - 3;
}

// make_packet for `count` consecutive rays (a run of one octant): the 8 rays of a full packet
// are read as 8 rows of 8 floats (org, tnear, dir, tfar) and transposed, instead of gathered one
// float at a time. The lanes' terms are computed as above.
void make_packet_run(const Ray* rays, int count, int octant, Packet& pk) {
  static_assert(sizeof(Ray) == 8 * sizeof(float), "a ray is one row of 8 floats");
  if (count < kPacketSize) {
    uint32_t index[kPacketSize];
    for (int i = 0; i < kPacketSize; ++i) index[i] = static_cast<uint32_t>(i < count ? i : 0);
    make_packet(rays, index, count, octant, pk);
    return;
  }
  const float* f = &rays[0].org.x;
  __m256 field[8];
  for (int i = 0; i < 8; ++i) field[i] = _mm256_loadu_ps(f + 8 * i);
  transpose8(field);  // row i was ray i; row j is now field j of the eight rays
  for (int a = 0; a < 3; ++a) {
    _mm256_store_ps(pk.org_of[a], field[a]);
    _mm256_store_ps(pk.dir_of[a], field[4 + a]);
  }
  _mm256_store_ps(pk.tnear_of, field[3]);
  _mm256_store_ps(pk.tfar_of, field[7]);
  _mm256_store_ps(pk.tfar, field[7]);
  for (int i = 0; i < kPacketSize; ++i) pk.hit[i] = Hit{};
  set_packet_terms(octant, pk);
}

// Lane i as the single ray make_traversal_ray makes of it (without the watertight shear, which
// the fast test does not read).
inline const TraversalRay& lane_ray(Packet& pk, int i) {
  if (!((pk.ray_made >> i) & 1)) {
    TraversalRay& r = pk.ray[i];
    for (int a = 0; a < 3; ++a) {
      r.org[a] = pk.org_of[a][i];
      r.dir[a] = pk.dir_of[a][i];
      r.inv[a] = pk.inv_of[a][i];
      r.org_inv[a] = pk.org_inv_of[a][i];
      r.near_row[a] = (pk.nonnegative[a] >> i) & 1 ? a : a + 3;
      r.far_row[a] = (pk.nonnegative[a] >> i) & 1 ? a + 3 : a;
    }
    r.tnear = pk.tnear_of[i];
    r.tfar = pk.tfar_of[i];
    pk.ray_made |= 1u << i;
  }
  return pk.ray[i];
}

inline __m256 lanes_of(uint32_t mask) {
  const __m256i bits = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
  const __m256i selected = _mm256_and_si256(_mm256_set1_epi32(static_cast<int>(mask)), bits);
  return _mm256_castsi256_ps(_mm256_cmpeq_epi32(selected, bits));
}

// The 8 lanes of `v` folded by `op` (_mm_min_ps or _mm_max_ps).
template <__m128 (*op)(__m128, __m128)>
inline float horizontal(__m256 v) {
  __m128 m = op(_mm256_castps256_ps128(v), _mm256_extractf128_ps(v, 1));
  m = op(m, _mm_movehl_ps(m, m));
  m = op(m, _mm_shuffle_ps(m, m, 1));
  return _mm_cvtss_f32(m);
}
inline float horizontal_min(__m256 v) {
  return horizontal<_mm_min_ps>(v);
}
inline float horizontal_max(__m256 v) {
  return horizontal<_mm_max_ps>(v);
}

// One triangle (lane `j` of a pack) against the rays of `active`: the Möller-Trumbore test of
// bvh_triangle.h with the lanes over rays instead of triangles. Each lane performs the same
// operations in the same order as the single-ray test, so a ray gets the same t, u, v bit for
// bit on either path.
inline void intersect_triangle_packet(const TriPack4& p, int j, Packet& pk, uint32_t active) {
  const __m256 e1x = _mm256_broadcast_ss(&p.p[3][j]), e1y = _mm256_broadcast_ss(&p.p[4][j]),
               e1z = _mm256_broadcast_ss(&p.p[5][j]);
  const __m256 e2x = _mm256_broadcast_ss(&p.p[6][j]), e2y = _mm256_broadcast_ss(&p.p[7][j]),
               e2z = _mm256_broadcast_ss(&p.p[8][j]);
  const __m256 dx = pk.dir[0], dy = pk.dir[1], dz = pk.dir[2];
  const __m256 px = _mm256_fmsub_ps(dy, e2z, _mm256_mul_ps(dz, e2y));
  const __m256 py = _mm256_fmsub_ps(dz, e2x, _mm256_mul_ps(dx, e2z));
  const __m256 pz = _mm256_fmsub_ps(dx, e2y, _mm256_mul_ps(dy, e2x));
  const __m256 det = _mm256_fmadd_ps(e1x, px, _mm256_fmadd_ps(e1y, py, _mm256_mul_ps(e1z, pz)));
  const __m256 tx = _mm256_sub_ps(pk.org[0], _mm256_broadcast_ss(&p.p[0][j]));
  const __m256 ty = _mm256_sub_ps(pk.org[1], _mm256_broadcast_ss(&p.p[1][j]));
  const __m256 tz = _mm256_sub_ps(pk.org[2], _mm256_broadcast_ss(&p.p[2][j]));
  const __m256 sign = _mm256_and_ps(det, _mm256_set1_ps(-0.0f));
  const __m256 abs_det = _mm256_xor_ps(det, sign);
  const __m256 u =
      _mm256_xor_ps(_mm256_fmadd_ps(tx, px, _mm256_fmadd_ps(ty, py, _mm256_mul_ps(tz, pz))), sign);
  const __m256 qx = _mm256_fmsub_ps(ty, e1z, _mm256_mul_ps(tz, e1y));
  const __m256 qy = _mm256_fmsub_ps(tz, e1x, _mm256_mul_ps(tx, e1z));
  const __m256 qz = _mm256_fmsub_ps(tx, e1y, _mm256_mul_ps(ty, e1x));
  const __m256 v =
      _mm256_xor_ps(_mm256_fmadd_ps(dx, qx, _mm256_fmadd_ps(dy, qy, _mm256_mul_ps(dz, qz))), sign);
  const __m256 t = _mm256_xor_ps(
      _mm256_fmadd_ps(e2x, qx, _mm256_fmadd_ps(e2y, qy, _mm256_mul_ps(e2z, qz))), sign);
  const __m256 zero = _mm256_setzero_ps();
  // The slack of the single-ray leaf test: a hit at exactly tfar is settled by triangle index.
  const __m256 tfar = _mm256_mul_ps(_mm256_load_ps(pk.tfar), _mm256_set1_ps(kTieSlack));
  __m256 valid = _mm256_and_ps(_mm256_cmp_ps(abs_det, zero, _CMP_GT_OQ), lanes_of(active));
  valid = _mm256_and_ps(valid, _mm256_cmp_ps(u, zero, _CMP_GE_OQ));
  valid = _mm256_and_ps(valid, _mm256_cmp_ps(v, zero, _CMP_GE_OQ));
  valid = _mm256_and_ps(valid, _mm256_cmp_ps(_mm256_add_ps(u, v), abs_det, _CMP_LE_OQ));
  valid = _mm256_and_ps(valid, _mm256_cmp_ps(t, _mm256_mul_ps(abs_det, pk.tnear), _CMP_GT_OQ));
  valid = _mm256_and_ps(valid, _mm256_cmp_ps(t, _mm256_mul_ps(abs_det, tfar), _CMP_LT_OQ));
  uint32_t mask = static_cast<uint32_t>(_mm256_movemask_ps(valid));
  if (!mask) return;
  const __m256 rcp = _mm256_div_ps(_mm256_set1_ps(1.0f), abs_det);
  alignas(32) float ts[kPacketSize], us[kPacketSize], vs[kPacketSize];
  _mm256_store_ps(ts, _mm256_mul_ps(t, rcp));
  _mm256_store_ps(us, _mm256_mul_ps(u, rcp));
  _mm256_store_ps(vs, _mm256_mul_ps(v, rcp));
  const uint32_t prim = p.prim[j];
  while (mask) {
    const int i = __builtin_ctz(mask);
    mask &= mask - 1;
    if (is_nearer_hit(ts[i], prim, pk.tfar[i], pk.hit[i])) {
      pk.tfar[i] = ts[i];
      pk.hit[i] = Hit{ts[i], prim, us[i], vs[i]};
    }
  }
}

inline void intersect_leaf_packet(NodeRef leaf, Packet& pk, uint32_t mask) {
  if (__builtin_popcount(mask) <= kLeafSwitchThreshold) {
    while (mask) {
      const int i = __builtin_ctz(mask);
      mask &= mask - 1;
      intersect_fast_leaf<false, false>(leaf, lane_ray(pk, i), pk.tfar[i], &pk.hit[i]);
    }
    return;
  }
  const TriPack4* packs = leaf_packs(leaf);
  const uint32_t pack_count = leaf_code(leaf);
  for (uint32_t k = 0; k < pack_count; ++k) {
    for (int j = 0; j < 4 && packs[k].prim[j] != kInvalidId; ++j)
      intersect_triangle_packet(packs[k], j, pk, mask);
  }
}

// Conservative bounds of a stream's rays, to cull a node's children for all of them at once
// before their own box tests: per axis the range of the rays' inverse directions and origin terms
// (the rays share an octant, so the near plane of every axis is common).
struct Frustum {
  bool valid = false;  // false: a non-finite term; every child goes on to the rays' own tests
  float inv_lo[3], inv_hi[3], oi_lo[3], oi_hi[3], inv_abs[3], oi_abs[3];
  float tnear_lo;  // no far bound: camera rays have none, and a NaN one would hide the others'
  int near_row[3], far_row[3];
};

// Bound of the rounding of a frustum term against the rays' own fused box tests: a few float
// roundings of terms of magnitude |plane| |inv| + |org inv|, kept far above them.
constexpr float kFrustumSlack = 0x1p-18f;

// Children of `node` that some ray of the frustum may enter: a child whose box the frustum's
// bounds place outside every ray's [tnear, inf) is culled. Loose, but conservative for every
// ray (each bound is padded by kFrustumSlack of its terms' magnitude).
template <int N>
int frustum_children(const FastNode<N>& node, const Frustum& f) {
  using L = LanesOf<N>;
  using V = typename L::V;
  V tmin = L::set1(f.tnear_lo), tmax = L::set1(std::numeric_limits<float>::infinity());
  const V sign = L::set1(-0.0f);
  for (int a = 0; a < 3; ++a) {
    const V near = L::load(node.bounds[f.near_row[a]]), far = L::load(node.bounds[f.far_row[a]]);
    const V inv_lo = L::set1(f.inv_lo[a]), inv_hi = L::set1(f.inv_hi[a]);
    const V inv_abs = L::set1(f.inv_abs[a] * kFrustumSlack);
    const V oi_abs = L::set1(f.oi_abs[a] * kFrustumSlack);
    // The rays' entry along this axis is near * inv - org_inv, linear in each term.
    const V near_lo = L::min(L::mul(near, inv_lo), L::mul(near, inv_hi));
    const V far_hi = L::max(L::mul(far, inv_lo), L::mul(far, inv_hi));
    const V near_slack = L::fmadd(L::and_(L::xor_(near, sign), near), inv_abs, oi_abs);
    const V far_slack = L::fmadd(L::and_(L::xor_(far, sign), far), inv_abs, oi_abs);
    tmin = L::max(tmin, L::sub(L::sub(near_lo, L::set1(f.oi_hi[a])), near_slack));
    tmax = L::min(tmax, L::add(L::sub(far_hi, L::set1(f.oi_lo[a])), far_slack));
  }
  return L::movemask(L::le(tmin, tmax));
}

// Up to 8 packets (64 rays) of one octant; ray i of the stream is lane i % 8 of packet i / 8.
constexpr int kStreamPackets = 8;
constexpr int kStreamSize = kPacketSize * kStreamPackets;
static_assert(kStreamSize == 64, "a stream's rays are the bits of a uint64_t");
struct Stream {
  Packet pk[kStreamPackets];
  int packets = 0;
  Frustum frustum;
};

inline uint32_t packet_bits(uint64_t rays, int p) {
  return static_cast<uint32_t>(rays >> (kPacketSize * p)) & ((1u << kPacketSize) - 1);
}

// From the packets' lanes: padding lanes repeat a ray of their packet, so they widen nothing.
void make_frustum(const Stream& s, Frustum& f) {
  const __m256 inf = _mm256_set1_ps(kInf);
  __m256 inv_lo[3], inv_hi[3], oi_lo[3], oi_hi[3];
  __m256 tnear_lo = inf;
  // x - x is 0 for a finite x, NaN for an infinite or NaN one.
  __m256 finite_terms = _mm256_setzero_ps();
  for (int a = 0; a < 3; ++a) {
    inv_lo[a] = oi_lo[a] = inf;
    inv_hi[a] = oi_hi[a] = _mm256_set1_ps(-kInf);
  }
  for (int p = 0; p < s.packets; ++p) {
    const Packet& pk = s.pk[p];
    for (int a = 0; a < 3; ++a) {
      inv_lo[a] = _mm256_min_ps(inv_lo[a], pk.inv[a]);
      inv_hi[a] = _mm256_max_ps(inv_hi[a], pk.inv[a]);
      oi_lo[a] = _mm256_min_ps(oi_lo[a], pk.org_inv[a]);
      oi_hi[a] = _mm256_max_ps(oi_hi[a], pk.org_inv[a]);
      finite_terms = _mm256_add_ps(finite_terms, _mm256_sub_ps(pk.inv[a], pk.inv[a]));
      finite_terms = _mm256_add_ps(finite_terms, _mm256_sub_ps(pk.org_inv[a], pk.org_inv[a]));
    }
    finite_terms = _mm256_add_ps(finite_terms, _mm256_sub_ps(pk.tnear, pk.tnear));
    tnear_lo = _mm256_min_ps(tnear_lo, pk.tnear);
  }
  for (int a = 0; a < 3; ++a) {
    f.inv_lo[a] = horizontal_min(inv_lo[a]);
    f.inv_hi[a] = horizontal_max(inv_hi[a]);
    f.oi_lo[a] = horizontal_min(oi_lo[a]);
    f.oi_hi[a] = horizontal_max(oi_hi[a]);
    f.inv_abs[a] = std::max(std::fabs(f.inv_lo[a]), std::fabs(f.inv_hi[a]));
    f.oi_abs[a] = std::max(std::fabs(f.oi_lo[a]), std::fabs(f.oi_hi[a]));
    f.near_row[a] = s.pk[0].near_row[a];
    f.far_row[a] = s.pk[0].far_row[a];
  }
  f.tnear_lo = horizontal_min(tnear_lo);
  f.valid =
      _mm256_movemask_ps(_mm256_cmp_ps(finite_terms, _mm256_setzero_ps(), _CMP_EQ_OQ)) == 0xff;
}

// The rays of `entering` that enter child `c`, by the same operations in the same order as the
// single-ray box test, lane by lane; `tmin` gets their entry distances (+inf for the others).
template <int N>
inline uint32_t packet_enters_child(const FastNode<N>& node, int c, const Packet& pk,
                                    __m256 entering, __m256 tfar, __m256& tmin) {
  __m256 tn[3], tf[3];
  for (int a = 0; a < 3; ++a) {
    const __m256 near = _mm256_broadcast_ss(&node.bounds[pk.near_row[a]][c]);
    const __m256 far = _mm256_broadcast_ss(&node.bounds[pk.far_row[a]][c]);
    tn[a] = _mm256_fmsub_ps(near, pk.inv[a], pk.org_inv[a]);
    tf[a] = _mm256_fmsub_ps(far, pk.inv[a], pk.org_inv[a]);
  }
  const __m256 entry = _mm256_max_ps(_mm256_max_ps(tn[0], tn[1]), _mm256_max_ps(tn[2], pk.tnear));
  const __m256 exit = _mm256_min_ps(_mm256_min_ps(_mm256_min_ps(tf[0], tf[1]), tf[2]), tfar);
  const __m256 in = _mm256_and_ps(_mm256_cmp_ps(entry, exit, _CMP_LE_OQ), entering);
  tmin = _mm256_blendv_ps(_mm256_set1_ps(kInf), entry, in);
  return static_cast<uint32_t>(_mm256_movemask_ps(in));
}

struct StreamEntry {
  NodeRef ref;
  uint64_t rays;  // rays that entered this node's box
  float dist;     // the nearest of their entry distances
};

// The stream's rays of `live` through the tree, nearest child first (by its rays' nearest entry).
// At each node the frustum culls children for all rays at once; the children it keeps are
// tested against each packet's rays (SIMD over the rays). Rays that thin out go on one by one.
template <int N>
void traverse_stream(const TraversalContext& ctx, Stream& s, uint64_t live) {
  using Node = FastNode<N>;
  StreamEntry stack[kStackSize];
  int sp = 0;
  NodeRef cur = ctx.root;
  uint64_t rays = live;
  for (;;) {
    for (;;) {
      if (__builtin_popcountll(rays) <= kSwitchThreshold) {
        for (; rays; rays &= rays - 1) {
          const int i = __builtin_ctzll(rays);
          Packet& pk = s.pk[i / kPacketSize];
          const int lane = i % kPacketSize;
          traverse_from<N, false, false, false>(ctx, cur, lane_ray(pk, lane), pk.tfar[lane],
                                                &pk.hit[lane]);
        }
        break;
      }
      if (is_leaf(cur)) {
        for (int p = 0; p < s.packets; ++p) {
          if (const uint32_t bits = packet_bits(rays, p)) intersect_leaf_packet(cur, s.pk[p], bits);
        }
        break;
      }
      const Node& node = *ref_ptr<Node>(cur);
      int candidates = s.frustum.valid ? frustum_children<N>(node, s.frustum) : (1 << N) - 1;
      __m256 tfar[kStreamPackets], entering[kStreamPackets];
      for (int p = 0; p < s.packets; ++p) {
        tfar[p] = _mm256_load_ps(s.pk[p].tfar);
        entering[p] = lanes_of(packet_bits(rays, p));
      }
      NodeRef kids[N];
      uint64_t kid_rays[N];
      float kid_dist[N];
      int count = 0;
      for (; candidates; candidates &= candidates - 1) {
        const int c = __builtin_ctz(candidates);
        if (node.child[c] == kEmptyRef) break;  // empty slots are the last ones
        uint64_t entered = 0;
        __m256 nearest = _mm256_set1_ps(kInf);
        for (int p = 0; p < s.packets; ++p) {
          if (!packet_bits(rays, p)) continue;
          __m256 tmin;
          const uint32_t in = packet_enters_child<N>(node, c, s.pk[p], entering[p], tfar[p], tmin);
          entered |= uint64_t{in} << (kPacketSize * p);
          nearest = _mm256_min_ps(nearest, tmin);
        }
        if (!entered) continue;
        kids[count] = node.child[c];
        kid_rays[count] = entered;
        kid_dist[count] = horizontal_min(nearest);
        ++count;
      }
      if (count == 0) break;
      // Farthest first onto the stack, continue with the nearest.
      int order[N];
      for (int a = 0; a < count; ++a) {
        int b = a;
        while (b > 0 && kid_dist[order[b - 1]] < kid_dist[a]) {
          order[b] = order[b - 1];
          --b;
        }
        order[b] = a;
      }
      for (int a = 0; a < count - 1; ++a) {
        const int k = order[a];
        prefetch_block<N>(kids[k]);
        stack[sp++] = {kids[k], kid_rays[k], kid_dist[k]};
      }
      const int nearest = order[count - 1];
      cur = kids[nearest];
      rays = kid_rays[nearest];
    }
    for (;;) {
      if (sp == 0) return;
      const StreamEntry& e = stack[--sp];
      // Rays that have since found a hit nearer than every ray's entry skip the box.
      uint64_t still = 0;
      const __m256 dist = _mm256_set1_ps(e.dist);
      for (int p = 0; p < s.packets; ++p) {
        if (!packet_bits(e.rays, p)) continue;
        const uint32_t nearer = static_cast<uint32_t>(
            _mm256_movemask_ps(_mm256_cmp_ps(dist, _mm256_load_ps(s.pk[p].tfar), _CMP_LE_OQ)));
        still |= uint64_t{packet_bits(e.rays, p) & nearer} << (kPacketSize * p);
      }
      if (still) {
        cur = e.ref;
        rays = still;
        break;
      }
    }
  }
}

template <int N>
void intersect_batch_streams(const TraversalContext& ctx, const Kernels& single, const Ray* rays,
                             size_t count, Hit* hits) {
  if (ctx.root == kEmptyRef) {
    for (size_t i = 0; i < count; ++i) hits[i] = Hit{};
    return;
  }
  Stream s;  // once per batch: its 64 rays and hits are not cheap to construct
  // Runs of 3 rays or fewer go ray by ray, as thinned-out streams do.
  for_each_octant_run(
      rays, count, kStreamSize, kSwitchThreshold + 1,
      [&](size_t first, int n, int octant) {
        s.packets = (n + kPacketSize - 1) / kPacketSize;
        for (int p = 0; p < s.packets; ++p)
          make_packet_run(rays + first + p * kPacketSize,
                          std::min(kPacketSize, n - p * kPacketSize), octant, s.pk[p]);
        make_frustum(s, s.frustum);
        traverse_stream<N>(ctx, s, n == kStreamSize ? ~uint64_t{0} : (uint64_t{1} << n) - 1);
        for (int i = 0; i < n; ++i) hits[first + i] = s.pk[i / kPacketSize].hit[i % kPacketSize];
      },
      [&](size_t i) {
        hits[i] = Hit{};
        single.intersect(ctx, rays[i], hits[i]);
      });
}

}  // namespace

IntersectBatchKernel select_coherent_batch_kernel(const TreeShape& shape) {
  return batch_kernel_for<IntersectBatchKernel>(shape, &intersect_batch_streams<8>,
                                                &intersect_batch_streams<4>);
}

}  // namespace tuneray::bvh
