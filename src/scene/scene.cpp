#include "scene/scene.h"

namespace tuneray {

namespace {

template <typename T>
size_t vector_bytes(const std::vector<T>& v) {
  return v.capacity() * sizeof(T);
}

size_t image_bytes(const Image& image) {
  return image.pixel_count() * sizeof(Color);
}

}  // namespace

BBox Scene::bounds() const {
  BBox box;
  for (const Triangle& t : triangles)
    for (uint32_t v : t.v) box.extend(positions[v]);
  return box;
}

size_t Scene::emissive_triangle_count() const {
  size_t count = 0;
  for (uint32_t id : material_ids)
    if (materials[id].is_emissive()) ++count;
  return count;
}

size_t Scene::memory_bytes() const {
  size_t bytes = sizeof(Scene);
  bytes += vector_bytes(positions) + vector_bytes(normals) + vector_bytes(uvs);
  bytes += vector_bytes(triangles) + vector_bytes(material_ids);
  bytes += vector_bytes(meshes) + vector_bytes(materials) + vector_bytes(textures);
  for (const MeshRange& m : meshes) bytes += m.name.capacity();
  for (const Material& m : materials) bytes += m.name.capacity();
  for (const Texture& t : textures) bytes += t.path.capacity() + image_bytes(t.image);
  bytes += vector_bytes(point_lights) + image_bytes(environment.map);
  return bytes;
}

}  // namespace tuneray
