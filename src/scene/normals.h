// Vertex normals for meshes whose files carry none.
#pragma once

#include <vector>

#include "scene/scene.h"

namespace tuneray {

// Twice the triangle's area times its unit normal (counter-clockwise winding is the front).
inline Vec3f area_normal(Vec3f p0, Vec3f p1, Vec3f p2) {
  return cross(p1 - p0, p2 - p0);
}

// Adds each triangle's area-weighted normal to its three entries of `sums` (indexed like
// `positions`), so big faces dominate the shading of the vertices they share with small ones.
void accumulate_area_normals(const std::vector<Vec3f>& positions,
                             const std::vector<Triangle>& triangles, std::vector<Vec3f>& sums);

// Unit vector along `n`, or +y when `n` is zero or not finite (a vertex of degenerate faces only).
Vec3f normalize_or_up(Vec3f n);

// Replaces scene.normals by area-weighted smooth normals of the whole scene.
void generate_smooth_normals(Scene& scene);

}  // namespace tuneray
