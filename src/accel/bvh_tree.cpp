#include "accel/bvh_tree.h"

#include <sys/mman.h>

#include <cstdlib>
#include <new>

namespace tuneray::bvh {

void* tree_alloc(size_t bytes) {
  constexpr size_t kHugePage = size_t{2} << 20;
  const size_t lines = (bytes + kCacheLine - 1) / kCacheLine * kCacheLine;
  void* p = nullptr;
  if (lines >= kHugePage) {
    const size_t whole = (lines + kHugePage - 1) / kHugePage * kHugePage;
    p = std::aligned_alloc(kHugePage, whole);
    // Only advice: where the kernel has no transparent huge pages the memory stays as it is.
    if (p) madvise(p, whole, MADV_HUGEPAGE);
  } else {
    p = std::aligned_alloc(kCacheLine, lines == 0 ? kCacheLine : lines);
  }
  if (!p) throw std::bad_alloc();
  return p;
}

void Tree::adopt_embree(RTCBVH handle, NodeRef root, TreeShape shape) {
  reset();
  handle_ = handle;
  root_ = root;
  shape_ = shape;
}

void Tree::adopt_buffer(void* buffer, size_t bytes, NodeRef root) {
  if (buffer_) std::free(buffer_);
  if (leaf_buffer_) std::free(leaf_buffer_);
  if (handle_) rtcReleaseBVH(handle_);
  handle_ = nullptr;
  leaf_buffer_ = nullptr;
  buffer_ = buffer;
  buffer_bytes_ = bytes;
  root_ = root;
}

void Tree::adopt_collapsed(void* nodes, size_t bytes, NodeRef root, TreeShape shape, void* leaves) {
  if (buffer_) std::free(buffer_);
  if (leaf_buffer_) std::free(leaf_buffer_);
  buffer_ = nodes;
  leaf_buffer_ = leaves;
  buffer_bytes_ = bytes;
  root_ = root;
  shape_ = shape;
  collapsed_ = true;
}

void Tree::adopt_inner_nodes(void* nodes, size_t bytes, NodeRef root) {
  if (buffer_) std::free(buffer_);
  buffer_ = nodes;
  buffer_bytes_ = bytes;
  root_ = root;
}

void Tree::reset() {
  if (handle_) rtcReleaseBVH(handle_);
  if (buffer_) std::free(buffer_);
  if (leaf_buffer_) std::free(leaf_buffer_);
  handle_ = nullptr;
  buffer_ = nullptr;
  leaf_buffer_ = nullptr;
  buffer_bytes_ = 0;
  root_ = kEmptyRef;
  collapsed_ = false;
}

}  // namespace tuneray::bvh
