#include "scene/normals.h"

#include <cmath>

namespace tuneray {

void accumulate_area_normals(const std::vector<Vec3f>& positions,
                             const std::vector<Triangle>& triangles, std::vector<Vec3f>& sums) {
  for (const Triangle& t : triangles) {
    Vec3f n = area_normal(positions[t.v[0]], positions[t.v[1]], positions[t.v[2]]);
    for (uint32_t v : t.v) sums[v] += n;
  }
}

Vec3f normalize_or_up(Vec3f n) {
  float len = length(n);
  if (!(len > 0.0f) || !std::isfinite(len)) return Vec3f(0, 1, 0);
  return n / len;
}

void generate_smooth_normals(Scene& scene) {
  std::vector<Vec3f> sums(scene.positions.size(), Vec3f(0.0f));
  accumulate_area_normals(scene.positions, scene.triangles, sums);
  scene.normals.resize(scene.positions.size());
  for (size_t i = 0; i < sums.size(); ++i) scene.normals[i] = normalize_or_up(sums[i]);
}

}  // namespace tuneray
