#include "bench/ray_sets.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <time.h>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>

#include "math/rng.h"

namespace tuneray {

namespace {

Vec3f triangle_normal(const Scene& s, uint32_t prim) {
  const Triangle& t = s.triangles[prim];
  Vec3f n =
      cross(s.positions[t.v[1]] - s.positions[t.v[0]], s.positions[t.v[2]] - s.positions[t.v[0]]);
  float len = length(n);
  return len > 0 ? n / len : Vec3f(0, 0, 1);
}

Vec3f cosine_direction(Vec3f n, Pcg32& rng) {
  float r = std::sqrt(rng.next_float()), phi = 2 * kPi * rng.next_float();
  Vec3f t = std::fabs(n.x) > 0.5f ? normalize(cross(n, Vec3f(0, 1, 0)))
                                  : normalize(cross(n, Vec3f(1, 0, 0)));
  Vec3f b = cross(n, t);
  float z = std::sqrt(std::max(0.0f, 1 - r * r));
  return normalize(t * (r * std::cos(phi)) + b * (r * std::sin(phi)) + n * z);
}

}  // namespace

std::vector<RaySet> make_ray_sets(const Scene& scene, const Accel& reference, size_t count) {
  const CameraDesc& cam = scene.cameras.front();
  const int width = std::max(8, static_cast<int>(std::sqrt(count * 16.0 / 9.0)) / 8 * 8);
  const int height = std::max(8, static_cast<int>(count / width) / 8 * 8);
  Vec3f forward = normalize(cam.target - cam.position);
  Vec3f right = normalize(cross(forward, cam.up));
  Vec3f up = cross(right, forward);
  float tan_half = std::tan(cam.vfov_deg * kPi / 360.0f);
  float aspect = float(width) / float(height);

  RaySet primary{"primary", false, {}}, bounce{"incoherent", false, {}}, shadow{"shadow", true, {}};
  Pcg32 rng(7);
  for (int ty = 0; ty < height; ty += 8) {
    for (int tx = 0; tx < width; tx += 8) {
      for (int y = ty; y < ty + 8; ++y) {
        for (int x = tx; x < tx + 8; ++x) {
          float px = (2 * (x + rng.next_float()) / width - 1) * tan_half * aspect;
          float py = (1 - 2 * (y + rng.next_float()) / height) * tan_half;
          primary.rays.push_back(
              {cam.position, 0, normalize(forward + right * px + up * py), kInf});
        }
      }
    }
  }
  std::vector<uint32_t> emissive;
  for (uint32_t i = 0; i < scene.triangles.size(); ++i) {
    uint32_t m = scene.material_ids.empty() ? 0 : scene.material_ids[i];
    if (m < scene.materials.size() && scene.materials[m].is_emissive()) emissive.push_back(i);
  }
  BBox box;
  for (const Vec3f& p : scene.positions) box.extend(p);
  const float eps = 1e-4f * box.diagonal();
  // Hits of the primary rays are the path vertices; cycle through them until each set is full.
  std::vector<std::pair<Vec3f, Vec3f>> vertices;  // position, normal facing the incoming ray
  for (const Ray& r : primary.rays) {
    Hit h;
    if (!reference.intersect(r, h)) continue;
    Vec3f n = triangle_normal(scene, h.prim);
    if (dot(n, r.dir) > 0) n = -n;
    vertices.push_back({r.org + r.dir * h.t, n});
  }
  if (vertices.empty()) vertices.push_back({box.center(), Vec3f(0, 1, 0)});
  for (size_t i = 0; i < count; ++i) {
    auto [p, n] = vertices[i % vertices.size()];
    bounce.rays.push_back({p + n * eps, 0, cosine_direction(n, rng), kInf});
    Vec3f light;
    if (!emissive.empty()) {
      const Triangle& t = scene.triangles[emissive[rng.next_u32() % emissive.size()]];
      float u = rng.next_float(), v = rng.next_float();
      if (u + v > 1) u = 1 - u, v = 1 - v;
      Vec3f a = scene.positions[t.v[0]];
      light = a + (scene.positions[t.v[1]] - a) * u + (scene.positions[t.v[2]] - a) * v;
    } else if (!scene.point_lights.empty()) {
      light = scene.point_lights[rng.next_u32() % scene.point_lights.size()].position;
    } else {
      light = box.center() + Vec3f(0, box.diagonal(), 0);
    }
    Vec3f d = light - p;
    float len = length(d);
    if (len <= 2 * eps) continue;
    shadow.rays.push_back({p + n * eps, 0, d / len, len - 2 * eps});
  }
  return {std::move(primary), std::move(bounce), std::move(shadow)};
}

namespace {

using Clock = std::chrono::steady_clock;

double cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + ts.tv_nsec * 1e-9;
}

}  // namespace

double trace_seconds(const Accel& accel, const RaySet& set, bool cpu_time) {
  std::atomic<size_t> sink{0};
  const double cpu_start = cpu_time ? cpu_seconds() : 0.0;
  auto start = Clock::now();
  tbb::parallel_for(tbb::blocked_range<size_t>(0, set.rays.size(), 1024),
                    [&](const tbb::blocked_range<size_t>& range) {
                      size_t hits = 0;
                      for (size_t i = range.begin(); i < range.end(); ++i) {
                        if (set.shadow) {
                          hits += accel.occluded(set.rays[i]);
                        } else {
                          Hit h;
                          hits += accel.intersect(set.rays[i], h);
                        }
                      }
                      sink += hits;
                    });
  double s = cpu_time ? cpu_seconds() - cpu_start
                      : std::chrono::duration<double>(Clock::now() - start).count();
  return sink.load() == size_t(-1) ? 0 : s;
}

}  // namespace tuneray
