// Memory layouts of the tuned BVH. Inner nodes hold the boxes of their N children (N = 2, 4, 8)
// as rows lo_x, lo_y, lo_z, hi_x, hi_y, hi_z so one SIMD load covers one plane of all children.
// Child references are tagged pointers: bit 0 set = leaf, 0 = empty slot.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>

namespace tuneray::bvh {

// Nodes and leaves start on a cache line: a 256-byte 8-wide node then spans 4 lines, not 5.
inline constexpr size_t kCacheLine = 64;

// Bytes a block takes in a contiguous layout where every block starts on a cache line.
inline constexpr size_t whole_lines(size_t bytes) {
  return (bytes + kCacheLine - 1) / kCacheLine * kCacheLine;
}

// The deepest tree the traversal's stack holds (a path of this many nodes, 8 wide; Embree's
// maxDepth is at most this too).
inline constexpr int kMaxTraversalDepth = 64;

using NodeRef = uintptr_t;
inline constexpr NodeRef kLeafTag = 1;
inline constexpr NodeRef kEmptyRef = 0;
// Bits 1..5 of a leaf reference hold its number of triangle packs (fast layout), so the
// traversal starts on the packs without waiting for the leaf header; every block is 64-byte
// aligned, so the low 6 bits are free.
inline constexpr int kLeafCodeShift = 1;
inline constexpr NodeRef kLeafCodeMax = 31;
inline constexpr NodeRef kRefLowBits = kCacheLine - 1;

inline bool is_leaf(NodeRef ref) {
  return (ref & kLeafTag) != 0;
}
template <class T>
inline T* ref_ptr(NodeRef ref) {
  return reinterpret_cast<T*>(ref & ~kRefLowBits);
}
// An inner node's reference is its address (make_node_ref), so the traversal's chain from one
// node to the next needs no masking step.
template <class T>
inline T* inner_ptr(NodeRef ref) {
  return reinterpret_cast<T*>(ref);
}
// `code` is the pack count of a fast leaf (at most kLeafCodeMax), 0 for a compact leaf.
inline NodeRef make_leaf_ref(const void* p, uint32_t code = 0) {
  return reinterpret_cast<uintptr_t>(p) | (NodeRef{code} << kLeafCodeShift) | kLeafTag;
}
inline uint32_t leaf_code(NodeRef ref) {
  return static_cast<uint32_t>((ref & kRefLowBits) >> kLeafCodeShift);
}
inline NodeRef make_node_ref(const void* p) {
  return reinterpret_cast<uintptr_t>(p);
}

// Fast layout: full-precision boxes. Empty slots have lo = +inf, hi = -inf (never hit).
template <int N>
struct alignas(32) FastNode {
  float bounds[6][N];
  NodeRef child[N];
};

// Compact layout: each child plane is 8 bits relative to this node's box: value = origin +
// q * scale, computed with one fused multiply-add (the build checks the rounded result is
// conservative with the very same operation the traversal uses).
template <int N>
struct alignas(8) CompactNode {
  float origin[3];
  float scale[3];
  uint8_t q[6][N];
  NodeRef child[N];  // empty slots are kEmptyRef
};

inline float dequantize(float origin, float scale, uint8_t q) {
  return std::fma(static_cast<float>(q), scale, origin);
}

// A compact leaf starts with this header, its triangle indices following at
// kLeafPayloadOffset. A fast leaf starts with its packs, so a ray's leaf test reads whole packs
// from a line boundary (two packs span five lines, not six behind a header), and keeps the header
// right after them, found through the pack count its reference carries (leaf_header).
struct LeafHeader {
  uint32_t prim_count;  // triangles (fast: also the valid lanes over all packs)
  uint32_t pack_count;  // fast layout: packs of 4; compact: 0
};
inline constexpr size_t kLeafPayloadOffset = 16;

// Fast layout leaf payload: 4 triangles per pack, SoA. Non-robust: v0, e1 = v1 - v0,
// e2 = v2 - v0 (Möller-Trumbore). Robust: v0, v1, v2 (exact vertices: the watertight test needs
// identical inputs on both sides of a shared edge). Unused lanes: zero geometry (det = 0, never
// hit) and prim = UINT32_MAX.
struct alignas(16) TriPack4 {
  float p[9][4];  // a.x a.y a.z b.x b.y b.z c.x c.y c.z
  uint32_t prim[4];
};

// Compact layout leaf payload: uint32_t triangle indices (into GeometryView::triangles).

// Bytes of a leaf, header included.
inline size_t leaf_bytes(const LeafHeader& header, bool compact) {
  return kLeafPayloadOffset +
         (compact ? header.prim_count * sizeof(uint32_t) : header.pack_count * sizeof(TriPack4));
}
// Where a leaf's header lies from its start: after a fast leaf's `packs` packs (0 for compact).
inline size_t leaf_header_offset(uint32_t packs) {
  return packs * sizeof(TriPack4);
}

// Writes a leaf's header where leaf_header finds it: after a fast leaf's packs, first in a
// compact one (header.pack_count is 0 there).
inline void write_leaf_header(char* leaf, const LeafHeader& header) {
  std::memcpy(leaf + leaf_header_offset(header.pack_count), &header, sizeof(header));
}

// The header of the leaf `ref` (a compact leaf's reference carries code 0).
inline const LeafHeader* leaf_header(NodeRef ref) {
  return reinterpret_cast<const LeafHeader*>(ref_ptr<const char>(ref) +
                                             leaf_header_offset(leaf_code(ref)));
}
// A fast leaf's packs.
inline const TriPack4* leaf_packs(NodeRef ref) {
  return ref_ptr<const TriPack4>(ref);
}
// A compact leaf's triangle indices.
inline const uint32_t* leaf_ids(NodeRef ref) {
  return reinterpret_cast<const uint32_t*>(ref_ptr<const char>(ref) + kLeafPayloadOffset);
}

}  // namespace tuneray::bvh
