#include "scene/merge.h"

namespace tuneray {

void append_geometry(Scene& into, Scene&& part) {
  const auto vertex_base = static_cast<uint32_t>(into.positions.size());
  const auto triangle_base = static_cast<uint32_t>(into.triangles.size());
  const auto material_base = static_cast<uint32_t>(into.materials.size());
  const auto texture_base = static_cast<int32_t>(into.textures.size());

  // uvs are all-or-nothing per scene: pad whichever side has none.
  if (into.uvs.empty() && !part.uvs.empty()) into.uvs.assign(into.positions.size(), Vec2f());
  if (!into.uvs.empty() && part.uvs.empty()) part.uvs.assign(part.positions.size(), Vec2f());

  into.positions.insert(into.positions.end(), part.positions.begin(), part.positions.end());
  into.normals.insert(into.normals.end(), part.normals.begin(), part.normals.end());
  into.uvs.insert(into.uvs.end(), part.uvs.begin(), part.uvs.end());
  for (const Triangle& t : part.triangles)
    into.triangles.push_back({{t.v[0] + vertex_base, t.v[1] + vertex_base, t.v[2] + vertex_base}});
  for (uint32_t id : part.material_ids) into.material_ids.push_back(id + material_base);
  for (MeshRange& m : part.meshes) {
    m.first += triangle_base;
    into.meshes.push_back(std::move(m));
  }
  for (Material& m : part.materials) {
    if (m.base_texture != kNoTexture) m.base_texture += texture_base;
    into.materials.push_back(std::move(m));
  }
  for (Texture& t : part.textures) into.textures.push_back(std::move(t));
  for (std::string& note : part.notes) into.notes.push_back(std::move(note));
}

}  // namespace tuneray
