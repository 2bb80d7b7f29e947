#include "accel/bvh_build.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <limits>

#include "math/bbox.h"
#include "scene/scene.h"

namespace tuneray::bvh {

namespace {

struct BuildContext {
  const GeometryView* geometry = nullptr;
  bool robust = false;
  std::atomic<size_t> splits{0};
  std::atomic<size_t> references{0};
};

Vec3f abs3(Vec3f v) {
  return {std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)};
}

Vec3f vertex(const GeometryView& g, uint32_t tri, int k) {
  return g.positions[g.triangles[tri].v[k]];
}

template <int N, bool kCompact>
struct Callbacks {
  using Node = std::conditional_t<kCompact, CompactNode<N>, FastNode<N>>;

  static void* create_node(RTCThreadLocalAllocator alloc, unsigned int, void*) {
    auto* node = static_cast<Node*>(rtcThreadLocalAlloc(alloc, sizeof(Node), kCacheLine));
    if constexpr (kCompact) {
      std::memset(node, 0, sizeof(Node));
      for (int i = 0; i < N; ++i) {
        for (int a = 0; a < 3; ++a) node->q[a][i] = 255;  // lo > hi: empty
      }
    } else {
      for (int i = 0; i < N; ++i) {
        for (int a = 0; a < 3; ++a) {
          node->bounds[a][i] = std::numeric_limits<float>::infinity();
          node->bounds[a + 3][i] = -std::numeric_limits<float>::infinity();
        }
        node->child[i] = kEmptyRef;
      }
    }
    return node;
  }

  static void set_children(void* node_ptr, void** children, unsigned int count, void*) {
    auto* node = static_cast<Node*>(node_ptr);
    for (unsigned int i = 0; i < count; ++i)
      node->child[i] = reinterpret_cast<NodeRef>(children[i]);
  }

  static void set_bounds(void* node_ptr, const RTCBounds** bounds, unsigned int count, void*) {
    auto* node = static_cast<Node*>(node_ptr);
    if constexpr (kCompact) {
      float lo[3] = {kInf, kInf, kInf}, hi[3] = {-kInf, -kInf, -kInf};
      for (unsigned int i = 0; i < count; ++i) {
        const float* b = &bounds[i]->lower_x;  // lower_x, y, z, align0, upper_x, y, z, align1
        for (int a = 0; a < 3; ++a) {
          lo[a] = std::min(lo[a], b[a]);
          hi[a] = std::max(hi[a], b[a + 4]);
        }
      }
      for (int a = 0; a < 3; ++a) {
        float origin = lo[a];
        float scale = (hi[a] - lo[a]) / 255.0f;
        while (dequantize(origin, scale, 255) < hi[a])
          scale = std::nextafter(scale, std::numeric_limits<float>::infinity());
        node->origin[a] = origin;
        node->scale[a] = scale;
        for (unsigned int i = 0; i < count; ++i) {
          const float* b = &bounds[i]->lower_x;
          node->q[a][i] = quantize_down(origin, scale, b[a]);
          node->q[a + 3][i] = quantize_up(origin, scale, b[a + 4]);
        }
      }
    } else {
      for (unsigned int i = 0; i < count; ++i) {
        const float* b = &bounds[i]->lower_x;
        for (int a = 0; a < 3; ++a) {
          node->bounds[a][i] = b[a];
          node->bounds[a + 3][i] = b[a + 4];
        }
      }
    }
  }

  // Largest q whose dequantized value is <= value (so the box only grows).
  static uint8_t quantize_down(float origin, float scale, float value) {
    if (!(scale > 0.0f)) return 0;
    int q = std::clamp(static_cast<int>(std::floor((value - origin) / scale)), 0, 255);
    while (q > 0 && dequantize(origin, scale, static_cast<uint8_t>(q)) > value) --q;
    return static_cast<uint8_t>(q);
  }
  static uint8_t quantize_up(float origin, float scale, float value) {
    if (!(scale > 0.0f)) return 0;
    int q = std::clamp(static_cast<int>(std::ceil((value - origin) / scale)), 0, 255);
    while (q < 255 && dequantize(origin, scale, static_cast<uint8_t>(q)) < value) ++q;
    return static_cast<uint8_t>(q);
  }

