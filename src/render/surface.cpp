#include "render/surface.h"

#include <cmath>

#include "image/texture_lookup.h"

namespace tuneray {

SurfaceInteraction make_interaction(const Scene& scene, const Hit& hit) {
  SurfaceInteraction si;
  const Triangle& t = scene.triangles[hit.prim];
  Vec3f p0 = scene.positions[t.v[0]], p1 = scene.positions[t.v[1]], p2 = scene.positions[t.v[2]];
  float w0 = 1.0f - hit.u - hit.v;
  // Barycentric interpolation is more precise than org + t dir far from the origin.
  si.position = p0 * w0 + p1 * hit.u + p2 * hit.v;
  Vec3f ng = cross(p1 - p0, p2 - p0);
  float len = length(ng);
  si.geometric_normal = len > 0 ? ng / len : Vec3f(0, 0, 1);
  Vec3f ns =
      scene.normals[t.v[0]] * w0 + scene.normals[t.v[1]] * hit.u + scene.normals[t.v[2]] * hit.v;
  float ns_len = length(ns);
  ns = ns_len > 0 && std::isfinite(ns_len) ? ns / ns_len : si.geometric_normal;
  if (!scene.uvs.empty()) {
    si.uv = scene.uvs[t.v[0]] * w0 + scene.uvs[t.v[1]] * hit.u + scene.uvs[t.v[2]] * hit.v;
  }
  // The shading tangent follows dp/du when UVs exist (anisotropic roughness aligns with the
  // texture), else an arbitrary but continuous frame.
  Vec3f tangent = p1 - p0;
  si.shading = Frame::from_normal_tangent(ns, tangent);
  si.prim = hit.prim;
  si.material = &scene.materials[scene.material_ids[hit.prim]];
  return si;
}

BsdfParams untextured_bsdf(const Material& m) {
  BsdfParams p;
  p.type = m.type;
  p.base_color = m.base_color;
  p.specular_color = m.specular_color;
  p.transmittance = m.transmittance;
  p.alpha_x = m.roughness_u;
  p.alpha_y = m.roughness_v;
  p.ior = m.ior;
  return p;
}

Color texture_factor(const Scene& scene, const Material& m, Vec2f uv) {
  return sample_bilinear_wrap(scene.textures[m.base_texture].image, uv);
}

BsdfParams resolve_bsdf(const Scene& scene, const SurfaceInteraction& si) {
  const Material& m = *si.material;
  BsdfParams p = untextured_bsdf(m);
  if (m.base_texture != kNoTexture) p.base_color *= texture_factor(scene, m, si.uv);
  return p;
}

}  // namespace tuneray
