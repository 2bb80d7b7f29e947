// Scene statistics for `tuneray info`.
#pragma once

#include <cstddef>

#include "math/bbox.h"
#include "scene/scene.h"

namespace tuneray {

struct SceneStats {
  size_t triangles = 0;
  size_t vertices = 0;
  size_t meshes = 0;
  size_t materials = 0;
  size_t textures = 0;
  size_t emissive_triangles = 0;
  // Emissive triangles + point lights + 1 for an active environment.
  size_t lights = 0;
  size_t point_lights = 0;
  bool environment = false;
  BBox bounds;
  double surface_area = 0;  // sum of triangle areas
  double emissive_area = 0;
  size_t memory_bytes = 0;
};

SceneStats compute_stats(const Scene& scene);

}  // namespace tuneray
