#include "scene/builtins.h"
#include "scene/mesh_data.h"

namespace tuneray {

namespace {

// White-furnace test scenes: a closed unit sphere lit only by a uniform environment of
// radiance 1, so an energy-conserving, non-absorbing BSDF renders as radiance 1 everywhere.
Scene make_furnace(const std::string& name, Material material) {
  Scene s;
  s.name = s.source = name;
  uint32_t m = add_material(s, std::move(material));
  add_mesh(s, "sphere", make_icosphere(5), m);
  s.environment.constant = Color(1.0f);
  CameraDesc front = look_at("front", Vec3f(0, 0, 4), Vec3f(0), 40.0f);
  s.cameras.push_back(front);
  s.camera_paths.push_back({"orbit",
                            {front, look_at("near", Vec3f(0, 0.5f, 1.8f), Vec3f(0), 60.0f),
                             look_at("side", Vec3f(4, 1, 0), Vec3f(0), 40.0f),
                             look_at("far", Vec3f(-6, 3, -6), Vec3f(0), 20.0f)}});
  return s;
}

}  // namespace

Scene make_furnace_scene() {
  return make_furnace("furnace", {.name = "diffuse", .base_color = Color(1.0f)});
}

Scene make_furnace_ggx_scene() {
  return make_furnace("furnace_ggx", {.name = "glossy",
                                      .type = MaterialType::kGlossy,
                                      .specular_color = Color(1.0f),
                                      .roughness_u = 0.5f,
                                      .roughness_v = 0.5f});
}

}  // namespace tuneray
