#include "accel/bvh_packet.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "accel/bvh_traverse_impl.h"

namespace tuneray::bvh {

namespace {

using namespace detail;

constexpr int kPacketSize = 8;
// A packet with this many rays or fewer left in a subtree continues ray by ray: 8 lanes of box
// tests for a few rays cost more than their single-ray traversals (Embree's hybrid intersectors
// switch at a similar count).
constexpr int kSwitchThreshold = 3;
// Leaves are tested with SIMD over the packet's rays (one pass per triangle) when more than
// this many rays reach them, else ray by ray over the packs (two packs per pass).
constexpr int kLeafSwitchThreshold = 2;

// Up to 8 rays with a common octant, in SoA for the box and triangle tests, and as single rays
// for the hand-over to the single-ray traversal.
struct Packet {
  TraversalRay ray[kPacketSize];
  alignas(32) float tfar[kPacketSize];
  Hit hit[kPacketSize];
  __m256 inv[3], org_inv[3], tnear, org[3], dir[3];
  int near_row[3], far_row[3];
};

// The rays must share the octant `octant` (the packet box test picks one near plane per axis).
void make_packet(const Ray* rays, const uint32_t* index, int count, int octant, Packet& pk) {
  alignas(32) float inv[3][kPacketSize], org_inv[3][kPacketSize], org[3][kPacketSize],
      dir[3][kPacketSize], tnear[kPacketSize];
  for (int i = 0; i < kPacketSize; ++i) {
    const Ray& ray = rays[index[i < count ? i : 0]];
    pk.ray[i] = make_traversal_ray(ray.org, ray.dir, ray.tnear, ray.tfar, false);
    const TraversalRay& r = pk.ray[i];
    for (int a = 0; a < 3; ++a) {
      inv[a][i] = r.inv[a];
      org_inv[a][i] = r.org_inv[a];
      org[a][i] = r.org[a];
      dir[a][i] = r.dir[a];
    }
    tnear[i] = r.tnear;
    // Padding lanes never enter a box nor hit a triangle.
    pk.tfar[i] = i < count ? r.tfar : -kInf;
    pk.hit[i] = Hit{};
  }
  near_rows_of_octant(octant, pk.near_row);
  for (int a = 0; a < 3; ++a) {
    pk.inv[a] = _mm256_load_ps(inv[a]);
    pk.org_inv[a] = _mm256_load_ps(org_inv[a]);
    pk.org[a] = _mm256_load_ps(org[a]);
    pk.dir[a] = _mm256_load_ps(dir[a]);
    pk.far_row[a] = pk.near_row[a] < 3 ? pk.near_row[a] + 3 : pk.near_row[a] - 3;
  }
  pk.tnear = _mm256_load_ps(tnear);
}

inline __m256 lanes_of(uint32_t mask) {
  const __m256i bits = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
  const __m256i selected = _mm256_and_si256(_mm256_set1_epi32(static_cast<int>(mask)), bits);
  return _mm256_castsi256_ps(_mm256_cmpeq_epi32(selected, bits));
}

inline float horizontal_min(__m256 v) {
  __m128 m = _mm_min_ps(_mm256_castps256_ps128(v), _mm256_extractf128_ps(v, 1));
  m = _mm_min_ps(m, _mm_movehl_ps(m, m));
  m = _mm_min_ss(m, _mm_shuffle_ps(m, m, 1));
  return _mm_cvtss_f32(m);
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
      intersect_fast_leaf<false, false>(leaf, pk.ray[i], pk.tfar[i], &pk.hit[i]);
    }
    return;
  }
  const TriPack4* packs = leaf_payload<TriPack4>(ref_ptr<LeafHeader>(leaf));
  const uint32_t pack_count = leaf_code(leaf);
  for (uint32_t k = 0; k < pack_count; ++k) {
    for (int j = 0; j < 4 && packs[k].prim[j] != kInvalidId; ++j)
      intersect_triangle_packet(packs[k], j, pk, mask);
  }
}

// A stack entry keeps each ray's own entry distance, so a ray that has found a nearer hit skips
// the box even when another ray of the packet still needs it.
struct PacketEntry {
  NodeRef ref;
  uint32_t mask;  // rays that entered this node's box
  __m256 dist;    // their entry distances (+inf for the others)
};

