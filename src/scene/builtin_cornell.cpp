#include "scene/builtins.h"
#include "scene/mesh_data.h"

namespace tuneray {

CameraDesc look_at(const std::string& name, Vec3f position, Vec3f target, float vfov_deg) {
  CameraDesc c;
  c.name = name;
  c.position = position;
  c.target = target;
  c.vfov_deg = vfov_deg;
  return c;
}

// The box spans [0, 1]^3 with y up and its open side towards +z, where the camera stands.
Scene make_cornell_scene() {
  Scene s;
  s.name = s.source = "cornell";
  const Color white(0.725f, 0.71f, 0.68f);
  uint32_t m_white = add_material(s, {.name = "white", .base_color = white});
  uint32_t m_red = add_material(s, {.name = "red", .base_color = Color(0.63f, 0.065f, 0.05f)});
  uint32_t m_green = add_material(s, {.name = "green", .base_color = Color(0.14f, 0.45f, 0.091f)});
  // Brushed aluminium: highlights stretched along the tangent direction.
  uint32_t m_metal = add_material(s, {.name = "brushed_metal",
                                      .type = MaterialType::kGlossy,
                                      .specular_color = Color(0.91f, 0.92f, 0.92f),
                                      .roughness_u = 0.35f,
                                      .roughness_v = 0.05f});
  // ~0.2 x 0.2 light: about the share of the ceiling the original Cornell light has.
  uint32_t m_light = add_material(
      s, {.name = "light", .base_color = Color(0.78f), .emission = Color(17.0f, 12.0f, 4.0f)});

  const Vec3f x(1, 0, 0), y(0, 1, 0), z(0, 0, 1);
  add_mesh(s, "floor", make_quad(Vec3f(0), x, z, y), m_white);
  add_mesh(s, "ceiling", make_quad(y, x, z, -y), m_white);
  add_mesh(s, "back_wall", make_quad(Vec3f(0), x, y, z), m_white);
  add_mesh(s, "left_wall", make_quad(Vec3f(0), y, z, x), m_red);
  add_mesh(s, "right_wall", make_quad(x, y, z, -x), m_green);
  const float half = 0.1f, light_y = 0.999f;  // just below the ceiling, facing down
  add_mesh(s, "light",
           make_quad(Vec3f(0.5f - half, light_y, 0.5f - half), x * (2 * half), z * (2 * half), -y),
           m_light);

  MeshData tall = make_box(Vec3f(0.18f, 0, 0.2f), Vec3f(0.48f, 0.6f, 0.5f));
  rotate_y(tall, 17.0f, Vec3f(0.33f, 0, 0.35f));
  add_mesh(s, "tall_box", tall, m_metal);
  MeshData short_box = make_box(Vec3f(0.52f, 0, 0.47f), Vec3f(0.82f, 0.3f, 0.77f));
  rotate_y(short_box, -17.0f, Vec3f(0.67f, 0, 0.62f));
  add_mesh(s, "short_box", short_box, m_white);

  const Vec3f centre(0.5f, 0.5f, 0.5f);
  CameraDesc front = look_at("front", Vec3f(0.5f, 0.5f, 2.44f), Vec3f(0.5f, 0.5f, 0), 39.3f);
  s.cameras.push_back(front);
  s.camera_paths.push_back(
      {"tour",
       {front, look_at("far", Vec3f(0.5f, 0.55f, 4.0f), centre, 30.0f),
        look_at("near_tall_box", Vec3f(0.6f, 0.45f, 1.1f), Vec3f(0.33f, 0.35f, 0.35f), 45.0f),
        look_at("corner_low", Vec3f(0.92f, 0.12f, 0.95f), Vec3f(0.2f, 0.4f, 0.2f), 60.0f),
        look_at("light_close", Vec3f(0.5f, 0.6f, 0.8f), Vec3f(0.5f, 1.0f, 0.5f), 50.0f),
        look_at("top_down", Vec3f(0.5f, 0.95f, 0.9f), Vec3f(0.55f, 0.0f, 0.5f), 70.0f)}});
  return s;
}

}  // namespace tuneray