  static void* create_leaf(RTCThreadLocalAllocator alloc, const RTCBuildPrimitive* prims,
                           size_t count, void* user) {
    auto* ctx = static_cast<BuildContext*>(user);
    ctx->references.fetch_add(count, std::memory_order_relaxed);
    const GeometryView& g = *ctx->geometry;
    size_t packs = kCompact ? 0 : (count + 3) / 4;
    LeafHeader header{static_cast<uint32_t>(count), static_cast<uint32_t>(packs)};
    size_t bytes = leaf_bytes(&header, kCompact);
    auto* leaf = static_cast<LeafHeader*>(rtcThreadLocalAlloc(alloc, bytes, kCacheLine));
    *leaf = header;
    if constexpr (kCompact) {
      uint32_t* ids = leaf_payload<uint32_t>(leaf);
      for (size_t i = 0; i < count; ++i) ids[i] = prims[i].primID;
    } else {
      TriPack4* pack = leaf_payload<TriPack4>(leaf);
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
    return reinterpret_cast<void*>(make_leaf_ref(leaf));
  }
};

// Clips the triangle of `prim` at `position` along `dim`; both halves are intersected with the
// primitive's own box (it may already be a fragment of an earlier split). Crossing points are
// padded outward by a few ulps so the halves stay conservative despite rounding.
void split_primitive(const RTCBuildPrimitive* prim, unsigned int dim, float position,
                     RTCBounds* left, RTCBounds* right, void* user) {
  auto* ctx = static_cast<BuildContext*>(user);
  const GeometryView& g = *ctx->geometry;
  BBox l, r;
  Vec3f v[3] = {vertex(g, prim->primID, 0), vertex(g, prim->primID, 1), vertex(g, prim->primID, 2)};
  for (int i = 0; i < 3; ++i) {
    const Vec3f& p = v[i];
    const Vec3f& q = v[(i + 1) % 3];
    if (p[dim] <= position) l.extend(p);
    if (p[dim] >= position) r.extend(p);
    if ((p[dim] < position && q[dim] > position) || (p[dim] > position && q[dim] < position)) {
      float t = (position - p[dim]) / (q[dim] - p[dim]);
      Vec3f x = lerp(p, q, std::clamp(t, 0.0f, 1.0f));
      Vec3f pad = (abs3(x) + abs3(q - p)) * 4e-7f;
      x[dim] = position;
      Vec3f lo = x - pad, hi = x + pad;
      lo[dim] = hi[dim] = position;
      l.extend(lo);
      l.extend(hi);
      r.extend(lo);
      r.extend(hi);
    }
  }
  const float pl[3] = {prim->lower_x, prim->lower_y, prim->lower_z};
  const float pu[3] = {prim->upper_x, prim->upper_y, prim->upper_z};
  float* out_l = &left->lower_x;
  float* out_r = &right->lower_x;
  for (int a = 0; a < 3; ++a) {
    out_l[a] = std::max(l.lo[a], pl[a]);
    out_l[a + 4] = std::min(l.hi[a], pu[a]);
    out_r[a] = std::max(r.lo[a], pl[a]);
    out_r[a + 4] = std::min(r.hi[a], pu[a]);
  }
  out_l[dim + 4] = std::min(out_l[dim + 4], position);
  out_r[dim] = std::max(out_r[dim], position);
  ctx->splits.fetch_add(1, std::memory_order_relaxed);
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

void PrimitiveCache::prepare(const GeometryView& g) {
  if (positions_ == g.positions && triangles_ == g.triangles && vertex_count_ == g.vertex_count &&
      pristine_.size() == g.triangle_count)
    return;
  positions_ = g.positions;
  triangles_ = g.triangles;
  vertex_count_ = g.vertex_count;
  pristine_.resize(g.triangle_count);
  for (size_t i = 0; i < g.triangle_count; ++i) {
    BBox box;
    for (int k = 0; k < 3; ++k) box.extend(vertex(g, static_cast<uint32_t>(i), k));
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
}

RTCBuildPrimitive* PrimitiveCache::restore(size_t capacity) {
  capacity = std::max(capacity, pristine_.size());
  if (work_.size() != capacity) {
    work_.clear();
    work_.shrink_to_fit();
    work_.resize(capacity);
  }
  std::copy(pristine_.begin(), pristine_.end(), work_.begin());
  return work_.data();
}

BuildResult build_tree(const GeometryView& geometry, const BvhConfig& config, EmbreeDevice& device,
                       PrimitiveCache& primitives, Tree& tree) {
  tree.reset();
  BuildResult result;
  TreeShape shape{config.branching, config.compact, config.robust};
  primitives.prepare(geometry);
  if (primitives.count() == 0) {
    tree.adopt_embree(nullptr, kEmptyRef, shape);
    return result;
  }
  const bool high = config.quality == BvhQuality::kHigh;
  size_t capacity =
      high ? static_cast<size_t>(std::ceil(primitives.count() * kSpatialSplitCapacityFactor))
           : primitives.count();

  BuildContext ctx;
  ctx.geometry = &geometry;
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
  result.spatial_splits = ctx.splits.load();
  result.references = ctx.references.load();
  if (high && result.spatial_splits == 0)
    result.notes = "quality=high: Embree performed no spatial split (fell back to medium)";
  return result;
}

}  // namespace tuneray::bvh
