// A built tuned BVH: the root reference plus whatever owns the node memory (Embree's BVH handle
// for the tree as built, or our own contiguous buffer after the static relayout).
#pragma once

#include <embree3/rtcore.h>

#include <cstddef>

#include "accel/bvh_layout.h"

namespace tuneray::bvh {

struct TreeShape {
  int width = 2;
  bool compact = false;
  bool robust = false;
};

// Memory for nodes or leaves that a Tree adopts (released with std::free), cache-line aligned.
// A buffer of 2 MiB or more is aligned to 2 MiB, rounded up to whole 2 MiB and advised as
// transparent huge pages, as Embree advises its own BVH memory: a tree of tens of MiB spans
// thousands of 4 KiB pages, far beyond the TLB, and in a frame the shading evicts the tree's
// translations as well as its lines. Throws std::bad_alloc.
void* tree_alloc(size_t bytes);

class Tree {
 public:
  Tree() = default;
  ~Tree() { reset(); }
  Tree(const Tree&) = delete;
  Tree& operator=(const Tree&) = delete;

  // Takes ownership of an Embree BVH handle whose allocator holds the nodes of `root`.
  void adopt_embree(RTCBVH handle, NodeRef root, TreeShape shape);
  // Takes ownership of a buffer from tree_alloc holding the nodes of `root`; releases the
  // Embree handle (the nodes it held are no longer referenced).
  void adopt_buffer(void* buffer, size_t bytes, NodeRef root);
  // Takes ownership of a buffer from tree_alloc holding the inner nodes of `root`, of shape
  // `shape`, whose leaves are still in the Embree handle's allocator (kept), but for those in
  // `leaves` (from tree_alloc too, may be null): leaves the collapse made by merging others.
  void adopt_collapsed(void* nodes, size_t bytes, NodeRef root, TreeShape shape,
                       void* leaves = nullptr);
  // Takes ownership of a buffer from tree_alloc holding the inner nodes of `root`, whose
  // leaves stay where they are (the Embree handle, kept); replaces the inner nodes held so far.
  void adopt_inner_nodes(void* nodes, size_t bytes, NodeRef root);
  void reset();

  NodeRef root() const { return root_; }
  const TreeShape& shape() const { return shape_; }
  // The whole tree in one buffer of ours (static=1).
  bool relaid_out() const { return buffer_ != nullptr && handle_ == nullptr; }
  bool collapsed() const { return collapsed_; }

 private:
  NodeRef root_ = kEmptyRef;
  TreeShape shape_;
  RTCBVH handle_ = nullptr;
  void* buffer_ = nullptr;
  size_t buffer_bytes_ = 0;
  void* leaf_buffer_ = nullptr;  // merged leaves of a collapsed tree
  bool collapsed_ = false;
};

}  // namespace tuneray::bvh
