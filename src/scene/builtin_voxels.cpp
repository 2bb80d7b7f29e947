#include <cmath>

#include "scene/builtins.h"
#include "scene/mesh_data.h"

namespace tuneray {

namespace {

constexpr int kSize = 80;  // columns per side

// Column heights (1..15 cubes) from a few smooth waves: hills, a valley and a plateau.
int column_height(int x, int z) {
  float h = 6.0f + 3.5f * std::sin(x * 0.17f) * std::cos(z * 0.13f) +
            2.5f * std::sin((x + 2 * z) * 0.07f) + 2.0f * std::cos((x - z) * 0.21f);
  return std::clamp(static_cast<int>(std::lround(h)), 1, 15);
}

int height_or_zero(int x, int z) {
  if (x < 0 || z < 0 || x >= kSize || z >= kSize) return 0;
  return column_height(x, z);
}

}  // namespace

// A 3D heightfield of unit cubes. Only faces that can be seen are emitted, one unit quad per
// exposed cube face, so every triangle has the same size (area 1/2), like a Minecraft export.
Scene make_voxels_scene() {
  Scene s;
  s.name = s.source = "voxels";
  uint32_t m_grass = add_material(s, {.name = "grass", .base_color = Color(0.3f, 0.5f, 0.15f)});
  uint32_t m_snow = add_material(s, {.name = "snow", .base_color = Color(0.85f)});
  uint32_t m_dirt = add_material(s, {.name = "dirt", .base_color = Color(0.45f, 0.3f, 0.2f)});
  uint32_t m_stone = add_material(s, {.name = "stone", .base_color = Color(0.4f)});

  MeshData tops_low, tops_high, sides_dirt, sides_stone;
  const Vec3f x(1, 0, 0), y(0, 1, 0), z(0, 0, 1);
  for (int i = 0; i < kSize; ++i)
    for (int k = 0; k < kSize; ++k) {
      int h = column_height(i, k);
      Vec3f base(static_cast<float>(i), 0, static_cast<float>(k));
      (h >= 11 ? tops_high : tops_low).append(make_quad(base + y * h, x, z, y));
      const struct { int dx, dz; } neighbours[4] = {{-1, 0}, {1, 0}, {0, -1}, {0, 1}};
      for (auto [dx, dz] : neighbours) {
        Vec3f facing(static_cast<float>(dx), 0, static_cast<float>(dz));
        Vec3f corner = base + Vec3f(dx > 0 ? 1.0f : 0.0f, 0, dz > 0 ? 1.0f : 0.0f);
        Vec3f along = dx != 0 ? z : x;
        for (int level = height_or_zero(i + dx, k + dz); level < h; ++level)
          (level >= h - 2 ? sides_dirt : sides_stone)
              .append(make_quad(corner + y * level, along, y, facing));
      }
    }
  add_mesh(s, "grass", tops_low, m_grass);
  add_mesh(s, "snow", tops_high, m_snow);
  add_mesh(s, "dirt", sides_dirt, m_dirt);
  add_mesh(s, "stone", sides_stone, m_stone);

  s.environment.constant = Color(0.35f, 0.45f, 0.6f);  // sky
  // A far point light acts as the sun: about 2 W/m^2 arrive on the terrain.
  const Vec3f centre(kSize / 2.0f, 6.0f, kSize / 2.0f);
  const Vec3f sun = centre + Vec3f(120, 220, 80);
  s.point_lights.push_back(
      {sun, Color(1.0f, 0.95f, 0.85f) * (2.0f * dot(sun - centre, sun - centre))});

  const float n = static_cast<float>(kSize);
  CameraDesc overview = look_at("overview", Vec3f(-18, 40, -18), centre, 45.0f);
  s.cameras.push_back(overview);
  s.camera_paths.push_back(
      {"flyover",
       {overview, look_at("far", Vec3f(n + 60, 70, n + 60), centre, 35.0f),
        look_at("valley", Vec3f(4, 14, n / 2), Vec3f(n, 8, n / 2 + 5), 60.0f),
        look_at("close_hill", Vec3f(20, 17, 10), Vec3f(24, 10, 18), 55.0f),
        look_at("top_down", Vec3f(n / 2, 90, n / 2 + 1), Vec3f(n / 2, 0, n / 2), 40.0f)}});
  return s;
}

}  // namespace tuneray
