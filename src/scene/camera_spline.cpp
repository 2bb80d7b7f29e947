#include "scene/camera_spline.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace tuneray {

namespace {

// One centripetal Catmull-Rom segment between p1 and p2 (Barry-Goldman pyramid form).
Vec3f catmull_rom(Vec3f p0, Vec3f p1, Vec3f p2, Vec3f p3, float s) {
  auto knot = [](Vec3f a, Vec3f b) { return std::max(std::sqrt(length(b - a)), 1e-4f); };
  float t0 = 0, t1 = t0 + knot(p0, p1), t2 = t1 + knot(p1, p2), t3 = t2 + knot(p2, p3);
  float t = t1 + (t2 - t1) * s;
  Vec3f a1 = p0 * ((t1 - t) / (t1 - t0)) + p1 * ((t - t0) / (t1 - t0));
  Vec3f a2 = p1 * ((t2 - t) / (t2 - t1)) + p2 * ((t - t1) / (t2 - t1));
  Vec3f a3 = p2 * ((t3 - t) / (t3 - t2)) + p3 * ((t - t2) / (t3 - t2));
  Vec3f b1 = a1 * ((t2 - t) / (t2 - t0)) + a2 * ((t - t0) / (t2 - t0));
  Vec3f b2 = a2 * ((t3 - t) / (t3 - t1)) + a3 * ((t - t1) / (t3 - t1));
  return b1 * ((t2 - t) / (t2 - t1)) + b2 * ((t - t1) / (t2 - t1));
}

}  // namespace

std::vector<CameraDesc> sample_camera_path(const CameraPath& path, int count) {
  const auto& k = path.keyframes;
  if (k.empty()) throw std::invalid_argument("camera path '" + path.name + "' has no keyframes");
  if (count < 1) throw std::invalid_argument("camera path sample count must be >= 1");
  std::vector<CameraDesc> out;
  out.reserve(count);
  const int segments = static_cast<int>(k.size()) - 1;
  for (int i = 0; i < count; ++i) {
    if (segments == 0) {
      out.push_back(k[0]);
      continue;
    }
    float x = count == 1 ? 0.0f : static_cast<float>(i) * segments / (count - 1);
    int seg = std::min(static_cast<int>(x), segments - 1);
    float s = x - seg;
    // End keyframes are mirrored to make phantom control points.
    auto at = [&](int j, auto member) {
      if (j < 0) return k[0].*member * 2.0f - k[1].*member;
      if (j > segments) return k[segments].*member * 2.0f - k[segments - 1].*member;
      return k[j].*member;
    };
    CameraDesc c = k[seg];
    c.name = path.name + "#" + std::to_string(i);
    c.position =
        catmull_rom(at(seg - 1, &CameraDesc::position), at(seg, &CameraDesc::position),
                    at(seg + 1, &CameraDesc::position), at(seg + 2, &CameraDesc::position), s);
    c.target = catmull_rom(at(seg - 1, &CameraDesc::target), at(seg, &CameraDesc::target),
                           at(seg + 1, &CameraDesc::target), at(seg + 2, &CameraDesc::target), s);
    c.vfov_deg = k[seg].vfov_deg * (1 - s) + k[seg + 1].vfov_deg * s;
    c.lens_radius = k[seg].lens_radius * (1 - s) + k[seg + 1].lens_radius * s;
    out.push_back(c);
  }
  return out;
}

CameraPath automatic_camera_path(const Scene& scene) {
  BBox b = scene.bounds();
  Vec3f c = b.center();
  float r = 0.5f * b.diagonal();
  if (!(r > 0)) r = 1.0f;
  CameraPath path;
  path.name = "auto";
  // Distance factors alternate far and close; the close ones sit inside the bounding sphere so
  // the view is filled by nearby geometry (or, in enclosed scenes, by the interior).
  const float distance[] = {2.6f, 1.2f, 0.35f, 0.9f, 0.15f, 1.8f, 0.5f, 3.0f};
  const float height[] = {0.6f, 0.3f, 0.1f, 0.5f, 0.05f, 0.8f, 0.2f, 0.4f};
  const int n = 8;
  for (int i = 0; i < n; ++i) {
    float angle = 2.0f * kPi * i / n + 0.3f;
    CameraDesc k;
    k.name = "auto" + std::to_string(i);
    k.position = c + Vec3f(std::sin(angle), 0, std::cos(angle)) * (distance[i] * r) +
                 Vec3f(0, height[i] * r, 0);
    // Look past the centre towards the far side, so close views look across the scene.
    k.target = c + Vec3f(-std::sin(angle + 0.5f), -0.2f, -std::cos(angle + 0.5f)) * (0.3f * r);
    k.vfov_deg = 50;
    path.keyframes.push_back(k);
  }
  return path;
}

std::vector<CameraDesc> cameras_along_path(const Scene& scene, int path_index, int count) {
  if (path_index < 0 ||
      (path_index > 0 && path_index >= static_cast<int>(scene.camera_paths.size())))
    throw std::invalid_argument("bad camera path " + std::to_string(path_index) +
                                ": the scene has " + std::to_string(scene.camera_paths.size()));
  const CameraPath path =
      scene.camera_paths.empty() ? automatic_camera_path(scene) : scene.camera_paths[path_index];
  return sample_camera_path(path, count);
}

}  // namespace tuneray
