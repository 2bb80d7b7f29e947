// Tree costs weighted by where a view's rays go (`ray_weight`), not only by box area.
//
// The SAH prices a box by its surface area: the chance that a random line through the scene's
// box crosses it. Rays that start on surfaces inside the scene and end at their nearest hit, or
// camera rays of one view, are not such lines: a reinsertion that removes 40 % of bmw-m6's summed
// area gained nothing measurable in its frames, because the area it removed lay where its rays do
// not go (docs/bvh.md, "Subtree reinsertion"). A RaySample keeps a few thousand segments of the
// rays a renderer traced through a view (origin, direction, distance to what they hit or the
// light), and a BoxMeasure prices a box by a blend of its relative area and the share of those
// segments that pass through it, so the reinsertion and the SAH-optimal collapse minimise the
// node visits of that view's rays. The hits stay exactly those of the unweighted tree (both
// passes keep the leaves as built); only which boxes the traversal visits changes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "math/bbox.h"
#include "math/ray.h"

namespace tuneray::bvh {

class RaySample {
 public:
  // Adds the segment of `ray` from its origin to `length` (at most its tfar). Segments with a
  // non-finite origin or direction, a zero direction, or a length that is NaN, negative or
  // (after the tfar bound) infinite, are skipped.
  void add(const Ray& ray, float length);
  size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }

  // The share of the segments that pass through `box` (touching counts), in [0, 1]; 0 for an
  // empty sample or box.
  float visit_share(const BBox& box) const;

 private:
  // Planes padded to whole groups of eight; padding segments have length -1 and never count.
  std::vector<float> ox_, oy_, oz_, ix_, iy_, iz_, length_;
  size_t size_ = 0;
};

// What a box costs the rays that visit it, up to a common factor: its surface area, or, with a
// sample and a weight w in (0, 1], (1 - w) * area / scene area + w * share of the sample's
// segments through it. Default-constructed it is the plain surface area, so passes that take a
// measure give the trees they gave before when none is set.
class BoxMeasure {
 public:
  BoxMeasure() = default;
  // `scene` is the root's box (the area term's scale); `rays` must outlive the measure.
  BoxMeasure(const RaySample* rays, float ray_weight, const BBox& scene);

  bool weighted() const { return rays_ != nullptr; }
  float operator()(const BBox& box) const {
    if (!rays_) return box.surface_area();
    return area_weight_ * box.surface_area() + ray_weight_ * rays_->visit_share(box);
  }

 private:
  const RaySample* rays_ = nullptr;
  float ray_weight_ = 0.0f;
  float area_weight_ = 1.0f;
};

}  // namespace tuneray::bvh
