// The single-ray traversal of the tuned BVH as inline templates, shared by the single-ray
// kernels (bvh_traverse.cpp) and the camera-ray streams (bvh_packet.cpp), which hand rays over to
// it when a stream thins out and use its leaf tests so both give the same hits bit for bit.
// Internal to src/accel.
#pragma once

#include <immintrin.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <type_traits>
#include <utility>
#include <vector>

#include "accel/bvh_layout.h"
#include "accel/bvh_traverse.h"
#include "accel/bvh_triangle.h"
#include "accel/ray_planes.h"
#include "scene/scene.h"

namespace tuneray::bvh::detail {

// Ize 2013: padding the far distance by 1 + 2 gamma(3) makes the float slab test
// conservative (no ray slips between two adjacent boxes).
constexpr float kRobustFarScale = 1.0f + 2.0f * (3.0f * 0x1p-24f) / (1.0f - 3.0f * 0x1p-24f);

constexpr int kStackSize = kMaxTraversalDepth * 8;

// Relative slack of the SIMD triangle pre-test of closest-hit queries (see intersect_fast_leaf):
// wide enough for the rounding of t * |det| against tfar * |det|.
constexpr float kTieSlack = 1.0f + 0x1p-20f;

// Whether a triangle hit at `t` replaces `best` (found so far, distance `tfar`): nearer, or as
// near and of a lower triangle index, so that equal distances give the same hit whatever the
// order of the visit. A first hit must lie strictly before the ray's end.
inline bool is_nearer_hit(float t, uint32_t prim, float tfar, const Hit& best) {
  return t < tfar || (t == tfar && best.prim != kInvalidId && prim < best.prim);
}

struct StackEntry {
  NodeRef ref;
  float dist;
};

// ---- box tests: bit i of the result = child i entered within [tnear, tfar]; dist[i] = entry.

// N = L::kWidth children at once (SSE for 4-wide nodes, AVX2 for 8-wide ones).
template <class L, bool kRobust>
inline int box_test(const typename L::V (&nears)[3], const typename L::V (&fars)[3],
                    const TraversalRay& r, float tfar, float* dist) {
  using V = typename L::V;
  V tn[3], tf[3];
  for (int a = 0; a < 3; ++a) {
    const V inv = L::set1(r.inv[a]);
    if constexpr (kRobust) {
      const V org = L::set1(r.org[a]);
      tn[a] = L::mul(L::sub(nears[a], org), inv);
      tf[a] = L::mul(L::sub(fars[a], org), inv);
    } else {
      const V oi = L::set1(r.org_inv[a]);
      tn[a] = L::fmsub(nears[a], inv, oi);
      tf[a] = L::fmsub(fars[a], inv, oi);
    }
  }
  if constexpr (kRobust) {
    const V tmin = L::max(L::max(tn[0], tn[1]), L::max(tn[2], L::set1(r.tnear)));
    V tmax = L::mul(L::min(L::min(tf[0], tf[1]), tf[2]), L::set1(kRobustFarScale));
    tmax = L::min(tmax, L::set1(tfar));
    L::store(dist, tmin);
    return L::movemask(L::le(tmin, tmax));
  } else {
    // r.tnear >= +0 (make_traversal_ray), so the integer order is exact (Lanes8::max_bits).
    const V tmin = L::max_bits(L::max_bits(tn[0], tn[1]), L::max_bits(tn[2], L::set1(r.tnear)));
    const V tmax = L::min_bits(L::min_bits(tf[0], tf[1]), L::min_bits(tf[2], L::set1(tfar)));
    L::store(dist, tmin);
    return L::le_bits(tmin, tmax);
  }
}

template <bool kRobust>
inline int box_test2(const float (&rows)[6][2], const TraversalRay& r, float tfar, float* dist) {
  int mask = 0;
  for (int i = 0; i < 2; ++i) {
    float tmin = r.tnear, tmax = kInf;
    for (int a = 0; a < 3; ++a) {
      const float near = rows[r.near_row[a]][i];
      const float far = rows[r.far_row[a]][i];
      float tn, tf;
      if constexpr (kRobust) {
        tn = (near - r.org[a]) * r.inv[a];
        tf = (far - r.org[a]) * r.inv[a];
      } else {
        tn = std::fma(near, r.inv[a], -r.org_inv[a]);
        tf = std::fma(far, r.inv[a], -r.org_inv[a]);
      }
      tmin = tn > tmin ? tn : tmin;
      tmax = tf < tmax ? tf : tmax;
    }
    if constexpr (kRobust) tmax *= kRobustFarScale;
    tmax = tmax < tfar ? tmax : tfar;
    dist[i] = tmin;
    if (tmin <= tmax) mask |= 1 << i;
  }
  return mask;
}

// The near and far planes of a 4- or 8-wide node's children for rays of one octant
// (`near_row`), loaded directly by row: no dynamically indexed register array, which would be
// spilled to the stack on every node.
template <int N, bool kCompact>
struct NodePlanes {
  using L = LanesOf<N>;
  using V = typename L::V;
  using Node = std::conditional_t<kCompact, CompactNode<N>, FastNode<N>>;
  static void load(const Node& n, const int* near_row, const int* far_row, V (&nears)[3],
                   V (&fars)[3]) {
    for (int a = 0; a < 3; ++a) {
      const int nr = near_row[a], fr = far_row[a];
      if constexpr (kCompact) {
        const V scale = L::set1(n.scale[a]), origin = L::set1(n.origin[a]);
        nears[a] = L::decode_u8(n.q[nr], scale, origin);
        fars[a] = L::decode_u8(n.q[fr], scale, origin);
      } else {
        nears[a] = L::load(n.bounds[nr]);
        fars[a] = L::load(n.bounds[fr]);
      }
    }
  }
};

template <int N, bool kCompact, bool kRobust>
struct NodeTest {
  using Planes = NodePlanes<N, kCompact>;
  static int run(const typename Planes::Node& n, const TraversalRay& r, float tfar, float* dist) {
    typename Planes::V nears[3], fars[3];
    Planes::load(n, r.near_row, r.far_row, nears, fars);
    return box_test<typename Planes::L, kRobust>(nears, fars, r, tfar, dist);
  }
};

template <bool kCompact, bool kRobust>
struct NodeTest<2, kCompact, kRobust> {
  using Node = std::conditional_t<kCompact, CompactNode<2>, FastNode<2>>;
  static int run(const Node& n, const TraversalRay& r, float tfar, float* dist) {
    if constexpr (kCompact) {
      float rows[6][2];
      for (int k = 0; k < 6; ++k) {
        for (int i = 0; i < 2; ++i)
          rows[k][i] = dequantize(n.origin[k % 3], n.scale[k % 3], n.q[k][i]);
      }
      return box_test2<kRobust>(rows, r, tfar, dist);
    } else {
      return box_test2<kRobust>(n.bounds, r, tfar, dist);
    }
  }
};

// ---- leaves: returns true on a hit (any-hit: stop; closest: tfar and hit updated).

template <bool kRobust, bool kAnyHit>
inline bool intersect_compact_leaf(NodeRef leaf, const TraversalContext& ctx, const TraversalRay& r,
                                   float& tfar, Hit* hit) {
  bool found = false;
  const uint32_t* ids = leaf_ids(leaf);
  const uint32_t prim_count = leaf_header(leaf)->prim_count;
  for (uint32_t i = 0; i < prim_count; ++i) {
    const Triangle& tri = ctx.triangles[ids[i]];
    const Vec3f& a = ctx.positions[tri.v[0]];
    const Vec3f& b = ctx.positions[tri.v[1]];
    const Vec3f& c = ctx.positions[tri.v[2]];
    TriangleHit th;
    bool ok =
        kRobust ? intersect_watertight(a, b, c, r, tfar, th) : intersect_mt(a, b, c, r, tfar, th);
    if (!ok) continue;
    if constexpr (kAnyHit) return true;
    found = true;
    tfar = th.t;
    *hit = Hit{th.t, ids[i], th.u, th.v};
  }
  return found;
}

// The pack count comes from the reference, so the packs are read without waiting for the header.
template <bool kRobust, bool kAnyHit>
[[gnu::always_inline]] inline bool intersect_fast_leaf(NodeRef ref, const TraversalRay& r,
                                                       float& tfar, Hit* hit) {
  bool found = false;
  const TriPack4* packs = leaf_packs(ref);
  const uint32_t pack_count = leaf_code(ref);
  for (uint32_t k = 0; k < pack_count; ++k) {
    const TriPack4& p = packs[k];
    if constexpr (kRobust) {
      for (int lane = 0; lane < 4; ++lane) {
        if (p.prim[lane] == kInvalidId) break;
        const Vec3f a{p.p[0][lane], p.p[1][lane], p.p[2][lane]};
        const Vec3f b{p.p[3][lane], p.p[4][lane], p.p[5][lane]};
        const Vec3f c{p.p[6][lane], p.p[7][lane], p.p[8][lane]};
        TriangleHit th;
        if (!intersect_watertight(a, b, c, r, tfar, th)) continue;
        if constexpr (kAnyHit) return true;
        found = true;
        tfar = th.t;
        *hit = Hit{th.t, p.prim[lane], th.u, th.v};
      }
    } else {
      // Two packs per AVX2 pass while two remain, the last odd one with SSE. A closest-hit
      // query lets the SIMD test pass hits a hair beyond tfar and decides on the divided t, so
      // equal distances are settled by the lower triangle index whatever the visiting order
      // (single rays and packets visit in different orders and must agree bit for bit).
      const float filter_tfar = kAnyHit ? tfar : tfar * kTieSlack;
      LaneHits th;
      int mask;
      const TriPack4* first = &p;
      if (k + 1 < pack_count) {
        mask = intersect_two_packs_mt(p.p, packs[k + 1].p, r, filter_tfar, th);
        ++k;
      } else {
        mask = intersect_pack_mt(p.p, r, filter_tfar, th);
      }
      if (!mask) continue;
      if constexpr (kAnyHit) return true;
      while (mask) {
        const int lane = __builtin_ctz(mask);
        mask &= mask - 1;
        const uint32_t prim = first[lane / 4].prim[lane % 4];
        if (is_nearer_hit(th.t[lane], prim, tfar, *hit)) {
          found = true;
          tfar = th.t[lane];
          *hit = Hit{th.t[lane], prim, th.u[lane], th.v[lane]};
        }
      }
    }
  }
  return found;
}

// Bit i set = child i of a node is a leaf (an empty slot is not).
template <int N>
inline int leaf_children(const NodeRef (&child)[N]) {
  if constexpr (N == 8 || N == 4) {
    int bits = 0;
    for (int k = 0; k < N; k += 4) {
      const __m256i refs = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(child + k));
      bits |= _mm256_movemask_pd(_mm256_castsi256_pd(_mm256_slli_epi64(refs, 63))) << k;
    }
    return bits;
  } else {
    int bits = 0;
    for (int i = 0; i < N; ++i) bits |= is_leaf(child[i]) ? 1 << i : 0;
    return bits;
  }
}

