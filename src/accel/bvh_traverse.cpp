#include "accel/bvh_traverse.h"

#include "accel/bvh_traverse_impl.h"

namespace tuneray::bvh {

namespace {

using namespace detail;

template <int N, bool kCompact, bool kRobust>
bool intersect_kernel(const TraversalContext& ctx, const Ray& ray, Hit& hit) {
  if (ctx.root == kEmptyRef) return false;
  const TraversalRay r = make_traversal_ray(ray.org, ray.dir, ray.tnear, ray.tfar, kRobust);
  float tfar = ray.tfar;
  Hit h;
  if (!traverse_from<N, kCompact, kRobust, false>(ctx, ctx.root, r, tfar, &h)) return false;
  hit = h;
  return true;
}

template <int N, bool kCompact, bool kRobust>
bool occluded_kernel(const TraversalContext& ctx, const Ray& ray) {
  if (ctx.root == kEmptyRef) return false;
  const TraversalRay r = make_traversal_ray(ray.org, ray.dir, ray.tnear, ray.tfar, kRobust);
  float tfar = ray.tfar;
  return traverse_from<N, kCompact, kRobust, true>(ctx, ctx.root, r, tfar, nullptr);
}

template <int N, bool kCompact, bool kRobust>
Kernels make_kernels() {
  return {&intersect_kernel<N, kCompact, kRobust>, &occluded_kernel<N, kCompact, kRobust>};
}

template <int N>
Kernels kernels_for_width(bool compact, bool robust) {
  if (compact) return robust ? make_kernels<N, true, true>() : make_kernels<N, true, false>();
  return robust ? make_kernels<N, false, true>() : make_kernels<N, false, false>();
}

}  // namespace

Kernels select_kernels(const TreeShape& shape) {
  switch (shape.width) {
    case 2:
      return kernels_for_width<2>(shape.compact, shape.robust);
    case 4:
      return kernels_for_width<4>(shape.compact, shape.robust);
    default:
      return kernels_for_width<8>(shape.compact, shape.robust);
  }
}

}  // namespace tuneray::bvh
