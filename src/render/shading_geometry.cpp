#include "render/shading_geometry.h"

#include <cmath>

namespace tuneray {

namespace {

bool same_bits(Vec3f a, Vec3f b) {
  return a.x == b.x && a.y == b.y && a.z == b.z;
}

}  // namespace

ShadingGeometry::ShadingGeometry(const Scene& scene) : scene_(scene) {
  triangles_.resize(scene.triangles.size());
  for (size_t i = 0; i < scene.triangles.size(); ++i) {
    const Triangle& t = scene.triangles[i];
    const Vec3f p0 = scene.positions[t.v[0]], p1 = scene.positions[t.v[1]],
                p2 = scene.positions[t.v[2]];
    TriangleShading& ts = triangles_[i];
    const Vec3f ng = cross(p1 - p0, p2 - p0);
    const float len = length(ng);
    ts.geometric_normal = len > 0 ? ng / len : Vec3f(0, 0, 1);
    ts.material = scene.material_ids[i];
    const Vec3f n0 = scene.normals[t.v[0]];
    const float n0_len = length(n0);
    // A flat triangle's frame only holds if its normal is unit already; anything else (zero,
    // unnormalised or non-finite normals) takes make_interaction's general path.
    if (same_bits(n0, scene.normals[t.v[1]]) && same_bits(n0, scene.normals[t.v[2]]) &&
        std::abs(n0_len - 1.0f) < 1e-5f) {
      const Frame frame = Frame::from_normal_tangent(n0, p1 - p0);
      ts.flat = 1;
      ts.normal = frame.n;
      ts.tangent = frame.s;
    }
  }
}

SurfaceInteraction ShadingGeometry::interaction(const Hit& hit) const {
  const TriangleShading& ts = triangles_[hit.prim];
  const Triangle& t = scene_.triangles[hit.prim];
  SurfaceInteraction si;
  const Vec3f p0 = scene_.positions[t.v[0]], p1 = scene_.positions[t.v[1]],
              p2 = scene_.positions[t.v[2]];
  const float w0 = 1.0f - hit.u - hit.v;
  si.position = p0 * w0 + p1 * hit.u + p2 * hit.v;
  si.geometric_normal = ts.geometric_normal;
  if (!scene_.uvs.empty())
    si.uv = scene_.uvs[t.v[0]] * w0 + scene_.uvs[t.v[1]] * hit.u + scene_.uvs[t.v[2]] * hit.v;
  if (ts.flat) {
    si.shading = Frame(ts.tangent, cross(ts.normal, ts.tangent), ts.normal);
  } else {
    Vec3f ns = scene_.normals[t.v[0]] * w0 + scene_.normals[t.v[1]] * hit.u +
               scene_.normals[t.v[2]] * hit.v;
    const float ns_len = length(ns);
    ns = ns_len > 0 && std::isfinite(ns_len) ? ns / ns_len : ts.geometric_normal;
    si.shading = Frame::from_normal_tangent(ns, p1 - p0);
  }
  si.prim = hit.prim;
  si.material = &scene_.materials[ts.material];
  return si;
}

}  // namespace tuneray
