#include "scene/indicators.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace tuneray {

namespace {

// log10 with a floor, so empty quantities map to the bottom of their range.
double log10_floor(double x, double floor_value) {
  return x > 0 ? std::max(std::log10(x), floor_value) : floor_value;
}

// How much a material scatters diffusely: 1 for Lambert, 0 for mirror and glass.
double diffuseness(const Material& m) {
  switch (m.type) {
    case MaterialType::kLambert:
      return 1.0;
    case MaterialType::kMirror:
    case MaterialType::kDielectric:
      return 0.0;
    case MaterialType::kGlossy:
      return std::clamp(0.5 * (m.roughness_u + m.roughness_v), 0.0, 1.0);
    case MaterialType::kPrincipled: {
      double kd = luminance(m.base_color), ks = luminance(m.specular_color);
      return kd + ks > 0 ? kd / (kd + ks) : 1.0;
    }
  }
  return 1.0;
}

}  // namespace

const std::array<IndicatorInfo, kIndicatorCount>& indicator_infos() {
  static const std::array<IndicatorInfo, kIndicatorCount> infos = {{
      {"meshes_log10", 0, 5, "log10 of the number of meshes (1 .. 1e5)"},
      {"triangles_log10", 0, 7, "log10 of the number of triangles (1 .. 1e7)"},
      {"lights_log10", 0, 5, "log10 of 1 + emissive triangles + point lights + environment"},
      {"camera_x", -1, 2, "camera position x in the scene box (0 = min, 1 = max)"},
      {"camera_y", -1, 2, "camera position y in the scene box"},
      {"camera_z", -1, 2, "camera position z in the scene box"},
      {"target_x", -1, 2, "camera target x in the scene box"},
      {"target_y", -1, 2, "camera target y in the scene box"},
      {"target_z", -1, 2, "camera target z in the scene box"},
      {"fov", 0, 180, "vertical field of view in degrees"},
      {"diffuse_ratio", 0, 1, "area-weighted diffuseness of materials (0 mirror/glass, 1 Lambert)"},
      {"extent_log10", -3, 5, "log10 of the bounding-box diagonal"},
      {"area_ratio_log10", -4, 4, "log10 of total surface area / diagonal^2"},
      {"light_area_ratio_log10", -8, 2, "log10 of emissive area / diagonal^2 (-8 when none)"},
      {"area_per_mesh_log10", -8, 2, "log10 of (total area / meshes) / diagonal^2"},
      {"mesh_area_var_mean_log10", -20, 0,
       "log10 of the mean over meshes of the variance of triangle area / diagonal^2"},
      {"mesh_area_var_var_log10", -40, 0,
       "log10 of the variance over meshes of that per-mesh variance"},
  }};
  return infos;
}

SceneIndicators compute_scene_indicators(const Scene& scene) {
  SceneIndicators s;
  s.bounds = scene.bounds();
  s.diagonal = s.bounds.diagonal();
  double diag2 = s.diagonal > 0 ? s.diagonal * s.diagonal : 1.0;
  s.meshes = static_cast<double>(std::max<size_t>(scene.meshes.size(), 1));
  s.triangles = static_cast<double>(scene.triangles.size());
  s.lights = static_cast<double>(scene.emissive_triangle_count() + scene.point_lights.size() +
                                 (scene.environment.active() ? 1 : 0));

  auto triangle_area = [&](size_t i) {
    const Triangle& t = scene.triangles[i];
    Vec3f p0 = scene.positions[t.v[0]], p1 = scene.positions[t.v[1]], p2 = scene.positions[t.v[2]];
    return 0.5 * static_cast<double>(length(cross(p1 - p0, p2 - p0)));
  };

  double total_area = 0, light_area = 0, diffuse_weighted = 0;
  std::vector<double> material_diffuseness(scene.materials.size());
  for (size_t m = 0; m < scene.materials.size(); ++m)
    material_diffuseness[m] = diffuseness(scene.materials[m]);

  // Per-mesh variance of normalised triangle areas (Welford), then mean and variance of those.
  std::vector<double> mesh_variances;
  auto mesh_variance = [&](uint32_t first, uint32_t count) {
    double mean = 0, m2 = 0;
    for (uint32_t k = 0; k < count; ++k) {
      double a = triangle_area(first + k) / diag2;
      double delta = a - mean;
      mean += delta / (k + 1);
      m2 += delta * (a - mean);
    }
    return count > 0 ? m2 / count : 0.0;
  };
  if (scene.meshes.empty()) {
    mesh_variances.push_back(mesh_variance(0, static_cast<uint32_t>(scene.triangles.size())));
  } else {
    for (const MeshRange& r : scene.meshes)
      mesh_variances.push_back(mesh_variance(r.first, r.count));
  }
  for (size_t i = 0; i < scene.triangles.size(); ++i) {
    double a = triangle_area(i);
    total_area += a;
    uint32_t mat = scene.material_ids[i];
    diffuse_weighted += a * material_diffuseness[mat];
    if (scene.materials[mat].is_emissive()) light_area += a;
  }
  s.diffuse_ratio = total_area > 0 ? diffuse_weighted / total_area : 1.0;
  s.area_ratio = total_area / diag2;
  s.light_area_ratio = light_area / diag2;
  s.area_per_mesh_ratio = s.area_ratio / s.meshes;
  double mean = 0;
  for (double v : mesh_variances) mean += v;
  mean /= static_cast<double>(mesh_variances.size());
  double var = 0;
  for (double v : mesh_variances) var += (v - mean) * (v - mean);
  var /= static_cast<double>(mesh_variances.size());
  s.mesh_area_variance_mean = mean;
  s.mesh_area_variance_variance = var;
  return s;
}

Indicators compute_indicators(const SceneIndicators& s, const CameraDesc& camera) {
  Vec3f extent = s.bounds.extent();
  auto unit_box = [&](Vec3f p, int axis) {
    double e = extent[axis];
    return e > 0 ? (p[axis] - s.bounds.lo[axis]) / e : 0.5;
  };
  Indicators ind;
  ind.values = {
      log10_floor(s.meshes, 0),
      log10_floor(s.triangles, 0),
      log10_floor(1 + s.lights, 0),
      unit_box(camera.position, 0),
      unit_box(camera.position, 1),
      unit_box(camera.position, 2),
      unit_box(camera.target, 0),
      unit_box(camera.target, 1),
      unit_box(camera.target, 2),
      camera.vfov_deg,
      s.diffuse_ratio,
      log10_floor(s.diagonal, -3),
      log10_floor(s.area_ratio, -4),
      log10_floor(s.light_area_ratio, -8),
      log10_floor(s.area_per_mesh_ratio, -8),
      log10_floor(s.mesh_area_variance_mean, -20),
      log10_floor(s.mesh_area_variance_variance, -40),
  };
  return ind;
}

}  // namespace tuneray