template <int N>
void traverse_packet(const TraversalContext& ctx, Packet& pk, uint32_t live) {
  using Node = FastNode<N>;
  alignas(32) PacketEntry stack[kStackSize];
  int sp = 0;
  NodeRef cur = ctx.root;
  uint32_t cur_mask = live;
  const __m256 inf = _mm256_set1_ps(kInf);
  for (;;) {
    for (;;) {
      if (__builtin_popcount(cur_mask) <= kSwitchThreshold) {
        while (cur_mask) {
          const int i = __builtin_ctz(cur_mask);
          cur_mask &= cur_mask - 1;
          traverse_from<N, false, false, false>(ctx, cur, pk.ray[i], pk.tfar[i], &pk.hit[i]);
        }
        break;
      }
      if (is_leaf(cur)) {
        intersect_leaf_packet(cur, pk, cur_mask);
        break;
      }
      const Node& node = *ref_ptr<Node>(cur);
      const __m256 tfar = _mm256_load_ps(pk.tfar);
      const __m256 entering = lanes_of(cur_mask);
      NodeRef kids[N];
      uint32_t kid_mask[N];
      __m256 kid_tmin[N];
      float kid_dist[N];
      int count = 0;
      for (int c = 0; c < N && node.child[c] != kEmptyRef; ++c) {
        // The same operations in the same order as the single-ray box test, lane by lane.
        __m256 tn[3], tf[3];
        for (int a = 0; a < 3; ++a) {
          const __m256 near = _mm256_broadcast_ss(&node.bounds[pk.near_row[a]][c]);
          const __m256 far = _mm256_broadcast_ss(&node.bounds[pk.far_row[a]][c]);
          tn[a] = _mm256_fmsub_ps(near, pk.inv[a], pk.org_inv[a]);
          tf[a] = _mm256_fmsub_ps(far, pk.inv[a], pk.org_inv[a]);
        }
        const __m256 tmin =
            _mm256_max_ps(_mm256_max_ps(tn[0], tn[1]), _mm256_max_ps(tn[2], pk.tnear));
        const __m256 tmax = _mm256_min_ps(_mm256_min_ps(_mm256_min_ps(tf[0], tf[1]), tf[2]), tfar);
        const __m256 in = _mm256_and_ps(_mm256_cmp_ps(tmin, tmax, _CMP_LE_OQ), entering);
        const uint32_t mask = static_cast<uint32_t>(_mm256_movemask_ps(in));
        if (!mask) continue;
        kids[count] = node.child[c];
        kid_mask[count] = mask;
        kid_tmin[count] = _mm256_blendv_ps(inf, tmin, in);
        kid_dist[count] = horizontal_min(kid_tmin[count]);
        ++count;
      }
      if (count == 0) break;
      // Farthest first onto the stack (by the packet's nearest entry), continue with the nearest.
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
        stack[sp++] = {kids[k], kid_mask[k], kid_tmin[k]};
      }
      const int nearest = order[count - 1];
      cur = kids[nearest];
      cur_mask = kid_mask[nearest];
    }
    for (;;) {
      if (sp == 0) return;
      const PacketEntry& e = stack[--sp];
      // Rays that have since found a hit nearer than their own entry skip the box.
      const uint32_t mask = e.mask & static_cast<uint32_t>(_mm256_movemask_ps(_mm256_cmp_ps(
                                         e.dist, _mm256_load_ps(pk.tfar), _CMP_LE_OQ)));
      if (mask) {
        cur = e.ref;
        cur_mask = mask;
        break;
      }
    }
  }
}

template <int N>
void intersect_batch_packets(const TraversalContext& ctx, const Kernels& single, const Ray* rays,
                             size_t count, Hit* hits) {
  for (size_t i = 0; i < count; ++i) hits[i] = Hit{};
  if (ctx.root == kEmptyRef) return;
  // Octant runs of 3 rays or fewer go ray by ray, as thinned-out packets do.
  for_each_octant_group(
      rays, count, kPacketSize, kSwitchThreshold + 1,
      [&](const uint32_t* index, int n, int octant) {
        Packet pk;
        make_packet(rays, index, n, octant, pk);
        traverse_packet<N>(ctx, pk, (1u << n) - 1);
        for (int i = 0; i < n; ++i) hits[index[i]] = pk.hit[i];
      },
      [&](uint32_t i) { single.intersect(ctx, rays[i], hits[i]); });
}

}  // namespace

IntersectBatchKernel select_coherent_batch_kernel(const TreeShape& shape) {
  return batch_kernel_for<IntersectBatchKernel>(shape, &intersect_batch_packets<8>,
                                                &intersect_batch_packets<4>);
}

}  // namespace tuneray::bvh
