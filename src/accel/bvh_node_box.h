// Reading and writing the child boxes of an inner node, for both layouts, so the build
// callbacks, the whole-tree walks and the collapse agree on one conservative quantization.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>

#include "accel/bvh_layout.h"
#include "math/bbox.h"

namespace tuneray::bvh {

template <int N, bool kCompact>
using NodeOf = std::conditional_t<kCompact, CompactNode<N>, FastNode<N>>;

// Child i's box as the traversal sees it (dequantized for the compact layout).
template <int N, bool kCompact>
BBox child_box(const NodeOf<N, kCompact>& n, int i) {
  BBox b;
  for (int a = 0; a < 3; ++a) {
    if constexpr (kCompact) {
      b.lo[a] = dequantize(n.origin[a], n.scale[a], n.q[a][i]);
      b.hi[a] = dequantize(n.origin[a], n.scale[a], n.q[a + 3][i]);
    } else {
      b.lo[a] = n.bounds[a][i];
      b.hi[a] = n.bounds[a + 3][i];
    }
  }
  return b;
}

template <int N, bool kCompact>
int child_count(const NodeOf<N, kCompact>& n) {
  int count = 0;
  for (int i = 0; i < N; ++i) count += n.child[i] != kEmptyRef ? 1 : 0;
  return count;
}

// An inner node with every slot empty (fast: lo = +inf, hi = -inf; compact: q lo > q hi).
template <int N, bool kCompact>
void clear_node(NodeOf<N, kCompact>& node) {
  constexpr float kInfinity = std::numeric_limits<float>::infinity();
  if constexpr (kCompact) {
    node = {};
    for (int i = 0; i < N; ++i)
      for (int a = 0; a < 3; ++a) node.q[a][i] = 255;
  } else {
    for (int i = 0; i < N; ++i) {
      for (int a = 0; a < 3; ++a) {
        node.bounds[a][i] = kInfinity;
        node.bounds[a + 3][i] = -kInfinity;
      }
    }
  }
  for (int i = 0; i < N; ++i) node.child[i] = kEmptyRef;
}

// Largest q whose dequantized value is <= value (so the box only grows).
inline uint8_t quantize_down(float origin, float scale, float value) {
  if (!(scale > 0.0f)) return 0;
  int q = std::clamp(static_cast<int>(std::floor((value - origin) / scale)), 0, 255);
  while (q > 0 && dequantize(origin, scale, static_cast<uint8_t>(q)) > value) --q;
  return static_cast<uint8_t>(q);
}
inline uint8_t quantize_up(float origin, float scale, float value) {
  if (!(scale > 0.0f)) return 0;
  int q = std::clamp(static_cast<int>(std::ceil((value - origin) / scale)), 0, 255);
  while (q < 255 && dequantize(origin, scale, static_cast<uint8_t>(q)) < value) ++q;
  return static_cast<uint8_t>(q);
}

// Writes the boxes of children 0..count-1: exactly (fast), or quantized relative to their union
// so that every dequantized box contains the given one (compact; the check uses the very fused
// multiply-add of the traversal).
template <int N, bool kCompact>
void set_child_boxes(NodeOf<N, kCompact>& node, const BBox* boxes, int count) {
  if constexpr (kCompact) {
    BBox all;
    for (int i = 0; i < count; ++i) all.extend(boxes[i]);
    for (int a = 0; a < 3; ++a) {
      float origin = all.lo[a];
      float scale = (all.hi[a] - all.lo[a]) / 255.0f;
      while (dequantize(origin, scale, 255) < all.hi[a])
        scale = std::nextafter(scale, std::numeric_limits<float>::infinity());
      node.origin[a] = origin;
      node.scale[a] = scale;
      for (int i = 0; i < count; ++i) {
        node.q[a][i] = quantize_down(origin, scale, boxes[i].lo[a]);
        node.q[a + 3][i] = quantize_up(origin, scale, boxes[i].hi[a]);
      }
    }
  } else {
    for (int i = 0; i < count; ++i) {
      for (int a = 0; a < 3; ++a) {
        node.bounds[a][i] = boxes[i].lo[a];
        node.bounds[a + 3][i] = boxes[i].hi[a];
      }
    }
  }
}

}  // namespace tuneray::bvh
