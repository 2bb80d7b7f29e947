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

// Per child of an N-wide node, the rays (bit masks) whose box test entered it: a ray's child
// mask widened to N lanes selects where its bit goes, one vector OR per ray.
typedef uint32_t MaskLanes4 __attribute__((vector_size(16)));
typedef uint32_t MaskLanes8 __attribute__((vector_size(32)));

template <int N>
struct ChildRays {
  using Masks = std::conditional_t<N == 8, MaskLanes8, MaskLanes4>;
  Masks rays{};
  int children = 0;  // bit c set = child c was entered by some ray
  void add(int hit_children, uint32_t ray_bit) {
    Masks child_bit;
    for (int c = 0; c < N; ++c) child_bit[c] = 1u << c;
    rays |= reinterpret_cast<Masks>((hit_children & child_bit) != 0) & ray_bit;
    children |= hit_children;
  }
};

// The rays of `live`, all of direction octant `octant` (bit a set = negative along axis a),
// through the tree; returns those that are blocked.
template <int N>
uint32_t occlude_stream(const TraversalContext& ctx, const TraversalRay* ray, uint32_t live,
                        int octant) {
  using Planes = NodePlanes<N, false>;
  using V = typename Planes::V;
  int near_row[3], far_row[3];
  near_rows_of_octant(octant, near_row);
  far_rows_of_octant(octant, far_row);
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
      const auto& node = *ref_ptr<typename Planes::Node>(cur);
      V nears[3], fars[3];
      Planes::load(node, near_row, far_row, nears, fars);
      ChildRays<N> entered;
      for (uint32_t m = rays; m; m &= m - 1) {
        const int i = __builtin_ctz(m);
        alignas(32) float dist[N];
        // Added without a branch: whether a ray enters any child is a coin flip to the predictor.
        entered.add(box_test<typename Planes::L, false>(nears, fars, ray[i], ray[i].tfar, dist),
                    1u << i);
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
          for (uint32_t todo = entered.rays[c] & ~blocked; todo; todo &= todo - 1) {
            const int i = __builtin_ctz(todo);
            float tfar = ray[i].tfar;
            if (intersect_fast_leaf<false, true>(node.child[c], ray[i], tfar, nullptr))
              blocked |= 1u << i;
          }
        }
        if (blocked == live) return blocked;
      }
      if (!children) {  // no ray goes on below this node
        rays = 0;
        break;
      }
      // Any hit ends a ray's query, so children go in slot order, as in the single-ray kernel.
      const int first = __builtin_ctz(children);
      children &= children - 1;
      while (children) {
        const int c = __builtin_ctz(children);
        children &= children - 1;
        prefetch_block<N>(node.child[c]);
        stack[sp++] = {node.child[c], entered.rays[c]};
      }
      cur = node.child[first];
      rays = entered.rays[first] & ~blocked;
      if (!rays) break;
    }
    for (uint32_t m = rays; m; m &= m - 1) {
      const int i = __builtin_ctz(m);
      float tfar = ray[i].tfar;
      if (intersect_fast_leaf<false, true>(cur, ray[i], tfar, nullptr)) blocked |= 1u << i;
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
        const uint32_t live = n == kStreamSize ? ~0u : (1u << n) - 1;
        for (uint32_t blocked = occlude_stream<N>(ctx, group, live, octant); blocked;
             blocked &= blocked - 1)
          occluded[index[__builtin_ctz(blocked)]] = 1;
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
