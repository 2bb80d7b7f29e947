// The `tuned` backend: a BVH built by Embree's rtcBuildBVH into our own node and leaf layouts
// (bvh_layout.h), traversed by our SIMD kernels (bvh_traverse.h), configured by the 11
// parameters of BvhConfig.
#pragma once

#include <memory>

#include "accel/accel.h"
#include "accel/bvh_build.h"
#include "accel/bvh_config.h"
#include "accel/bvh_packet.h"
#include "accel/bvh_stream.h"
#include "accel/bvh_traverse.h"
#include "accel/bvh_tree.h"
#include "accel/bvh_walk.h"
#include "accel/embree_device.h"
#include "accel/ray_sample.h"

namespace tuneray {

class TunedBvhAccel final : public Accel {
 public:
  explicit TunedBvhAccel(BvhConfig config = {},
                         std::shared_ptr<EmbreeDevice> device = EmbreeDevice::shared());

  // Validates (throws std::invalid_argument); takes effect at the next build().
  void set_config(const BvhConfig& config);
  const BvhConfig& config() const { return config_; }

  // Rays of the view the tree is for (accel/ray_sample.h), used by later builds whose
  // configuration has a ray_weight; null: every box is priced by its area.
  void set_ray_sample(std::shared_ptr<const bvh::RaySample> rays) { rays_ = std::move(rays); }
  const std::shared_ptr<const bvh::RaySample>& ray_sample() const { return rays_; }

  std::string name() const override { return "tuned"; }
  std::string describe() const override { return config_.to_string(); }

  // Each build makes a new tree; the previous one is released only when the new one is ready.
  // A refused build (BuildError) leaves the accelerator empty (every ray misses), never
  // half-built. build_ms covers box setup, rtcBuildBVH and (static=1) the relayout; the
  // statistics walk afterwards is not timed.
  BuildStats build(const GeometryView& geometry) override;

  // Exchanges the built trees (each with the configuration it was built with) of this and
  // `other`; each keeps its device and primitive cache. Lets a caller keep the trees of several
  // configurations and switch between them without rebuilding, while a renderer goes on holding
  // this accelerator by reference. Neither tree moves in memory.
  void swap_tree(TunedBvhAccel& other) noexcept;

  // Shape of the current tree (leaf sizes, references) beyond BuildStats.
  const bvh::TreeStats& tree_stats() const { return tree_stats_; }
  bool relaid_out() const { return tree_ && tree_->relaid_out(); }

  bool intersect(const Ray& ray, Hit& hit) const override;
  bool occluded(const Ray& ray) const override;
  void intersect_batch(std::span<const Ray> rays, std::span<Hit> hits,
                       RayCoherence coherence = RayCoherence::kIncoherent) const override;
  void occluded_batch(std::span<const Ray> rays, std::span<uint8_t> occluded) const override;
  void intersect_planes(const RayPlanes& rays, std::span<Hit> hits,
                        RayCoherence coherence = RayCoherence::kIncoherent) const override;

 private:
  BvhConfig config_;
  std::string config_note_;
  std::shared_ptr<EmbreeDevice> device_;
  std::shared_ptr<const bvh::RaySample> rays_;
  bvh::PrimitiveCache primitives_;
  std::unique_ptr<bvh::Tree> tree_;
  bvh::TraversalContext context_;
  bvh::Kernels kernels_;
  bvh::IntersectBatchKernel coherent_batch_ = nullptr;    // packets; none for some layouts
  bvh::IntersectPlanesKernel coherent_planes_ = nullptr;  // the same, from planes
  bvh::OccludedBatchKernel occluded_batch_ = nullptr;     // streams; none for some layouts
  bvh::TreeStats tree_stats_;
};

}  // namespace tuneray
