// Two accelerators over the same geometry must answer every ray alike, bit for bit: the same
// closest hit (triangle, t, u, v) and the same occlusion. For tree transformations that keep the
// leaves (collapse, reinsertion).
#pragma once

#include <gtest/gtest.h>

#include <cstddef>
#include <vector>

#include "accel/accel.h"

namespace tuneray::test {

struct AnswerCounts {
  size_t hits = 0;
  size_t blocked = 0;
};

inline AnswerCounts expect_same_answers(const Accel& reference, const Accel& other,
                                        const std::vector<Ray>& rays) {
  AnswerCounts counts;
  for (const Ray& ray : rays) {
    Hit a, b;
    const bool found_a = reference.intersect(ray, a), found_b = other.intersect(ray, b);
    EXPECT_EQ(found_a, found_b);
    EXPECT_EQ(a.prim, b.prim);
    EXPECT_EQ(a.t, b.t);
    EXPECT_EQ(a.u, b.u);
    EXPECT_EQ(a.v, b.v);
    counts.hits += found_a ? 1 : 0;
    const bool occluded = reference.occluded(ray);
    EXPECT_EQ(occluded, other.occluded(ray));
    counts.blocked += occluded ? 1 : 0;
  }
  return counts;
}

}  // namespace tuneray::test
