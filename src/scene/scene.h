// The renderable scene: one global triangle list (what the accelerators see), per-triangle
// material and mesh ids (what shading and the indicators see), materials, textures, lights,
// environment and cameras. Loaders and built-in scenes produce it.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "image/image.h"
#include "math/bbox.h"
#include "math/vec.h"
#include "scene/camera.h"
#include "scene/material.h"

namespace tuneray {

struct Triangle {
  uint32_t v[3];
};

// A named group of triangles (an OBJ object/group or a PLY/glTF mesh) for statistics and
// the per-mesh indicators. Triangles [first, first + count) of Scene::triangles.
struct MeshRange {
  std::string name;
  uint32_t first = 0;
  uint32_t count = 0;
};

struct PointLight {
  Vec3f position;
  Color intensity;  // radiant intensity (W/sr)
};

struct Environment {
  Color constant{0.0f};  // used when map is empty
  Image map;             // equirectangular, linear radiance; y up, u = 0 at -z (see docs)
  float scale = 1.0f;
  bool active() const { return !map.empty() || max_component(constant) > 0.0f; }
};

struct Texture {
  std::string path;
  Image image;  // linear (sRGB decoded at load)
};

struct Scene {
  std::string name;
  std::string source;  // file or built-in name

  // Geometry (all meshes merged, world space).
  std::vector<Vec3f> positions;
  std::vector<Vec3f> normals;  // per vertex, same size as positions (generated when missing)
  std::vector<Vec2f> uvs;      // per vertex, same size as positions, or empty
  std::vector<Triangle> triangles;
  std::vector<uint32_t> material_ids;  // per triangle
  std::vector<MeshRange> meshes;

  std::vector<Material> materials;
  std::vector<Texture> textures;
  std::vector<PointLight> point_lights;
  Environment environment;
  float light_scale = 1.0f;  // multiplies every emission (JSON "light_scale")

  std::vector<CameraDesc> cameras;  // at least one after loading
  std::vector<CameraPath> camera_paths;

  // Things the loader decided on the user's behalf (automatic camera, default sky, ...), for
  // `tuneray info`; loading itself prints nothing.
  std::vector<std::string> notes;

  BBox bounds() const;
  size_t triangle_count() const { return triangles.size(); }
  size_t emissive_triangle_count() const;
  // Rough resident size of geometry, materials and textures, in bytes.
  size_t memory_bytes() const;
};

}  // namespace tuneray
