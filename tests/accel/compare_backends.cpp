#include "compare_backends.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "math/rng.h"
#include "scene/scene.h"
#include "test_geometry.h"

namespace tuneray::test {

namespace {
Vec3f surface_point(const GeometryView& g, Pcg32& rng, Vec3f* normal) {
  const Triangle& t = g.triangles[rng.next_u32() % g.triangle_count];
  Vec3f a = g.positions[t.v[0]], b = g.positions[t.v[1]], c = g.positions[t.v[2]];
  float u = rng.next_float(), v = rng.next_float();
  if (u + v > 1) {
    u = 1 - u;
    v = 1 - v;
  }
  Vec3f n = cross(b - a, c - a);
  float len = length(n);
  *normal = len > 0 ? n / len : Vec3f(0, 0, 1);
  return a + (b - a) * u + (c - a) * v;
}

Vec3f triangle_normal(const GeometryView& g, uint32_t prim) {
  const Triangle& t = g.triangles[prim];
  Vec3f n =
      cross(g.positions[t.v[1]] - g.positions[t.v[0]], g.positions[t.v[2]] - g.positions[t.v[0]]);
  float len = length(n);
  return len > 0 ? n / len : Vec3f(0, 0, 1);
}

// Independent check in double precision: does the ray hit triangle h.prim at h.t, (h.u, h.v)?
bool hit_in_double(const GeometryView& g, const Hit& h, const Ray& r) {
  if (h.prim >= g.triangle_count) return false;
  const Triangle& t = g.triangles[h.prim];
  double p[3][3];
  for (int k = 0; k < 3; ++k) {
    for (int a = 0; a < 3; ++a) p[k][a] = g.positions[t.v[k]][a];
  }
  double w = 1.0 - h.u - h.v;
  for (int a = 0; a < 3; ++a) {
    double on_triangle = w * p[0][a] + h.u * p[1][a] + h.v * p[2][a];
    double on_ray = double(r.org[a]) + double(h.t) * r.dir[a];
    double scale = std::fabs(on_ray) + std::fabs(h.t) + 1e-6;
    if (std::fabs(on_triangle - on_ray) > 1e-4 * scale) return false;
  }
  return h.u >= -1e-4f && h.v >= -1e-4f && h.u + h.v <= 1 + 1e-4f;
}
}  // namespace

RaySets make_ray_sets(const GeometryView& g, size_t count, uint64_t seed) {
  RaySets out;
  Pcg32 rng(seed);
  BBox box;
  for (size_t i = 0; i < g.vertex_count; ++i) box.extend(g.positions[i]);
  const float diag = box.diagonal();
  BBox outer{box.lo - box.extent() * 0.5f, box.hi + box.extent() * 0.5f};
  for (size_t i = 0; i < count; ++i) {
    Ray r;
    if (i % 2 == 0) {
      // From around the scene towards a random point inside it (primary-like).
      r.org = random_point(rng, outer);
      r.dir = normalize(random_point(rng, box) - r.org);
    } else {
      // Random direction from a surface point (bounce-like).
      Vec3f n;
      Vec3f p = surface_point(g, rng, &n);
      Vec3f d = random_direction(rng);
      if (dot(d, n) < 0) n = -n;
      r.org = p + n * (1e-4f * diag);
      r.dir = d;
    }
    out.closest.push_back(r);
  }
  for (size_t i = 0; i < count; ++i) {
    Vec3f n0, n1;
    Vec3f p = surface_point(g, rng, &n0);
    Vec3f q = surface_point(g, rng, &n1);
    Vec3f d = q - p;
    float len = length(d);
    if (len <= 0) continue;
    Ray r;
    r.dir = d / len;
    // Skip segments that graze either end's surface: they run inside coplanar faces (walls of
    // a box), where two different triangle tests legitimately disagree.
    if (std::fabs(dot(r.dir, n0)) < 0.05f || std::fabs(dot(r.dir, n1)) < 0.05f) continue;
    r.org = p + r.dir * (1e-4f * diag);
    r.tfar = len * 0.999f - 1e-4f * diag;
    if (r.tfar <= 0) continue;
    out.shadow.push_back(r);
  }
  return out;
}

std::string Agreement::summary() const {
  return std::to_string(rays) + " rays, " + std::to_string(hits) + " hits: hit/miss mismatches " +
         std::to_string(hit_mismatch) + ", distance mismatches " + std::to_string(dist_mismatch) +
         ", primitive mismatches " + std::to_string(prim_mismatch) + ", shadow mismatches " +
         std::to_string(shadow_mismatch);
}

Agreement compare(const Accel& test, const Accel& reference, const RaySets& rays,
                  const GeometryView& g) {
  Agreement a;
  BBox box;
  for (size_t i = 0; i < g.vertex_count; ++i) box.extend(g.positions[i]);
  const float diag = box.diagonal();
  for (const Ray& r : rays.closest) {
    Hit h, ref;
    bool hit = test.intersect(r, h);
    bool ref_hit = reference.intersect(r, ref);
    a.rays++;
    if (hit != ref_hit) {
      a.hit_mismatch++;
      continue;
    }
    if (!hit) continue;
    a.hits++;
    // Relative 1e-5, except for hits closer than 1 % of the scene diagonal (rays leaving a
    // surface), where the rounding of the vertex coordinates dominates: there 1e-7 * diagonal.
    // At grazing incidence t is ill-conditioned (an error in the plane offset moves t by that
    // error / cos): the tolerance grows with 1 / |cos| of the angle to the reference triangle.
    float tolerance = 1e-5f * std::max(ref.t, 0.01f * diag / length(r.dir));
    tolerance /= std::max(0.01f, std::fabs(dot(triangle_normal(g, ref.prim), normalize(r.dir))));
    if (std::fabs(h.t - ref.t) > tolerance) {
      a.dist_mismatch++;
      if (std::getenv("ACCEL_DEBUG"))
        std::fprintf(stderr, "t %.9g ref %.9g prim %u ref %u\n", h.t, ref.t, h.prim, ref.prim);
      continue;
    }
    // Different triangles at the same distance are a tie (shared edge, overlapping faces) only
    // if the reported triangle really is hit there, with the reported barycentrics.
    if (h.prim != ref.prim && !hit_in_double(g, h, r)) a.prim_mismatch++;
  }
  for (const Ray& r : rays.shadow) {
    a.rays++;
    if (test.occluded(r) != reference.occluded(r)) a.shadow_mismatch++;
  }
  return a;
}

}  // namespace tuneray::test
