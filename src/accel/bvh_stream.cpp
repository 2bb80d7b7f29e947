#include "accel/bvh_stream.h"

#include <algorithm>
#include <vector>

#include "accel/bvh_traverse_impl.h"

namespace tuneray::bvh {

namespace {

using namespace detail;
using namespace single;

// Up to 64 rays share a traversal, one bit each: a node's fetch is shared by more rays than at
// 32 (shadow batches 3-15 % faster on the shared scenes; 128 was slower again).
constexpr int kStreamSize = 64;
using RayMask = uint64_t;
// An octant with fewer rays than this goes ray by ray: a stream's set-up and its per-node loop
// over the mask cost more than they save for one or two rays.
constexpr int kMinStream = 3;

struct StreamEntry {
  NodeRef ref;
  RayMask rays;  // rays that entered this node's box
};

// Per child of a node, the rays that entered it. Each ray stores its child mask as one byte; a
// child's rays are then bit c of the bytes, gathered for 32 rays at a time by one shift and one
// byte movemask, only for the children the stream goes on to. (Widening each ray's child mask
// into one lane per child and OR-ing it in cost eight vector instructions per ray and node; with
// 64-bit lanes, streams of 64 were slower than streams of 32.)
static_assert(kStreamSize == 64, "ChildRays gathers two 32-byte rows of ray masks");
struct ChildRays {
  alignas(32) uint8_t of_ray[kStreamSize] = {};  // bit c = the ray entered child c
  int children = 0;                              // bit c = some ray entered child c
  void add(int hit_children, int ray) {
    of_ray[ray] = static_cast<uint8_t>(hit_children);
    children |= hit_children;
  }
  RayMask rays(int child) const {
    // A 16-bit shift by 7 - c brings bit c of each byte to that byte's top bit (what comes in
    // from the neighbouring byte lands below it).
    const __m128i k = _mm_cvtsi32_si128(7 - child);
    const __m256i lo = _mm256_load_si256(reinterpret_cast<const __m256i*>(of_ray));
    const __m256i hi = _mm256_load_si256(reinterpret_cast<const __m256i*>(of_ray + 32));
    const uint32_t l = static_cast<uint32_t>(_mm256_movemask_epi8(_mm256_sll_epi16(lo, k)));
    const uint32_t h = static_cast<uint32_t>(_mm256_movemask_epi8(_mm256_sll_epi16(hi, k)));
    return RayMask{l} | (RayMask{h} << 32);
  }
};

// The rays of `live`, all of direction octant `octant` (bit a set = negative along axis a),
// through the tree; returns those that are blocked.
template <int N>
RayMask occlude_stream(const TraversalContext& ctx, const TraversalRay* ray, RayMask live,
                       int octant) {
  using Planes = NodePlanes<N, false>;
  using V = typename Planes::V;
  int near_row[3], far_row[3];
  near_rows_of_octant(octant, near_row);
  far_rows_of_octant(octant, far_row);
  StreamEntry stack[kStackSize];
  int sp = 0;
  stack[sp++] = {ctx.root, live};
  RayMask blocked = 0;
  while (sp > 0) {
    const StreamEntry e = stack[--sp];
    NodeRef cur = e.ref;
    RayMask rays = e.rays & ~blocked;
    if (!rays) continue;
    while (!is_leaf(cur)) {
      const auto& node = *inner_ptr<typename Planes::Node>(cur);
      // The child references (the node's last line) are read after the rays' box tests; asked
      // for now, their miss overlaps the planes' (shadow batches after 2 MiB of other reads,
      // thirty-ninth session: bmw-m6 0.83-0.89 -> 0.91-0.92x native, lost-empire 0.94-0.98 ->
      // 0.98-1.02x).
      _mm_prefetch(reinterpret_cast<const char*>(node.child), _MM_HINT_T0);
      V nears[3], fars[3];
      Planes::load(node, near_row, far_row, nears, fars);
      ChildRays entered;
      for (RayMask m = rays; m; m &= m - 1) {
        const int i = __builtin_ctzll(m);
        alignas(32) float dist[N];
        // Added without a branch: whether a ray enters any child is a coin flip to the predictor.
        entered.add(box_test<typename Planes::L, false>(nears, fars, ray[i], ray[i].tfar, dist), i);
      }
      int children = entered.children;
      if (const int leaves = children & leaf_children<N>(node.child)) {
        // Entered leaves are tested here, all requested first so their cache misses overlap
        // (a stream of scattered rays reaches several leaves of a node at once); an any hit
        // ends a ray, so the order of the tests changes no answer.
        children &= ~leaves;
        for (int m = leaves; m; m &= m - 1) prefetch_leaf<false>(node.child[__builtin_ctz(m)]);
        for (int m = leaves; m; m &= m - 1) {
          const int c = __builtin_ctz(m);
          for (RayMask todo = entered.rays(c) & ~blocked; todo; todo &= todo - 1) {
            const int i = __builtin_ctzll(todo);
            float tfar = ray[i].tfar;
            if (intersect_fast_leaf<false, true>(node.child[c], ray[i], tfar, nullptr))
              blocked |= RayMask{1} << i;
          }
        }
        if (blocked == live) return blocked;
      }
      if (!children) {  // no ray goes on below this node
        rays = 0;
        break;
      }
      // Any hit ends a ray's query, so children go in slot order: the lowest entered first, the
      // others back from the highest down. (The single-ray kernel's order, the highest first,
      // measured level to 3 % slower here: batch_replay, forty-seventh session.)
      const int first = __builtin_ctz(children);
      children &= children - 1;
      while (children) {
        const int c = __builtin_ctz(children);
        children &= children - 1;
        prefetch_block<N>(node.child[c]);
        stack[sp++] = {node.child[c], entered.rays(c)};
      }
      cur = node.child[first];
      rays = entered.rays(first) & ~blocked;
      if (!rays) break;
    }
    for (RayMask m = rays; m; m &= m - 1) {
      const int i = __builtin_ctzll(m);
      float tfar = ray[i].tfar;
      if (intersect_fast_leaf<false, true>(cur, ray[i], tfar, nullptr)) blocked |= RayMask{1} << i;
    }
    if (blocked == live) break;
  }
  return blocked;
}

template <int N>
void occluded_batch_stream(const TraversalContext& ctx, const Ray* rays, size_t count,
                           uint8_t* occluded) {
  std::fill(occluded, occluded + count, uint8_t{0});
  if (ctx.root == kEmptyRef) return;
  auto traversal_ray = [&](uint32_t i) {
    const Ray& r = rays[i];
    return make_traversal_ray(r.org, r.dir, r.tnear, r.tfar, false);
  };
  for_each_octant_group(
      rays, count, kStreamSize, kMinStream,
      [&](const uint32_t* index, int n, int octant) {
        TraversalRay group[kStreamSize];
        for (int i = 0; i < n; ++i) group[i] = traversal_ray(index[i]);
        const RayMask live = n == kStreamSize ? ~RayMask{0} : (RayMask{1} << n) - 1;
        for (RayMask blocked = occlude_stream<N>(ctx, group, live, octant); blocked;
             blocked &= blocked - 1)
          occluded[index[__builtin_ctzll(blocked)]] = 1;
      },
      [&](uint32_t i) {
        const TraversalRay ray = traversal_ray(i);
        float tfar = ray.tfar;
        occluded[i] = traverse_from<N, false, false, true>(ctx, ctx.root, ray, tfar, nullptr);
      });
}

}  // namespace

OccludedBatchKernel select_occluded_batch_kernel(const TreeShape& shape) {
  return batch_kernel_for<OccludedBatchKernel>(shape, &occluded_batch_stream<8>,
                                               &occluded_batch_stream<4>);
}

}  // namespace tuneray::bvh
