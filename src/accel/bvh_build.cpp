#include "accel/bvh_build.h"

#include <immintrin.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <limits>

#include "accel/bvh_node_box.h"
#include "math/bbox.h"
#include "scene/scene.h"

namespace tuneray::bvh {

namespace {

// Read by every callback on every thread; written only by create_leaf and create_node (once per
// leaf or node, on their own cache line so the reads do not miss). splitPrimitive writes nothing
// here: the number of spatial splits is references - triangles after the build (each split
// Embree keeps adds exactly one reference), so it needs no counter on its hot path.
struct BuildContext {
  const GeometryView* geometry = nullptr;
  const SplitTriangle* split_triangles = nullptr;
  bool robust = false;
  alignas(kCacheLine) std::atomic<size_t> references{0};
  std::atomic<size_t> inner_nodes{0};
};

Vec3f vertex(const GeometryView& g, uint32_t tri, int k) {
  return g.positions[g.triangles[tri].v[k]];
}

template <int N, bool kCompact>
struct Callbacks {
  using Node = NodeOf<N, kCompact>;

  static void* create_node(RTCThreadLocalAllocator alloc, unsigned int, void* user) {
    static_cast<BuildContext*>(user)->inner_nodes.fetch_add(1, std::memory_order_relaxed);
    auto* node = static_cast<Node*>(rtcThreadLocalAlloc(alloc, sizeof(Node), kCacheLine));
    clear_node<N, kCompact>(*node);
    return node;
  }

  static void set_children(void* node_ptr, void** children, unsigned int count, void*) {
    auto* node = static_cast<Node*>(node_ptr);
    for (unsigned int i = 0; i < count; ++i)
      node->child[i] = reinterpret_cast<NodeRef>(children[i]);
  }

  static void set_bounds(void* node_ptr, const RTCBounds** bounds, unsigned int count, void*) {
    BBox boxes[N];
    for (unsigned int i = 0; i < count; ++i) {
      const float* b = &bounds[i]->lower_x;  // lower_x, y, z, align0, upper_x, y, z, align1
      boxes[i].lo = Vec3f(b[0], b[1], b[2]);
      boxes[i].hi = Vec3f(b[4], b[5], b[6]);
    }
    set_child_boxes<N, kCompact>(*static_cast<Node*>(node_ptr), boxes, static_cast<int>(count));
  }

