// Procedural geometry and ray sets for the accel tests (generated in the test, no files).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "accel/accel.h"
#include "math/bbox.h"
#include "math/ray.h"
#include "math/rng.h"
#include "scene/scene.h"

namespace tuneray::test {

struct Mesh {
  std::vector<Vec3f> positions;
  std::vector<Triangle> triangles;
  GeometryView view() const {
    return {positions.data(), positions.size(), triangles.data(), triangles.size()};
  }
  BBox bounds() const {
    BBox b;
    for (const Vec3f& p : positions) b.extend(p);
    return b;
  }
  void add(Vec3f a, Vec3f b, Vec3f c) {
    uint32_t base = static_cast<uint32_t>(positions.size());
    positions.insert(positions.end(), {a, b, c});
    triangles.push_back({{base, base + 1, base + 2}});
  }
};

inline Vec3f random_point(Pcg32& rng, const BBox& box) {
  Vec3f e = box.extent();
  return box.lo + Vec3f(rng.next_float() * e.x, rng.next_float() * e.y, rng.next_float() * e.z);
}

inline Vec3f random_direction(Pcg32& rng) {
  float z = 1.0f - 2.0f * rng.next_float();
  float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  float phi = 2.0f * kPi * rng.next_float();
  return {r * std::cos(phi), r * std::sin(phi), z};
}

// `count` small random triangles in the unit cube plus a few long diagonal slivers (the
// slivers make spatial splits worthwhile).
inline Mesh make_soup(size_t count, uint64_t seed, float size = 0.04f) {
  Mesh m;
  Pcg32 rng(seed);
  BBox unit{Vec3f(0), Vec3f(1)};
  for (size_t i = 0; i < count; ++i) {
    Vec3f c = random_point(rng, unit);
    m.add(c + random_direction(rng) * size, c + random_direction(rng) * size,
          c + random_direction(rng) * size);
  }
  for (int i = 0; i < 16; ++i) {
    Vec3f a = random_point(rng, unit), b = random_point(rng, unit);
    m.add(a, b, a + random_direction(rng) * 0.02f);
  }
  return m;
}

// Closed mesh: icosahedron subdivided `levels` times, vertices shared (indexed), on the unit
// sphere around `center`.
Mesh make_icosphere(int levels, Vec3f center = Vec3f(0));

// A closed box of `n` x `n` quads per face (shared vertices): axis-aligned edges stress the
// watertight test on ties.
Mesh make_grid_box(int n);

}  // namespace tuneray::test
