// PLY and glTF (and whatever else assimp reads) into our scene: triangles only, node transforms
// baked in, diffuse/base colour, emission and the diffuse/base-colour texture.
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <assimp/Importer.hpp>
#include <cmath>
#include <filesystem>

#include "scene/gltf_check.h"
#include "scene/loaders.h"
#include "scene/ply_check.h"
#include "scene/texture_cache.h"

namespace tuneray {

namespace {

namespace fs = std::filesystem;

Color color_or(const aiMaterial& m, const char* key, unsigned type, unsigned index,
               Color fallback) {
  aiColor4D c;
  if (m.Get(key, type, index, c) != AI_SUCCESS) return fallback;
  return {c.r, c.g, c.b};
}

Material convert_material(const aiMaterial& in, const std::string& file, TextureCache& textures,
                          std::vector<std::string>& notes) {
  Material m;
  aiString name;
  m.name = in.Get(AI_MATKEY_NAME, name) == AI_SUCCESS ? name.C_Str() : "material";
  m.base_color = color_or(in, AI_MATKEY_COLOR_DIFFUSE, m.base_color);
  m.base_color = color_or(in, AI_MATKEY_BASE_COLOR, m.base_color);  // glTF PBR
  m.emission = color_or(in, AI_MATKEY_COLOR_EMISSIVE, Color(0.0f));
  aiString tex;
  if (in.GetTexture(aiTextureType_BASE_COLOR, 0, &tex) == AI_SUCCESS ||
      in.GetTexture(aiTextureType_DIFFUSE, 0, &tex) == AI_SUCCESS) {
    std::string t = tex.C_Str();
    if (!t.empty() && t[0] == '*') {
      notes.push_back("embedded texture of material '" + m.name + "' ignored");
    } else {
      fs::path p(t);
      if (!p.is_absolute()) p = fs::path(file).parent_path() / p;
      m.base_texture = textures.get(p.string(), file);
    }
  }
  return m;
}

void append_mesh(const aiMesh& mesh, const std::string& file, Scene& scene, bool with_uvs) {
  const auto base = static_cast<uint32_t>(scene.positions.size());
  const auto first = static_cast<uint32_t>(scene.triangles.size());
  for (unsigned i = 0; i < mesh.mNumVertices; ++i) {
    const aiVector3D& p = mesh.mVertices[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw SceneError(file + ": mesh '" + mesh.mName.C_Str() + "' vertex " + std::to_string(i) +
                       " has a non-finite coordinate");
    scene.positions.emplace_back(p.x, p.y, p.z);
    Vec3f n(0, 1, 0);
    if (mesh.mNormals) {
      const aiVector3D& a = mesh.mNormals[i];
      Vec3f v(a.x, a.y, a.z);
      float len = length(v);
      if (len > 0 && std::isfinite(len)) n = v / len;
    }
    scene.normals.push_back(n);
    if (with_uvs) {
      Vec2f uv;
      if (mesh.HasTextureCoords(0)) uv = {mesh.mTextureCoords[0][i].x, mesh.mTextureCoords[0][i].y};
      scene.uvs.push_back(uv);
    }
  }
  for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
    const aiFace& face = mesh.mFaces[f];
    if (face.mNumIndices != 3) continue;  // points and lines
    Triangle t;
    for (int k = 0; k < 3; ++k) {
      if (face.mIndices[k] >= mesh.mNumVertices)
        throw SceneError(file + ": mesh '" + mesh.mName.C_Str() + "' face " + std::to_string(f) +
                         " has an index out of range");
      t.v[k] = base + face.mIndices[k];
    }
    scene.triangles.push_back(t);
    scene.material_ids.push_back(mesh.mMaterialIndex);
  }
  auto count = static_cast<uint32_t>(scene.triangles.size()) - first;
  if (count > 0) {
    std::string name = mesh.mName.length ? mesh.mName.C_Str() : "mesh";
    scene.meshes.push_back({name, first, count});
  }
}

}  // namespace

Scene load_with_assimp(const std::string& path) {
  if (!fs::is_regular_file(path)) throw SceneError(path + ": cannot open file");
  const std::string format = mesh_format(path);
  if (format == "ply") check_ply_file(path);
  if (format == "gltf" || format == "glb") check_gltf_file(path);
  Assimp::Importer importer;
  const aiScene* in = importer.ReadFile(
      path, aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_GenSmoothNormals |
                aiProcess_PreTransformVertices | aiProcess_SortByPType);
  if (!in || (in->mFlags & AI_SCENE_FLAGS_INCOMPLETE))
    throw SceneError(path + ": " + std::string(importer.GetErrorString()));

  Scene scene;
  scene.source = path;
  scene.name = fs::path(path).stem().string();
  TextureCache textures(scene.textures);
  for (unsigned i = 0; i < in->mNumMaterials; ++i)
    scene.materials.push_back(convert_material(*in->mMaterials[i], path, textures, scene.notes));
  if (scene.materials.empty()) scene.materials.push_back(Material{.name = "default"});
  bool with_uvs = false;
  for (unsigned i = 0; i < in->mNumMeshes; ++i) with_uvs |= in->mMeshes[i]->HasTextureCoords(0);
  for (unsigned i = 0; i < in->mNumMeshes; ++i) {
    const aiMesh& mesh = *in->mMeshes[i];
    if (mesh.mMaterialIndex >= scene.materials.size())
      throw SceneError(path + ": mesh '" + mesh.mName.C_Str() + "' has no valid material");
    append_mesh(mesh, path, scene, with_uvs);
  }
  if (scene.triangles.empty()) throw SceneError(path + ": no triangles");
  return scene;
}

}  // namespace tuneray