// Brings a block the ray will visit soon into L1 while the current one is tested: the lines of an
// N-wide node (2, 3 or 4; a leaf's first pack spans three).
template <int N>
inline void prefetch_block(NodeRef ref) {
  const char* p = ref_ptr<const char>(ref);
  _mm_prefetch(p, _MM_HINT_T0);
  _mm_prefetch(p + 64, _MM_HINT_T0);
  if constexpr (N >= 4) _mm_prefetch(p + 128, _MM_HINT_T0);
  if constexpr (N >= 8) _mm_prefetch(p + 192, _MM_HINT_T0);
}

// A fast leaf's first pack (three lines), or a compact leaf's header and ids.
template <bool kCompact>
inline void prefetch_leaf(NodeRef ref) {
  const char* p = ref_ptr<const char>(ref);
  _mm_prefetch(p, _MM_HINT_T0);
  _mm_prefetch(p + 64, _MM_HINT_T0);
  if constexpr (!kCompact) _mm_prefetch(p + 128, _MM_HINT_T0);
}

// One ray through the subtree at `start`. Closest hit: `tfar` and `*hit` are updated on every
// nearer hit (the caller initialises them, so a packet can hand over a ray mid-way); any hit:
// returns at the first one.
template <int N, bool kCompact, bool kRobust, bool kAnyHit>
bool traverse_from(const TraversalContext& ctx, NodeRef start, const TraversalRay& ray,
                   float& tfar_io, Hit* hit) {
  using Node = std::conditional_t<kCompact, CompactNode<N>, FastNode<N>>;
  // Local copies: the leaf tests store through `hit`, which the compiler would otherwise have to
  // assume may change the ray and tfar, reloading them at every node.
  const TraversalRay r = ray;
  float tfar = tfar_io;
  bool found = false;
  // An any-hit query never reads an entry's distance, so its stack holds references alone
  // (half the bytes to write and read back).
  std::conditional_t<kAnyHit, NodeRef, StackEntry> stack[kStackSize];
  int sp = 0;
  NodeRef cur = start;
  for (;;) {
    while (!is_leaf(cur)) {
      const Node& node = *inner_ptr<Node>(cur);
      // The child references sit on the node's last line, read only once the boxes are
      // tested: requested now, their miss overlaps the planes' instead of following it.
      if constexpr (!kCompact && N == 8)
        _mm_prefetch(reinterpret_cast<const char*>(node.child), _MM_HINT_T0);
      alignas(32) float dist[N];
      int mask = NodeTest<N, kCompact, kRobust>::run(node, r, tfar, dist);
      if constexpr (kCompact) {
        // Slots past the last child decode to an inverted box, but a degenerate parent box
        // (all extents 0) would not reject them: mask them out explicitly.
        for (int i = 0; i < N; ++i) {
          if (node.child[i] == kEmptyRef) mask &= ~(1 << i);
        }
      }
      if (mask == 0) goto pop;
      // Any hit: leaves are tested as soon as their box is entered, not pushed and popped (a ray
      // enters several small sibling leaves of a node at once, and any hit among them ends the
      // query). Closest hit: leaves go in distance order with the inner children, where a hit in
      // a nearer subtree culls them; testing every entered leaf at once cost bounce rays up to 5 %
      // (batch_replay on conference, lost-empire, bunny; level on bmw-m6).
      if constexpr (kAnyHit) {
        if (const int leaves = mask & leaf_children<N>(node.child)) {
          mask &= ~leaves;
          // All of them are requested before the first is tested, so their cache misses
          // overlap; so are the inner children the ray goes on to, whose misses then overlap
          // the tests.
          for (int m = leaves & (leaves - 1); m; m &= m - 1)
            prefetch_leaf<kCompact>(node.child[__builtin_ctz(m)]);
          for (int m = mask; m; m &= m - 1) prefetch_block<N>(node.child[__builtin_ctz(m)]);
          for (int m = leaves; m; m &= m - 1) {
            const NodeRef leaf = node.child[__builtin_ctz(m)];
            if constexpr (kCompact) {
              if (intersect_compact_leaf<kRobust, true>(leaf, ctx, r, tfar, hit)) return true;
            } else {
              if (intersect_fast_leaf<kRobust, true>(leaf, r, tfar, hit)) return true;
            }
          }
          if (mask == 0) goto pop;
        }
      }
      // Slot indices unsigned: tzcnt's result then needs no sign extension on the chain.
      const unsigned i0 = static_cast<unsigned>(__builtin_ctz(mask));
      mask &= mask - 1;
      NodeRef c0 = node.child[i0];
      if (mask == 0) {
        cur = c0;
        continue;
      }
      if constexpr (kAnyHit) {
        // Any hit ends the query, so the order costs more than it saves: push the rest as
        // they come.
        do {
          const int i = __builtin_ctz(mask);
          mask &= mask - 1;
          prefetch_block<N>(node.child[i]);
          stack[sp++] = node.child[i];
        } while (mask);
        cur = c0;
        continue;
      } else {
        const unsigned i1 = static_cast<unsigned>(__builtin_ctz(mask));
        const int rest = mask & (mask - 1);
        if (rest == 0) {
          // Two children, the common case: visit the nearer, push the farther (the first on a
          // tie).
          const NodeRef c1 = node.child[i1];
          const float d0 = dist[i0], d1 = dist[i1];
          // Without a branch: which child is nearer is close to a coin toss for scattered rays,
          // and a mispredicted branch costs more than the select's few cycles on the chain
          // (batch_replay, thirty-ninth session: bounce rays 1-2 % faster on the bunny and
          // lost-empire, level on bmw-m6 and conference). Ties keep slot order.
          const NodeRef swap = NodeRef{0} - static_cast<NodeRef>(d1 < d0);
          const NodeRef diff = (c0 ^ c1) & swap;
          const NodeRef far = c1 ^ diff;
          prefetch_block<N>(far);
          stack[sp++] = {far, std::max(d0, d1)};
          cur = c0 ^ diff;
          continue;
        }
        if constexpr (N >= 4) {
          // Three or more: pushed in descending order of distance, ties in slot order (as a
          // stable sort leaves them), and the nearest is visited. Each child's place is its
          // rank, counted with one SIMD comparison against all distances instead of an insertion
          // sort's data-dependent branches.
          using L = LanesOf<N>;
          const int hit = mask | (1 << i0);
          const typename L::V all = L::load(dist);
          StackEntry* base = stack + sp;
          for (int m = hit; m; m &= m - 1) {
            const int i = __builtin_ctz(m);
            const typename L::V d = L::set1(dist[i]);
            const int before =
                L::movemask(L::gt(all, d)) | (L::movemask(L::eq(all, d)) & ((1 << i) - 1));
            base[__builtin_popcount(before & hit)] = {node.child[i], dist[i]};
          }
          const int count = __builtin_popcount(hit);
          for (int a = 0; a < count - 1; ++a) prefetch_block<N>(base[a].ref);
          sp += count - 1;
          cur = base[count - 1].ref;
        }
      }
    }
    {
      bool leaf_hit;
      if constexpr (kCompact)
        leaf_hit = intersect_compact_leaf<kRobust, kAnyHit>(cur, ctx, r, tfar, hit);
      else
        leaf_hit = intersect_fast_leaf<kRobust, kAnyHit>(cur, r, tfar, hit);
      if (leaf_hit) {
        if constexpr (kAnyHit) return true;
        found = true;
      }
    }
  pop:
    for (;;) {
      if (sp == 0) {
        tfar_io = tfar;
        return found;
      }
      if constexpr (kAnyHit) {
        cur = stack[--sp];
        break;
      } else {
        const StackEntry& e = stack[--sp];
        if (e.dist <= tfar) {
          cur = e.ref;
          break;
        }
      }
    }
  }
}

