// What make_interaction derives from a triangle that does not depend on where it is hit,
// computed once per scene instead of at every hit: the unit geometric normal, the material, and
// for flat-shaded triangles (three equal vertex normals, as loaders write for faceted meshes and
// as the built-in scenes have) the whole shading frame. A hit then costs no square root or
// division on a flat triangle and one less of each on a smooth one (issue 11: make_interaction
// was 13 % of a Cornell box render).
#pragma once

#include <immintrin.h>

#include <cstdint>
#include <vector>

#include "render/surface.h"
#include "scene/scene.h"

namespace tuneray {

struct alignas(16) TriangleShading {
  Vec3f geometric_normal;  // unit, from the winding; (0, 0, 1) for a degenerate triangle
  uint32_t material = 0;   // index into Scene::materials
  Vec3f tangent;           // flat triangles: the shading frame's s axis (unit, orthogonal to n)
  uint32_t flat = 0;       // 1: the three vertex normals are equal; the frame below is exact
  Vec3f normal;            // flat triangles: the shading normal (the vertices' common normal)
  float padding = 0;
};

class ShadingGeometry {
 public:
  // Reads the scene's triangles once; `scene` must outlive this object.
  explicit ShadingGeometry(const Scene& scene);

  // The interaction make_interaction(scene, hit) computes, up to float rounding: on flat
  // triangles the frame comes from the common vertex normal directly instead of from
  // normalising its barycentric blend.
  SurfaceInteraction interaction(const Hit& hit) const;

  const TriangleShading& triangle(uint32_t prim) const { return triangles_[prim]; }
  void prefetch(uint32_t prim) const {
    _mm_prefetch(reinterpret_cast<const char*>(&triangles_[prim]), _MM_HINT_T0);
  }

 private:
  const Scene& scene_;
  std::vector<TriangleShading> triangles_;
};

}  // namespace tuneray
