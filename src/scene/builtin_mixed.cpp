#include "scene/builtins.h"
#include "scene/mesh_data.h"

namespace tuneray {

// Triangle sizes that differ by ten orders of magnitude: a 100k-triangle torus on a floor of
// two triangles 400 units wide, lit by a square area light.
Scene make_mixed_scene() {
  Scene s;
  s.name = s.source = "mixed";
  uint32_t m_floor = add_material(s, {.name = "floor", .base_color = Color(0.5f)});
  uint32_t m_gold = add_material(s, {.name = "gold",
                                     .type = MaterialType::kGlossy,
                                     .specular_color = Color(1.0f, 0.71f, 0.29f),
                                     .roughness_u = 0.2f,
                                     .roughness_v = 0.2f});
  uint32_t m_plastic = add_material(s, {.name = "red_plastic",
                                        .type = MaterialType::kPrincipled,
                                        .base_color = Color(0.6f, 0.08f, 0.05f),
                                        .specular_color = Color(0.04f),
                                        .roughness_u = 0.1f,
                                        .roughness_v = 0.1f});
  uint32_t m_light = add_material(s, {.name = "light", .emission = Color(40.0f)});

  const Vec3f x(1, 0, 0), y(0, 1, 0), z(0, 0, 1);
  const float floor_half = 200.0f;
  add_mesh(
      s, "floor",
      make_quad(Vec3f(-floor_half, 0, -floor_half), x * (2 * floor_half), z * (2 * floor_half), y),
      m_floor);

  MeshData torus = make_torus(1.0f, 0.35f, 500, 100);  // 100,000 triangles
  rotate_x(torus, 60.0f, Vec3f(0));
  // Lowest point after the tilt: R sin 60° + r below the centre; rest it just above the floor.
  scale_translate(torus, 1.0f, Vec3f(0, 0.866f + 0.35f + 0.005f, 0));
  add_mesh(s, "torus", torus, m_gold);
  MeshData box = make_box(Vec3f(1.4f, 0, -0.4f), Vec3f(2.0f, 0.6f, 0.2f));
  rotate_y(box, 30.0f, Vec3f(1.7f, 0, -0.1f));
  add_mesh(s, "box", box, m_plastic);
  add_mesh(s, "light", make_quad(Vec3f(-0.5f, 4.0f, -0.5f), x, z, -y), m_light);

  const Vec3f centre(0, 0.9f, 0);
  CameraDesc front = look_at("front", Vec3f(0.5f, 2.2f, 5.0f), centre, 40.0f);
  s.cameras.push_back(front);
  s.camera_paths.push_back(
      {"tour",
       {front, look_at("far", Vec3f(-30, 20, 40), centre, 25.0f),
        look_at("close_torus", Vec3f(0.6f, 1.2f, 1.3f), Vec3f(0.2f, 1.1f, 0), 50.0f),
        look_at("horizon", Vec3f(-6, 0.4f, -4), Vec3f(40, 0.2f, 30), 60.0f),
        look_at("top_down", Vec3f(0.2f, 9, 0.5f), Vec3f(0, 0, 0), 45.0f)}});
  return s;
}

}  // namespace tuneray