// ---- batches: groups of rays of one direction octant, for the packet and stream kernels.

// Bit a set = the ray's direction is negative along axis a, by the sign test of
// make_traversal_ray (a -0 or tiny negative component counts as negative), so a group's shared
// near planes are the ones each of its rays would use alone. The sign bits come from one load
// (dir and tfar are the ray's second 16 bytes).
inline int ray_octant(const Ray& ray) {
  static_assert(offsetof(Ray, dir) + 4 * sizeof(float) <= sizeof(Ray), "dir and one float");
  return _mm_movemask_ps(_mm_loadu_ps(&ray.dir.x)) & 7;
}
// ray_octant of ray i of planes: the same sign bits.
inline int plane_octant(const RayPlanes& rays, size_t i) {
  return static_cast<int>((std::bit_cast<uint32_t>(rays.dir[0][i]) >> 31) |
                          (std::bit_cast<uint32_t>(rays.dir[1][i]) >> 31) << 1 |
                          (std::bit_cast<uint32_t>(rays.dir[2][i]) >> 31) << 2);
}

// A group's near planes come from its octant, never from one of its rays: a ray with a NaN
// direction (which enters no box) must not hand its rows to the others.
inline void near_rows_of_octant(int octant, int (&near_row)[3]) {
  for (int a = 0; a < 3; ++a) near_row[a] = (octant >> a) & 1 ? a + 3 : a;
}
inline void far_rows_of_octant(int octant, int (&far_row)[3]) {
  for (int a = 0; a < 3; ++a) far_row[a] = (octant >> a) & 1 ? a : a + 3;
}

