#include "scene/finalize.h"

#include <cmath>
#include <sstream>

#include "scene/camera_spline.h"
#include "scene/load.h"

namespace tuneray {

namespace {

const Vec3f kDiagonal = normalize(Vec3f(0.6f, 0.45f, 1.0f));

// Beyond this, squared extents and surface areas summed over a million triangles (BVH cost
// estimates, light pdfs) overflow float; no real scene comes near it (the solar system in
// metres spans 1e13).
constexpr float kMaxCoordinate = 1e15f;

void check_invariants(const Scene& s) {
  auto fail = [&](const std::string& what) { throw SceneError(s.source + ": " + what); };
  if (s.triangles.empty()) fail("no triangles");
  if (s.normals.size() != s.positions.size()) fail("normals and positions differ in count");
  if (!s.uvs.empty() && s.uvs.size() != s.positions.size())
    fail("uvs and positions differ in count");
  if (s.material_ids.size() != s.triangles.size()) fail("a triangle has no material id");
  for (const Triangle& t : s.triangles)
    for (uint32_t v : t.v)
      if (v >= s.positions.size()) fail("a triangle index is out of range");
  for (size_t i = 0; i < s.positions.size(); ++i) {
    const Vec3f& p = s.positions[i];
    if (!(std::abs(p.x) <= kMaxCoordinate && std::abs(p.y) <= kMaxCoordinate &&
          std::abs(p.z) <= kMaxCoordinate)) {
      std::ostringstream where;
      where << "vertex " << i << " at (" << p.x << ", " << p.y << ", " << p.z
            << ") is non-finite or beyond +-" << kMaxCoordinate
            << ", where float arithmetic in the BVH and the light sampling overflows; rescale "
               "the scene";
      fail(where.str());
    }
  }
  for (uint32_t id : s.material_ids)
    if (id >= s.materials.size()) fail("a material id is out of range");
  for (const Material& m : s.materials)
    if (m.base_texture != kNoTexture &&
        (m.base_texture < 0 || static_cast<size_t>(m.base_texture) >= s.textures.size()))
      fail("material '" + m.name + "' refers to a missing texture");
}

}  // namespace

CameraDesc frame_bounds(const BBox& box, float vfov_deg) {
  CameraDesc c;
  c.name = "auto";
  c.vfov_deg = vfov_deg;
  c.target = box.center();
  float radius = std::max(0.5f * box.diagonal(), 1e-3f);
  float distance = radius / std::sin(0.5f * vfov_deg * kPi / 180.0f);
  c.position = c.target + kDiagonal * distance;
  return c;
}

void finalize_scene(Scene& scene) {
  check_invariants(scene);
  if (scene.meshes.empty())
    scene.meshes.push_back({scene.name, 0, static_cast<uint32_t>(scene.triangles.size())});
  if (scene.cameras.empty()) {
    BBox box = scene.bounds();
    scene.cameras.push_back(frame_bounds(box));
    scene.notes.push_back("automatic camera framing the bounding box");
    if (scene.camera_paths.empty()) {
      scene.camera_paths.push_back(automatic_camera_path(scene));
      scene.notes.push_back("automatic camera path (far and close views around the bounds)");
    }
  }
  if (scene.emissive_triangle_count() == 0 && scene.point_lights.empty() &&
      !scene.environment.active()) {
    scene.environment.constant = Color(1.0f);
    scene.notes.push_back("no lights: added a constant sky of radiance 1");
  }
}

}  // namespace tuneray
