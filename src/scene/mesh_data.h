// Small procedural meshes for the built-in scenes, and appending them to a Scene.
#pragma once

#include <string>
#include <vector>

#include "scene/scene.h"

namespace tuneray {

struct MeshData {
  std::vector<Vec3f> positions;
  std::vector<Vec3f> normals;  // unit, one per position
  std::vector<Triangle> triangles;

  void append(const MeshData& other);
};

// Parallelogram corner, corner + u, corner + u + v, corner + v as two triangles with flat
// normals, turned so that its front faces along `facing`.
MeshData make_quad(Vec3f corner, Vec3f u, Vec3f v, Vec3f facing);
// Axis-aligned box [lo, hi] with outward flat normals (24 vertices, 12 triangles).
MeshData make_box(Vec3f lo, Vec3f hi);
// Unit sphere: an icosahedron subdivided `levels` times (20 * 4^levels triangles), exact normals.
MeshData make_icosphere(int levels);
// Torus around the y axis: `rings` segments around the axis, `sides` around the tube
// (2 * rings * sides triangles), exact normals.
MeshData make_torus(float major_radius, float minor_radius, int rings, int sides);

// Rotation about the y (then x) axis in degrees, then a translation.
void rotate_y(MeshData& mesh, float degrees, Vec3f pivot);
void rotate_x(MeshData& mesh, float degrees, Vec3f pivot);
void scale_translate(MeshData& mesh, float scale, Vec3f offset);

// Appends `mesh` as one MeshRange named `name` using material `material` (scene.uvs stays
// empty: built-ins are untextured).
void add_mesh(Scene& scene, const std::string& name, const MeshData& mesh, uint32_t material);
uint32_t add_material(Scene& scene, Material material);

}  // namespace tuneray
