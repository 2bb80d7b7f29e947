#include "scene/stats.h"

#include "scene/normals.h"

namespace tuneray {

SceneStats compute_stats(const Scene& scene) {
  SceneStats s;
  s.triangles = scene.triangles.size();
  s.vertices = scene.positions.size();
  s.meshes = scene.meshes.size();
  s.materials = scene.materials.size();
  s.textures = scene.textures.size();
  for (size_t i = 0; i < scene.triangles.size(); ++i) {
    const Triangle& t = scene.triangles[i];
    double area = 0.5 * length(area_normal(scene.positions[t.v[0]], scene.positions[t.v[1]],
                                           scene.positions[t.v[2]]));
    s.surface_area += area;
    if (scene.materials[scene.material_ids[i]].is_emissive()) {
      ++s.emissive_triangles;
      s.emissive_area += area;
    }
  }
  s.point_lights = scene.point_lights.size();
  s.environment = scene.environment.active();
  s.lights = s.emissive_triangles + s.point_lights + (s.environment ? 1 : 0);
  s.bounds = scene.bounds();
  s.memory_bytes = scene.memory_bytes();
  return s;
}

}  // namespace tuneray
