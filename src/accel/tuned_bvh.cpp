#include "accel/tuned_bvh.h"

#include <chrono>
#include <utility>

#include "accel/bvh_collapse.h"
#include "accel/bvh_reinsert.h"
#include "accel/bvh_stream.h"
#include "accel/bvh_walk.h"

namespace tuneray {

namespace {

BBox bounds_of(const GeometryView& geometry) {
  BBox box;
  for (size_t i = 0; i < geometry.vertex_count; ++i) box.extend(geometry.positions[i]);
  return box;
}

}  // namespace

TunedBvhAccel::TunedBvhAccel(BvhConfig config, std::shared_ptr<EmbreeDevice> device)
    : device_(std::move(device)) {
  set_config(config);
}

void TunedBvhAccel::set_config(const BvhConfig& config) {
  BvhConfig c = config;
  config_note_ = c.validate();
  config_ = c;
}

BuildStats TunedBvhAccel::build(const GeometryView& geometry) {
  using Clock = std::chrono::steady_clock;
  auto start = Clock::now();
  auto next = std::make_unique<bvh::Tree>();
  bvh::BuildResult result;
  std::string reinsert_note;
  // ray_weight reaches the tree through the passes after the build that price boxes.
  const bool weighted =
      config_.ray_weight > 0.0f && (config_.reinserts() || config_.collapses_optimally());
  const bool has_sample = rays_ && !rays_->empty();
  try {
    result = bvh::build_tree(geometry, config_, *device_, primitives_, *next);
    const bvh::BoxMeasure measure =
        weighted && has_sample
            ? bvh::BoxMeasure(rays_.get(), config_.ray_weight, bounds_of(geometry))
            : bvh::BoxMeasure();
    // The traversal's stack holds a path of kMaxTraversalDepth nodes (8 wide after the
    // collapse); the builder's max_depth bounds Embree's build, not this optimisation.
    if (config_.reinserts())
      reinsert_note =
          bvh::describe(bvh::reinsert_subtrees(*next, bvh::kMaxTraversalDepth, measure));
    // Leaves merge up to the configuration's largest leaf, so max_leaf keeps its meaning, and
    // are priced with its costs.
    if (config_.collapses())
      bvh::collapse_to_wide(*next, result.inner_nodes, config_.max_leaf,
                            config_.int_cost / config_.trav_cost, config_.optimal_collapse,
                            measure);
    if (config_.is_static) bvh::relayout_depth_first(*next);
  } catch (...) {
    tree_.reset();
    context_ = {};
    kernels_ = {};
    coherent_batch_ = nullptr;
    coherent_planes_ = nullptr;
    occluded_batch_ = nullptr;
    tree_stats_ = {};
    throw;
  }
  BuildStats stats;
  stats.build_ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();

  tree_ = std::move(next);
  context_ = {tree_->root(), geometry.positions, geometry.triangles};
  kernels_ = bvh::select_kernels(tree_->shape());
  coherent_batch_ = bvh::select_coherent_batch_kernel(tree_->shape());
  coherent_planes_ = bvh::select_coherent_planes_kernel(tree_->shape());
  occluded_batch_ = bvh::select_occluded_batch_kernel(tree_->shape());

  tree_stats_ = bvh::measure_tree(*tree_, config_.trav_cost, config_.int_cost);
  const bvh::TreeStats& ts = tree_stats_;
  stats.memory_bytes = ts.node_bytes + ts.leaf_bytes;
  stats.node_count = ts.node_count;
  stats.leaf_count = ts.leaf_count;
  stats.depth = ts.depth;
  stats.sah_cost = ts.sah_cost;
  std::string notes = config_note_;
  auto add = [&notes](const std::string& s) {
    if (!s.empty()) notes += (notes.empty() ? "" : "; ") + s;
  };
  add(result.notes);
  add(reinsert_note);
  if (tree_->collapsed())
    add(config_.optimal_collapse ? "collapsed into 8-wide nodes by the SAH-optimal plan"
                                 : "collapsed into 8-wide nodes");
  if (weighted)
    add(has_sample
            ? "boxes priced by " + std::to_string(rays_->size()) + " sampled rays of the view"
            : "ray_weight without a ray sample: boxes priced by area");
  if (tree_->relaid_out()) add("relaid out depth-first in one allocation");
  if (config_.quality == BvhQuality::kHigh)
    add("spatial splits: " + std::to_string(result.spatial_splits) + ", references " +
        std::to_string(ts.references) + " for " + std::to_string(geometry.triangle_count) +
        " triangles");
  stats.notes = notes;
  return stats;
}

void TunedBvhAccel::swap_tree(TunedBvhAccel& other) noexcept {
  using std::swap;
  // The traversal context points into the tree's own allocation and at the geometry, never
  // into this object, so it stays valid across the exchange.
  swap(config_, other.config_);
  swap(config_note_, other.config_note_);
  swap(tree_, other.tree_);
  swap(context_, other.context_);
  swap(kernels_, other.kernels_);
  swap(coherent_batch_, other.coherent_batch_);
  swap(coherent_planes_, other.coherent_planes_);
  swap(occluded_batch_, other.occluded_batch_);
  swap(tree_stats_, other.tree_stats_);
}

bool TunedBvhAccel::intersect(const Ray& ray, Hit& hit) const {
  if (!kernels_.intersect) return false;
  return kernels_.intersect(context_, ray, hit);
}

bool TunedBvhAccel::occluded(const Ray& ray) const {
  if (!kernels_.occluded) return false;
  return kernels_.occluded(context_, ray);
}

// The loops restate Accel's default ones because here the single-ray calls are not virtual (the
// class is final): the default's would add an indirect call per ray to the wavefront's hottest
// loops.
void TunedBvhAccel::intersect_batch(std::span<const Ray> rays, std::span<Hit> hits,
                                    RayCoherence coherence) const {
  if (coherence == RayCoherence::kCoherent && coherent_batch_) {
    coherent_batch_(context_, kernels_, rays.data(), rays.size(), hits.data());
    return;
  }
  for (size_t i = 0; i < rays.size(); ++i) {
    hits[i] = Hit{};
    intersect(rays[i], hits[i]);
  }
}

void TunedBvhAccel::intersect_planes(const RayPlanes& rays, std::span<Hit> hits,
                                     RayCoherence coherence) const {
  if (coherence == RayCoherence::kCoherent && coherent_planes_) {
    coherent_planes_(context_, kernels_, rays, hits.data());
    return;
  }
  // One ray at a time, each read from the planes: no pass that copies the batch into records.
  for (size_t i = 0; i < rays.size; ++i) {
    hits[i] = Hit{};
    intersect(rays.ray(i), hits[i]);
  }
}

void TunedBvhAccel::occluded_batch(std::span<const Ray> rays,
                                   std::span<uint8_t> occluded_out) const {
  if (occluded_batch_) {
    occluded_batch_(context_, rays.data(), rays.size(), occluded_out.data());
    return;
  }
  for (size_t i = 0; i < rays.size(); ++i) occluded_out[i] = occluded(rays[i]) ? 1 : 0;
}

}  // namespace tuneray