// Sorts a batch into direction octants (as Embree's ray streams do) and calls
// `group(index, n, octant)` for each run of up to `size` rays of one octant, in batch order within
// the octant (`index` holds their batch positions), or `single(i)` for each ray of a run shorter
// than `min_size`, too thin to be worth a group.
template <class GroupFn, class SingleFn>
void for_each_octant_group(const Ray* rays, size_t count, int size, int min_size, GroupFn group,
                           SingleFn single) {
  thread_local std::vector<uint32_t> order;
  thread_local std::vector<uint8_t> octant_of;
  order.resize(count);
  octant_of.resize(count);
  size_t begin[9] = {};
  for (size_t i = 0; i < count; ++i) {
    octant_of[i] = static_cast<uint8_t>(ray_octant(rays[i]));
    ++begin[octant_of[i] + 1];
  }
  for (int o = 0; o < 8; ++o) begin[o + 1] += begin[o];
  size_t fill[8];
  std::copy(begin, begin + 8, fill);
  for (size_t i = 0; i < count; ++i) order[fill[octant_of[i]]++] = static_cast<uint32_t>(i);
  for (int o = 0; o < 8; ++o) {
    for (size_t first = begin[o]; first < begin[o + 1]; first += static_cast<size_t>(size)) {
      const int n =
          static_cast<int>(std::min<size_t>(static_cast<size_t>(size), begin[o + 1] - first));
      if (n < min_size) {
        for (int i = 0; i < n; ++i) single(order[first + i]);
      } else {
        group(&order[first], n, o);
      }
    }
  }
}

// The batch kernels (packets, streams) exist for the 4- and 8-wide fast, non-robust layouts only:
// the kernel of this tree's width, or nullptr, where the caller loops over single rays.
template <class Kernel>
Kernel batch_kernel_for(const TreeShape& shape, Kernel width8, Kernel width4) {
  if (shape.compact || shape.robust) return nullptr;
  if (shape.width == 8) return width8;
  if (shape.width == 4) return width4;
  return nullptr;
}

}  // namespace tuneray::bvh::detail
