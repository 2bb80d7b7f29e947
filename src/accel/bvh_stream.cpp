#include "accel/bvh_stream.h"

#include <algorithm>
#include <vector>

#include "accel/bvh_traverse_impl.h"

namespace tuneray::bvh {

namespace {

using namespace detail;

// Up to 32 rays share a traversal, one bit each.
constexpr int kStreamSize = 32;
// An octant with fewer rays than this goes ray by ray: a stream's set-up and its per-node loop
// over the mask cost more than they save for one or two rays.
constexpr int kMinStream = 3;

struct StreamEntry {
  NodeRef ref;
  uint32_t rays;  // rays that entered this node's box
};

template <int N>
using LanesOf = std::conditional_t<N == 8, Lanes8, Lanes4>;

// Per child of an N-wide node, the rays (bit masks) whose box test entered it.
template <int N>
struct ChildRays;

template <>
struct ChildRays<8> {
  __m256i acc = _mm256_setzero_si256();
  void add(int hit_children, uint32_t ray_bit) {
    const __m256i lane_bits = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
    const __m256i hit =
        _mm256_cmpeq_epi32(_mm256_and_si256(_mm256_set1_epi32(hit_children), lane_bits), lane_bits);
    acc = _mm256_or_si256(acc, _mm256_and_si256(hit, _mm256_set1_epi32(static_cast<int>(ray_bit))));
  }
  // Bit c set = child c was entered by some ray; `rays[c]` = which ones.
  int store(uint32_t (&rays)[8]) const {
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(rays), acc);
    const __m256i none = _mm256_cmpeq_epi32(acc, _mm256_setzero_si256());
    return ~_mm256_movemask_ps(_mm256_castsi256_ps(none)) & 0xff;
  }
};

template <>
struct ChildRays<4> {
  __m128i acc = _mm_setzero_si128();
  void add(int hit_children, uint32_t ray_bit) {
    const __m128i lane_bits = _mm_setr_epi32(1, 2, 4, 8);
    const __m128i hit =
        _mm_cmpeq_epi32(_mm_and_si128(_mm_set1_epi32(hit_children), lane_bits), lane_bits);
    acc = _mm_or_si128(acc, _mm_and_si128(hit, _mm_set1_epi32(static_cast<int>(ray_bit))));
  }
  int store(uint32_t (&rays)[4]) const {
    _mm_storeu_si128(reinterpret_cast<__m128i*>(rays), acc);
    const __m128i none = _mm_cmpeq_epi32(acc, _mm_setzero_si128());
    return ~_mm_movemask_ps(_mm_castsi128_ps(none)) & 0xf;
  }
};

// The rays of `live`, all of direction octant `octant` (bit a set = negative along axis a),
// through the tree; returns those that are blocked.
template <int N>
uint32_t occlude_stream(const TraversalContext& ctx, const TraversalRay* ray, uint32_t live,
                        int octant) {
  using Node = FastNode<N>;
  using L = LanesOf<N>;
  using V = typename L::V;
  // The near planes come from the octant, not from one of the rays: a ray with a NaN direction
  // (which enters no box) must not hand its rows to the others.
  int near_row[3];
  for (int a = 0; a < 3; ++a) near_row[a] = (octant >> a) & 1 ? a + 3 : a;
  StreamEntry stack[kStackSize];
  int sp = 0;
  stack[sp++] = {ctx.root, live};
  uint32_t blocked = 0;
  while (sp > 0) {
    const StreamEntry e = stack[--sp];
    NodeRef cur = e.ref;
    uint32_t rays = e.rays & ~blocked;
    if (!rays) continue;
    while (!is_leaf(cur)) {
      const Node& node = *ref_ptr<Node>(cur);
      V nears[3], fars[3];
      for (int a = 0; a < 3; ++a) {
        const int nr = near_row[a], fr = nr < 3 ? nr + 3 : nr - 3;
        nears[a] = reinterpret_cast<const V&>(node.bounds[nr]);
        fars[a] = reinterpret_cast<const V&>(node.bounds[fr]);
      }
      ChildRays<N> entered;
      for (uint32_t m = rays; m; m &= m - 1) {
        const int i = __builtin_ctz(m);
        alignas(32) float dist[N];
        const int hit = box_test<L, false>(nears, fars, ray[i], ray[i].tfar, dist);
        if (hit) entered.add(hit, 1u << i);
      }
      alignas(16) uint32_t child_rays[N];
      int children = entered.store(child_rays);
      if (!children) goto next;
      // Any hit ends a ray's query, so children go in slot order, as in the single-ray kernel.
      const int first = __builtin_ctz(children);
      children &= children - 1;
      while (children) {
        const int c = __builtin_ctz(children);
        children &= children - 1;
        prefetch_block<N>(node.child[c]);
        stack[sp++] = {node.child[c], child_rays[c]};
      }
      cur = node.child[first];
      rays = child_rays[first];
    }
    for (uint32_t m = rays; m; m &= m - 1) {
      const int i = __builtin_ctz(m);
      float tfar = ray[i].tfar;
      if (intersect_fast_leaf<false, true>(cur, ray[i], tfar, nullptr)) blocked |= 1u << i;
    }
    if (blocked == live) break;
  next:;
  }
  return blocked;
}

template <int N>
void occluded_batch_stream(const TraversalContext& ctx, const Ray* rays, size_t count,
                           uint8_t* occluded) {
  std::fill(occluded, occluded + count, uint8_t{0});
  if (ctx.root == kEmptyRef || count == 0) return;
  thread_local std::vector<uint32_t> order;
  thread_local std::vector<uint8_t> octant_of;
  order.resize(count);
  octant_of.resize(count);
  size_t begin[9] = {};
  for (size_t i = 0; i < count; ++i) {
    const Vec3f& d = rays[i].dir;
    // The sign test of make_traversal_ray (a -0 or tiny negative component counts as
    // negative), so a group's near planes are the ones each of its rays would use alone.
    const int o =
        (std::signbit(d.x) ? 1 : 0) | (std::signbit(d.y) ? 2 : 0) | (std::signbit(d.z) ? 4 : 0);
    octant_of[i] = static_cast<uint8_t>(o);
    ++begin[o + 1];
  }
  for (int o = 0; o < 8; ++o) begin[o + 1] += begin[o];
  size_t fill[8];
  std::copy(begin, begin + 8, fill);
  for (size_t i = 0; i < count; ++i) order[fill[octant_of[i]]++] = static_cast<uint32_t>(i);

  TraversalRay group[kStreamSize];
  for (int o = 0; o < 8; ++o) {
    for (size_t first = begin[o]; first < begin[o + 1]; first += kStreamSize) {
      const int n = static_cast<int>(std::min<size_t>(kStreamSize, begin[o + 1] - first));
      for (int i = 0; i < n; ++i) {
        const Ray& r = rays[order[first + i]];
        group[i] = make_traversal_ray(r.org, r.dir, r.tnear, r.tfar, false);
      }
      if (n < kMinStream) {
        for (int i = 0; i < n; ++i) {
          float tfar = group[i].tfar;
          occluded[order[first + i]] =
              traverse_from<N, false, false, true>(ctx, ctx.root, group[i], tfar, nullptr) ? 1 : 0;
        }
        continue;
      }
      const uint32_t live = n == 32 ? ~0u : (1u << n) - 1;
      uint32_t blocked = occlude_stream<N>(ctx, group, live, o);
      for (; blocked; blocked &= blocked - 1) occluded[order[first + __builtin_ctz(blocked)]] = 1;
    }
  }
}

}  // namespace

OccludedBatchKernel select_occluded_batch_kernel(const TreeShape& shape) {
  if (shape.compact || shape.robust) return nullptr;
  if (shape.width == 8) return &occluded_batch_stream<8>;
  if (shape.width == 4) return &occluded_batch_stream<4>;
  return nullptr;
}

}  // namespace tuneray::bvh
