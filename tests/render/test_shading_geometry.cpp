// ShadingGeometry precomputes per triangle what make_interaction derives at every hit; both must
// describe the same surface.
#include <gtest/gtest.h>

#include <array>
#include <utility>
#include <vector>

#include "render/shading_geometry.h"
#include "render/surface.h"
#include "scene/scene.h"

namespace tuneray {
namespace {

// One triangle per case, each with its own three vertices and normals.
Scene triangles_with_normals(const std::vector<std::array<Vec3f, 6>>& cases) {
  Scene s;
  s.materials.resize(2);
  for (const auto& c : cases) {
    const uint32_t base = static_cast<uint32_t>(s.positions.size());
    for (int k = 0; k < 3; ++k) {
      s.positions.push_back(c[k]);
      s.normals.push_back(c[3 + k]);
      s.uvs.push_back({0.25f * static_cast<float>(k), 0.5f});
    }
    s.triangles.push_back({{base, base + 1, base + 2}});
    s.material_ids.push_back(static_cast<uint32_t>(s.material_ids.size() % 2));
  }
  return s;
}

void expect_near(Vec3f a, Vec3f b, float tolerance) {
  EXPECT_NEAR(a.x, b.x, tolerance);
  EXPECT_NEAR(a.y, b.y, tolerance);
  EXPECT_NEAR(a.z, b.z, tolerance);
}

// The compiler may fuse multiply-adds differently where each is inlined, so "the same" means
// equal up to a few float roundings.
constexpr float kRounding = 2e-6f;

const Vec3f kP0{0.1f, 0.2f, 0.3f}, kP1{1.3f, 0.1f, -0.2f}, kP2{0.4f, 1.7f, 0.6f};

TEST(ShadingGeometry, SmoothTrianglesGiveMakeInteractionsSurface) {
  const Vec3f n0 = normalize(Vec3f(0.1f, 0.2f, 1.0f)), n1 = normalize(Vec3f(-0.3f, 0.1f, 1.0f)),
              n2 = normalize(Vec3f(0.2f, -0.4f, 1.0f));
  // Equal but unnormalised normals are not "flat": make_interaction normalises them.
  const Vec3f long_normal(0.0f, 0.0f, 3.0f);
  Scene s = triangles_with_normals(
      {{kP0, kP1, kP2, n0, n1, n2}, {kP0, kP2, kP1, long_normal, long_normal, long_normal}});
  ShadingGeometry geometry(s);
  for (uint32_t prim = 0; prim < 2; ++prim) {
    EXPECT_EQ(geometry.triangle(prim).flat, 0u);
    for (const auto& [u, v] : {std::pair{0.2f, 0.3f}, {0.0f, 0.0f}, {0.7f, 0.29f}}) {
      const Hit hit{1.0f, prim, u, v};
      const SurfaceInteraction a = geometry.interaction(hit), b = make_interaction(s, hit);
      expect_near(a.position, b.position, kRounding);
      expect_near(a.geometric_normal, b.geometric_normal, kRounding);
      expect_near(a.shading.n, b.shading.n, kRounding);
      expect_near(a.shading.s, b.shading.s, kRounding);
      expect_near(a.shading.t, b.shading.t, kRounding);
      EXPECT_NEAR(a.uv.x, b.uv.x, kRounding);
      EXPECT_NEAR(a.uv.y, b.uv.y, kRounding);
      EXPECT_EQ(a.prim, prim);
      EXPECT_EQ(a.material, b.material);
      EXPECT_EQ(a.material, &s.materials[prim % 2]);
    }
  }
}

TEST(ShadingGeometry, FlatTrianglesTakeTheirFrameFromTheCommonNormal) {
  const Vec3f ng = normalize(cross(kP1 - kP0, kP2 - kP0));
  const Vec3f tilted = normalize(ng + Vec3f(0.2f, 0.0f, 0.0f));  // a faceted mesh's own normal
  Scene s = triangles_with_normals(
      {{kP0, kP1, kP2, ng, ng, ng}, {kP0, kP1, kP2, tilted, tilted, tilted}});
  ShadingGeometry geometry(s);
  for (uint32_t prim = 0; prim < 2; ++prim) {
    const Vec3f n = prim == 0 ? ng : tilted;
    EXPECT_EQ(geometry.triangle(prim).flat, 1u);
    const Frame expected = Frame::from_normal_tangent(n, kP1 - kP0);
    const Hit hit{1.0f, prim, 0.31f, 0.42f};
    const SurfaceInteraction a = geometry.interaction(hit), b = make_interaction(s, hit);
    expect_near(a.shading.n, expected.n, kRounding);
    expect_near(a.shading.s, expected.s, kRounding);
    expect_near(a.shading.t, expected.t, kRounding);
    EXPECT_NEAR(dot(a.shading.s, a.shading.n), 0.0f, 1e-6f);
    // make_interaction normalises the blend of three equal normals instead.
    expect_near(a.shading.n, b.shading.n, kRounding);
    expect_near(a.shading.s, b.shading.s, kRounding);
    expect_near(a.shading.t, b.shading.t, kRounding);
    expect_near(a.position, b.position, kRounding);
    expect_near(a.geometric_normal, b.geometric_normal, kRounding);
  }
}

TEST(ShadingGeometry, DegenerateTrianglesKeepTheFallbackNormal) {
  const Vec3f up(0, 1, 0);
  Scene s = triangles_with_normals({{Vec3f(0, 0, 0), Vec3f(1, 0, 0), Vec3f(2, 0, 0), up, up, up}});
  ShadingGeometry geometry(s);
  const Hit hit{1.0f, 0, 0.25f, 0.25f};
  EXPECT_EQ(geometry.interaction(hit).geometric_normal, Vec3f(0, 0, 1));
  EXPECT_EQ(make_interaction(s, hit).geometric_normal, Vec3f(0, 0, 1));
}

}  // namespace
}  // namespace tuneray