  static void* create_leaf(RTCThreadLocalAllocator alloc, const RTCBuildPrimitive* prims,
                           size_t count, void* user) {
    auto* ctx = static_cast<BuildContext*>(user);
    ctx->references.fetch_add(count, std::memory_order_relaxed);
    const GeometryView& g = *ctx->geometry;
    size_t packs = kCompact ? 0 : (count + 3) / 4;
    const LeafHeader header{static_cast<uint32_t>(count), static_cast<uint32_t>(packs)};
    const size_t bytes = leaf_bytes(header, kCompact);
    auto* leaf = static_cast<char*>(rtcThreadLocalAlloc(alloc, bytes, kCacheLine));
    write_leaf_header(leaf, header);
    if constexpr (kCompact) {
      auto* ids = reinterpret_cast<uint32_t*>(leaf + kLeafPayloadOffset);
      for (size_t i = 0; i < count; ++i) ids[i] = prims[i].primID;
    } else {
      auto* pack = reinterpret_cast<TriPack4*>(leaf);
      std::memset(static_cast<void*>(pack), 0, packs * sizeof(TriPack4));
      for (size_t i = 0; i < packs * 4; ++i) {
        TriPack4& p = pack[i / 4];
        size_t lane = i % 4;
        if (i >= count) {
          p.prim[lane] = kInvalidId;
          continue;
        }
        uint32_t tri = prims[i].primID;
        Vec3f a = vertex(g, tri, 0), b = vertex(g, tri, 1), c = vertex(g, tri, 2);
        if (!ctx->robust) {
          b = b - a;
          c = c - a;
        }
        const Vec3f rows[3] = {a, b, c};
        for (int r = 0; r < 3; ++r) {
          for (int k = 0; k < 3; ++k) p.p[r * 3 + k][lane] = rows[r][k];
        }
        p.prim[lane] = tri;
      }
    }
    // max_leaf <= 32 bounds a fast leaf to 8 packs, well inside the reference's count bits.
    return reinterpret_cast<void*>(make_leaf_ref(leaf, static_cast<uint32_t>(packs)));
  }
};

// Rounding: t = (position - p[dim]) / (q[dim] - p[dim]) carries three roundings, q - p one and the
// fused x = p + (q - p) t one, so x is off by at most ~4u |q - p| + u |x| per axis (u = 2^-24,
// t <= 1); the pad 4e-7 (|x| + |q - p|) is > 6u of each. SplitBoundsAreConservativeAndTight
// checks the boxes against exact clipping (a pad of 1e-7 already fails it).
[[gnu::always_inline]] inline void clip_triangle(const SplitTriangle& tri,
                                                 const RTCBuildPrimitive& prim, unsigned int dim,
                                                 float position, RTCBounds& left,
                                                 RTCBounds& right) {
  const __m128 inf = _mm_set1_ps(kInf);
  const __m128 sign = _mm_set1_ps(-0.0f);
  const __m128 pos = _mm_set1_ps(position);
  const __m128 on_dim = _mm_castsi128_ps(
      _mm_cmpeq_epi32(_mm_setr_epi32(0, 1, 2, 3), _mm_set1_epi32(static_cast<int>(dim))));
  const __m128 v[3] = {_mm_load_ps(tri.v[0]), _mm_load_ps(tri.v[1]), _mm_load_ps(tri.v[2])};
  const float d[3] = {tri.v[0][dim], tri.v[1][dim], tri.v[2][dim]};
  __m128 l_lo = inf, l_hi = _mm_sub_ps(_mm_setzero_ps(), inf), r_lo = inf, r_hi = l_hi;
  for (int i = 0; i < 3; ++i) {
    const int j = i == 2 ? 0 : i + 1;
    const __m128 p = v[i], q = v[j];
    const float pd = d[i], qd = d[j];
    if (pd <= position) {
      l_lo = _mm_min_ps(l_lo, p);
      l_hi = _mm_max_ps(l_hi, p);
    }
    if (pd >= position) {
      r_lo = _mm_min_ps(r_lo, p);
      r_hi = _mm_max_ps(r_hi, p);
    }
    if ((pd < position && qd > position) || (pd > position && qd < position)) {
      const float t = std::clamp((position - pd) / (qd - pd), 0.0f, 1.0f);
      const __m128 e = _mm_sub_ps(q, p);
      const __m128 x = _mm_fmadd_ps(e, _mm_set1_ps(t), p);
      const __m128 pad = _mm_mul_ps(_mm_add_ps(_mm_andnot_ps(sign, x), _mm_andnot_ps(sign, e)),
                                    _mm_set1_ps(4e-7f));
      const __m128 lo = _mm_blendv_ps(_mm_sub_ps(x, pad), pos, on_dim);
      const __m128 hi = _mm_blendv_ps(_mm_add_ps(x, pad), pos, on_dim);
      l_lo = _mm_min_ps(l_lo, lo);
      l_hi = _mm_max_ps(l_hi, hi);
      r_lo = _mm_min_ps(r_lo, lo);
      r_hi = _mm_max_ps(r_hi, hi);
    }
  }
  // The primitive's box: lower_x..z + geomID, upper_x..z + primID. Lane 3 of the outputs
  // (align0/align1) carries the primitive's ids; Embree overwrites them.
  const __m128 b_lo = _mm_loadu_ps(&prim.lower_x);
  const __m128 b_hi = _mm_loadu_ps(&prim.upper_x);
  l_lo = _mm_max_ps(l_lo, b_lo);
  l_hi = _mm_min_ps(_mm_min_ps(l_hi, b_hi), _mm_blendv_ps(inf, pos, on_dim));
  r_lo = _mm_max_ps(_mm_max_ps(r_lo, b_lo),
                    _mm_blendv_ps(_mm_sub_ps(_mm_setzero_ps(), inf), pos, on_dim));
  r_hi = _mm_min_ps(r_hi, b_hi);
  const __m128 lane3 = _mm_castsi128_ps(_mm_setr_epi32(0, 0, 0, -1));
  _mm_storeu_ps(&left.lower_x, _mm_blendv_ps(l_lo, b_lo, lane3));
  _mm_storeu_ps(&left.upper_x, _mm_blendv_ps(l_hi, b_hi, lane3));
  _mm_storeu_ps(&right.lower_x, _mm_blendv_ps(r_lo, b_lo, lane3));
  _mm_storeu_ps(&right.upper_x, _mm_blendv_ps(r_hi, b_hi, lane3));
}

}  // namespace

void split_bounds(const SplitTriangle& tri, const RTCBuildPrimitive& prim, unsigned int dim,
                  float position, RTCBounds& left, RTCBounds& right) {
  clip_triangle(tri, prim, dim, position, left, right);
}

namespace {

// Embree calls splitPrimitive for every bin boundary a fragment spans in each spatial binning:
// millions of calls per build (bmw-m6: 5.7 M for 42 k kept splits; lost-empire: 16 M for 216),
// so the clipping is branch-light SSE on the precomputed vertices and touches no shared counter.
void split_primitive(const RTCBuildPrimitive* prim, unsigned int dim, float position,
                     RTCBounds* left, RTCBounds* right, void* user) {
  const auto* ctx = static_cast<const BuildContext*>(user);
  clip_triangle(ctx->split_triangles[prim->primID], *prim, dim, position, *left, *right);
}

template <int N, bool kCompact>
void set_callbacks(RTCBuildArguments& args) {
  using C = Callbacks<N, kCompact>;
  args.createNode = &C::create_node;
  args.setNodeChildren = &C::set_children;
  args.setNodeBounds = &C::set_bounds;
  args.createLeaf = &C::create_leaf;
}

template <bool kCompact>
void set_callbacks_for_width(int width, RTCBuildArguments& args) {
  switch (width) {
    case 2:
      set_callbacks<2, kCompact>(args);
      break;
    case 4:
      set_callbacks<4, kCompact>(args);
      break;
    default:
      set_callbacks<8, kCompact>(args);
      break;
  }
}

RTCBuildQuality embree_quality(BvhQuality q) {
  switch (q) {
    case BvhQuality::kLow:
      return RTC_BUILD_QUALITY_LOW;
    case BvhQuality::kHigh:
      return RTC_BUILD_QUALITY_HIGH;
    default:
      return RTC_BUILD_QUALITY_MEDIUM;
  }
}

}  // namespace

void PrimitiveCache::prepare(const GeometryView& g, bool split_vertices) {
  const bool same = positions_ == g.positions && triangles_ == g.triangles &&
                    vertex_count_ == g.vertex_count && pristine_.size() == g.triangle_count;
  if (!same) {
    positions_ = g.positions;
    triangles_ = g.triangles;
    vertex_count_ = g.vertex_count;
    split_.clear();
    split_.shrink_to_fit();
    pristine_.resize(g.triangle_count);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, g.triangle_count, 4096),
                      [&](const tbb::blocked_range<size_t>& range) {
                        for (size_t i = range.begin(); i < range.end(); ++i) {
                          BBox box;
                          for (int k = 0; k < 3; ++k)
                            box.extend(vertex(g, static_cast<uint32_t>(i), k));
                          RTCBuildPrimitive& p = pristine_[i];
                          p.lower_x = box.lo.x;
                          p.lower_y = box.lo.y;
                          p.lower_z = box.lo.z;
                          p.upper_x = box.hi.x;
                          p.upper_y = box.hi.y;
                          p.upper_z = box.hi.z;
                          p.geomID = 0;
                          p.primID = static_cast<unsigned>(i);
                        }
                      });
  }
  if (split_vertices && split_.size() != g.triangle_count) {
    split_.resize(g.triangle_count);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, g.triangle_count, 4096),
                      [&](const tbb::blocked_range<size_t>& range) {
                        for (size_t i = range.begin(); i < range.end(); ++i) {
                          for (int k = 0; k < 3; ++k) {
                            Vec3f p = vertex(g, static_cast<uint32_t>(i), k);
                            split_[i].v[k][0] = p.x;
                            split_[i].v[k][1] = p.y;
                            split_[i].v[k][2] = p.z;
                            split_[i].v[k][3] = 0.0f;
                          }
                        }
                      });
  }
}

