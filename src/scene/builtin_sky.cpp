#include <algorithm>
#include <cmath>
#include <cstdint>

#include "scene/builtins.h"
#include "scene/mesh_data.h"

namespace tuneray {

namespace {

constexpr float kPiF = 3.14159265358979f;

// Value noise on a grid that wraps every `period` cells in x, so the map has no seam at u = 0.
float lattice(int x, int y, int period) {
  uint32_t h = static_cast<uint32_t>(((x % period) + period) % period) * 0x8da6b343u ^
               static_cast<uint32_t>(y) * 0xd8163841u;
  h ^= h >> 13;
  h *= 0x85ebca6bu;
  h ^= h >> 16;
  return static_cast<float>(h & 0xffffff) / 16777216.0f;
}

float value_noise(float x, float y, int period) {
  int x0 = static_cast<int>(std::floor(x)), y0 = static_cast<int>(std::floor(y));
  float fx = x - x0, fy = y - y0;
  fx = fx * fx * (3 - 2 * fx);
  fy = fy * fy * (3 - 2 * fy);
  float a = lattice(x0, y0, period), b = lattice(x0 + 1, y0, period);
  float c = lattice(x0, y0 + 1, period), d = lattice(x0 + 1, y0 + 1, period);
  return (a + (b - a) * fx) * (1 - fy) + (c + (d - c) * fx) * fy;
}

// Radiance of the sky in direction d (y up): horizon-to-zenith gradient, clouds, a small sun
// and a dim ground below the horizon. u, v are the texel's equirectangular coordinates.
Color sky_radiance(Vec3f d, float u, float v, Vec3f sun) {
  if (d.y < 0) return Color(0.18f, 0.16f, 0.13f) * (0.6f + 0.4f * (1.0f + d.y));
  float t = std::sqrt(d.y);
  Color horizon(1.1f, 1.05f, 0.95f), zenith(0.18f, 0.35f, 0.9f);
  Color c = horizon * (1 - t) + zenith * t;
  float clouds = 0, amplitude = 0.5f;
  for (int octave = 0, freq = 8; octave < 5; ++octave, freq *= 2, amplitude *= 0.5f)
    clouds += amplitude *
              value_noise(u * static_cast<float>(freq), v * static_cast<float>(freq) * 0.5f, freq);
  float cover = std::clamp((clouds - 0.45f) / 0.2f, 0.0f, 1.0f) * std::min(1.0f, d.y * 6.0f);
  c = c * (1 - 0.8f * cover) + Color(1.6f) * (0.8f * cover);
  float cos_sun = d.x * sun.x + d.y * sun.y + d.z * sun.z;
  // A hazy sun 9 degrees across: as much power as a sharp one would have at radiance ~1000, but
  // seven times likelier to be hit by a path through the glass, so the caustics converge.
  if (cos_sun > std::cos(0.08f)) c += Color(130.0f, 118.0f, 100.0f);
  return c;
}

Image make_sky_map(int width, int height, Vec3f sun) {
  Image map(width, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      // Texel centres in the environment light's convention (render/environment_light.h).
      float u = (static_cast<float>(x) + 0.5f) / static_cast<float>(width);
      float v = (static_cast<float>(y) + 0.5f) / static_cast<float>(height);
      float phi = u * 2 * kPiF - kPiF, theta = v * kPiF;
      Vec3f d(std::sin(theta) * std::sin(phi), std::cos(theta), -std::sin(theta) * std::cos(phi));
      map.at(x, y) = sky_radiance(d, u, v, sun);
    }
  return map;
}

MeshData sphere(float radius, Vec3f centre) {
  MeshData m = make_icosphere(4);
  scale_translate(m, radius, centre);
  return m;
}

}  // namespace

// Every material type under a procedural HDR sky map: what exercises the environment
// techniques (importance sampling of a small bright sun, 16-byte texels, low-resolution sky),
// which the shared scenes, lit by constant skies, cannot.
Scene make_sky_scene() {
  Scene s;
  s.name = s.source = "sky";
  Vec3f sun = normalize(Vec3f(0.45f, 0.6f, -0.66f));
  s.environment.map = make_sky_map(1024, 512, sun);

  uint32_t m_ground = add_material(s, {.name = "ground", .base_color = Color(0.45f, 0.43f, 0.4f)});
  uint32_t m_gold = add_material(s, {.name = "brushed_gold",
                                     .type = MaterialType::kGlossy,
                                     .specular_color = Color(1.0f, 0.78f, 0.34f),
                                     .roughness_u = 0.08f,
                                     .roughness_v = 0.3f});
  uint32_t m_mirror = add_material(
      s, {.name = "mirror", .type = MaterialType::kMirror, .specular_color = Color(0.95f)});
  uint32_t m_glass = add_material(s, {.name = "glass", .type = MaterialType::kDielectric});
  uint32_t m_plastic = add_material(s, {.name = "blue_plastic",
                                        .type = MaterialType::kPrincipled,
                                        .base_color = Color(0.05f, 0.15f, 0.5f),
                                        .specular_color = Color(0.04f),
                                        .roughness_u = 0.15f,
                                        .roughness_v = 0.15f});
  uint32_t m_clay = add_material(s, {.name = "clay", .base_color = Color(0.7f, 0.35f, 0.25f)});

  const Vec3f x(1, 0, 0), y(0, 1, 0), z(0, 0, 1);
  add_mesh(s, "ground", make_quad(Vec3f(-30, 0, -30), x * 60.0f, z * 60.0f, y), m_ground);
  add_mesh(s, "gold_sphere", sphere(0.5f, Vec3f(-1.6f, 0.5f, 0.2f)), m_gold);
  add_mesh(s, "mirror_sphere", sphere(0.6f, Vec3f(-0.3f, 0.6f, -0.9f)), m_mirror);
  add_mesh(s, "glass_sphere", sphere(0.5f, Vec3f(0.7f, 0.5f, 0.4f)), m_glass);
  add_mesh(s, "plastic_sphere", sphere(0.45f, Vec3f(1.9f, 0.45f, -0.4f)), m_plastic);
  MeshData torus = make_torus(0.45f, 0.15f, 96, 32);
  rotate_x(torus, 70.0f, Vec3f(0));
  scale_translate(torus, 1.0f, Vec3f(-0.6f, 0.6f, 1.1f));
  add_mesh(s, "clay_torus", torus, m_clay);

  const Vec3f centre(0, 0.5f, 0);
  CameraDesc front = look_at("front", Vec3f(0.3f, 1.3f, 4.6f), Vec3f(0, 0.7f, 0), 45.0f);
  s.cameras.push_back(front);
  s.camera_paths.push_back(
      {"orbit",
       {front, look_at("side", Vec3f(4.5f, 0.9f, 0.5f), centre, 40.0f),
        look_at("high", Vec3f(0.5f, 6.0f, 2.0f), centre, 40.0f),
        look_at("close_glass", Vec3f(1.2f, 0.8f, 1.6f), Vec3f(0.7f, 0.5f, 0.4f), 50.0f),
        look_at("far", Vec3f(-12, 4, 14), centre, 20.0f)}});
  return s;
}

}  // namespace tuneray
