#include "accel/bvh_tree.h"

#include <cstdlib>

namespace tuneray::bvh {

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