RTCBuildPrimitive* PrimitiveCache::restore(size_t capacity) {
  capacity = std::max(capacity, pristine_.size());
  // Keep the array while it fits: a medium build after a high one uses the front of the larger
  // array. A much smaller geometry (beyond the high capacity) gets a smaller array.
  const size_t largest = static_cast<size_t>(
      std::ceil(static_cast<double>(pristine_.size()) * kSpatialSplitCapacityFactor));
  if (work_capacity_ < capacity || work_capacity_ > std::max(largest, capacity)) {
    work_.reset();  // free first: the old contents need no copy
    work_.reset(new RTCBuildPrimitive[capacity]);
    work_capacity_ = capacity;
  }
  std::copy(pristine_.begin(), pristine_.end(), work_.get());
  return work_.get();
}

BuildResult build_tree(const GeometryView& geometry, const BvhConfig& config, EmbreeDevice& device,
                       PrimitiveCache& primitives, Tree& tree) {
  tree.reset();
  BuildResult result;
  TreeShape shape{config.branching, config.compact, config.robust};
  const bool high = config.quality == BvhQuality::kHigh;
  primitives.prepare(geometry, high);
  if (primitives.count() == 0) {
    tree.adopt_embree(nullptr, kEmptyRef, shape);
    return result;
  }
  size_t capacity =
      high ? static_cast<size_t>(std::ceil(primitives.count() * kSpatialSplitCapacityFactor))
           : primitives.count();

  BuildContext ctx;
  ctx.geometry = &geometry;
  ctx.split_triangles = primitives.split_triangles();
  ctx.robust = config.robust;

  RTCBuildArguments args = rtcDefaultBuildArguments();
  args.byteSize = sizeof(args);
  args.buildQuality = embree_quality(config.quality);
  args.buildFlags = config.is_static ? RTC_BUILD_FLAG_NONE : RTC_BUILD_FLAG_DYNAMIC;
  args.maxBranchingFactor = static_cast<unsigned>(config.branching);
  args.maxDepth = static_cast<unsigned>(config.max_depth);
  args.sahBlockSize = static_cast<unsigned>(config.sah_block_size);
  args.minLeafSize = static_cast<unsigned>(config.min_leaf);
  args.maxLeafSize = static_cast<unsigned>(config.max_leaf);
  args.traversalCost = config.trav_cost;
  args.intersectionCost = config.int_cost;
  args.primitives = primitives.restore(capacity);
  args.primitiveCount = primitives.count();
  args.primitiveArrayCapacity = capacity;
  if (config.compact)
    set_callbacks_for_width<true>(config.branching, args);
  else
    set_callbacks_for_width<false>(config.branching, args);
  args.splitPrimitive = high ? &split_primitive : nullptr;
  args.userPtr = &ctx;

  device.take_error();
  RTCBVH handle = rtcNewBVH(device.get());
  if (!handle) throw BuildError("tuned BVH: rtcNewBVH failed: " + device.take_error());
  args.bvh = handle;
  void* root = rtcBuildBVH(&args);
  std::string error = device.take_error();
  if (!root || !error.empty()) {
    rtcReleaseBVH(handle);
    throw BuildError("tuned BVH build refused by Embree (" + config.to_string() +
                     "): " + (error.empty() ? "no tree returned" : error));
  }
  tree.adopt_embree(handle, reinterpret_cast<NodeRef>(root), shape);
  result.references = ctx.references.load();
  result.inner_nodes = ctx.inner_nodes.load();
  result.spatial_splits = result.references - std::min(result.references, primitives.count());
  if (high && result.spatial_splits == 0)
    result.notes = "quality=high: Embree performed no spatial split (fell back to medium)";
  return result;
}

}  // namespace tuneray::bvh
