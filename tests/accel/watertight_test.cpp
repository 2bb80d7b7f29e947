// Rays aimed exactly at shared edges and vertices of closed meshes, from inside: with
// robust=1 none may pass through (leak). The fast test is measured too but not held to 0.
#include <gtest/gtest.h>

#include "accel/tuned_bvh.h"
#include "test_geometry.h"

namespace tuneray::test {
namespace {

// Targets: every vertex and points on every edge (midpoint and an uneven split).
std::vector<Vec3f> edge_and_vertex_targets(const Mesh& m) {
  std::vector<Vec3f> out(m.positions.begin(), m.positions.end());
  for (const Triangle& t : m.triangles) {
    for (int k = 0; k < 3; ++k) {
      Vec3f a = m.positions[t.v[k]], b = m.positions[t.v[(k + 1) % 3]];
      out.push_back(a + (b - a) * 0.5f);
      out.push_back(a + (b - a) * 0.3f);
    }
  }
  return out;
}

size_t count_leaks(const Accel& accel, const std::vector<Vec3f>& origins,
                   const std::vector<Vec3f>& targets) {
  size_t leaks = 0;
  for (const Vec3f& o : origins) {
    for (const Vec3f& target : targets) {
      Ray r;
      r.org = o;
      r.dir = target - o;  // not normalised: the ray passes exactly through the target at t = 1
      r.tfar = 4.0f;
      Hit h;
      if (!accel.intersect(r, h)) ++leaks;
      if (!accel.occluded(r)) ++leaks;
    }
  }
  return leaks;
}

void check_mesh(const Mesh& mesh, const std::vector<Vec3f>& origins, const char* name) {
  auto targets = edge_and_vertex_targets(mesh);
  for (const char* text :
       {"robust=1", "robust=1,branching=4", "robust=1,branching=8,compact=1",
        "robust=1,branching=8,quality=high", "robust=1,quality=low,branching=4,static=1"}) {
    TunedBvhAccel tuned(parse_bvh_config(text));
    tuned.build(mesh.view());
    EXPECT_EQ(count_leaks(tuned, origins, targets), 0u) << name << " with " << text;
  }
  TunedBvhAccel fast(parse_bvh_config("branching=8"));
  fast.build(mesh.view());
  std::cout << "[ info ] " << name << ": fast (non-robust) test leaks "
            << count_leaks(fast, origins, targets) << " of " << 2 * origins.size() * targets.size()
            << " queries\n";
}

TEST(Watertight, IcosphereFromInside) {
  Mesh m = make_icosphere(3, Vec3f(0.1f, -0.2f, 0.3f));
  check_mesh(m, {Vec3f(0.1f, -0.2f, 0.3f), Vec3f(0.3f, 0.1f, 0.2f), Vec3f(-0.2f, -0.5f, 0.4f)},
             "icosphere");
}

TEST(Watertight, GridBoxFromInside) {
  Mesh m = make_grid_box(8);
  check_mesh(m, {Vec3f(0), Vec3f(0.1f, 0.2f, -0.3f), Vec3f(0.25f, 0.25f, 0.25f)}, "grid box");
}

}  // namespace
}  // namespace tuneray::test
