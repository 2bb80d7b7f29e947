// Path reuse (render/path_reuse.h): the pair geometry against hand-computed values, the pools,
// the balance-heuristic gather on hand-made pools, and renders with and without it.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <vector>

#include "render/path_reuse.h"
#include "render_helpers.h"
#include "scene/builtins.h"

namespace tuneray {
namespace {

// A first vertex at p1 on a floor facing +y, its second vertex at p2 on a ceiling facing -y.
ReuseVertices floor_to_ceiling(Vec3f p1, Vec3f p2) {
  ReuseVertices v;
  v.p1 = p1;
  v.n1 = v.ng1 = Vec3f(0, 1, 0);
  v.w1 = Color(0.5f, 0.25f, 1.0f);
  v.p2 = p2;
  v.ng2 = v.ns2 = Vec3f(0, -1, 0);
  v.technique = v.shared = true;
  return v;
}

TEST(PathReuse, GeometryIsCosinesOverSquaredDistance) {
  const ReuseVertices straight = floor_to_ceiling(Vec3f(0, 0, 0), Vec3f(0, 2, 0));
  EXPECT_FLOAT_EQ(reuse_geometry(straight, straight), 0.25f);  // 1 x 1 / 4
  // From (0,0,0) to (2,2,0): both cosines 1/sqrt(2), r^2 = 8.
  const ReuseVertices slanted = floor_to_ceiling(Vec3f(0, 0, 0), Vec3f(2, 2, 0));
  EXPECT_NEAR(reuse_geometry(straight, slanted), 0.5f / 8.0f, 1e-7f);
}

TEST(PathReuse, GeometryIsZeroWhereTheTechniqueCannotSampleOrTheWalkDoesNotApply) {
  const ReuseVertices from = floor_to_ceiling(Vec3f(0, 0, 0), Vec3f(0, 2, 0));
  ReuseVertices to = floor_to_ceiling(Vec3f(0, 0, 0), Vec3f(0, -2, 0));  // below x1's floor
  EXPECT_EQ(reuse_geometry(from, to), 0.0f);
  to = floor_to_ceiling(Vec3f(0, 0, 0), Vec3f(0, 2, 0));
  to.ng2 = to.ns2 = Vec3f(0, 1, 0);  // x1 behind the surface side that x2's walk shaded
  EXPECT_EQ(reuse_geometry(from, to), 0.0f);
  to = floor_to_ceiling(Vec3f(0, 0, 0), Vec3f(2, 2, 0));
  to.ns2 = normalize(Vec3f(1, -0.2f, 0));  // a shading normal for which x1 lies below
  EXPECT_EQ(reuse_geometry(from, to), 0.0f);
  ReuseVertices tilted = from;
  tilted.ng1 = Vec3f(1, 0, 0);  // the direction is above the shading but not the geometric normal
  EXPECT_EQ(reuse_geometry(tilted, floor_to_ceiling(Vec3f(0, 0, 0), Vec3f(-1, 2, 0))), 0.0f);
  EXPECT_EQ(reuse_geometry(from, floor_to_ceiling(Vec3f(0, 0, 0), Vec3f(0, 0, 0))), 0.0f);
  to = floor_to_ceiling(Vec3f(0, 0, 0), Vec3f(std::nanf(""), 2, 0));
  EXPECT_EQ(reuse_geometry(from, to), 0.0f);
}

TEST(PathReuse, PoolsTakeOneSampleOrdinalOfConsecutivePixels) {
  // Pixels a (2 samples), b (1), c (3), d (1), e (2); pools of two pixels.
  const std::vector<PixelSampleId> ids = {{0, 0, 0}, {0, 0, 1}, {1, 0, 0}, {2, 0, 0}, {2, 0, 1},
                                          {2, 0, 2}, {3, 0, 0}, {4, 0, 0}, {4, 0, 1}};
  std::vector<uint32_t> slots, begin;
  reuse_pools(ids, 2, slots, begin);
  // Group (a, b): {a0, b0}; a1 alone is no pool. Group (c, d): {c0, d0}; c1, c2 alone.
  // Group (e): e alone in each ordinal.
  EXPECT_EQ(slots, (std::vector<uint32_t>{0, 2, 3, 6}));
  EXPECT_EQ(begin, (std::vector<uint32_t>{0, 2, 4}));
  reuse_pools(ids, 8, slots, begin);
  EXPECT_EQ(slots, (std::vector<uint32_t>{0, 2, 3, 6, 7, 1, 4, 8}));
  EXPECT_EQ(begin, (std::vector<uint32_t>{0, 5, 8}));
  reuse_pools({}, 8, slots, begin);
  EXPECT_TRUE(slots.empty());
  EXPECT_EQ(begin, (std::vector<uint32_t>{0}));
}

// Occludes the rays `blocked` says.
class FakeAccel : public Accel {
 public:
  std::function<bool(const Ray&)> blocked = [](const Ray&) { return false; };
  std::string name() const override { return "fake"; }
  std::string describe() const override { return "fake"; }
  BuildStats build(const GeometryView&) override { return {}; }
  bool intersect(const Ray&, Hit&) const override { return false; }
  bool occluded(const Ray& ray) const override { return blocked(ray); }
};

TEST(PathReuse, TwoTechniquesAtOnePlaceShareEqually) {
  // Both first vertices at the origin: every second vertex is as likely from either, so each
  // path's estimate is the mean of the two walks' reflected radiance.
  std::vector<ReuseVertices> v = {floor_to_ceiling(Vec3f(0, 0, 0), Vec3f(0, 2, 0)),
                                  floor_to_ceiling(Vec3f(0, 0, 0), Vec3f(1, 2, 0))};
  v[0].l2 = Color(0.1f);
  v[1].l2 = Color(0.2f);
  const Color lr0(2, 4, 6), lr1(4, 8, 2);
  std::vector<Color> indirect = {v[0].l2 + v[0].w1 * lr0, v[1].l2 + v[1].w1 * lr1};
  const std::vector<uint32_t> slots = {0, 1}, begin = {0, 2};
  FakeAccel accel;
  PathReuseScratch scratch;
  std::vector<Color> out = indirect;
  EXPECT_EQ(reuse_paths(accel, slots, begin, v, out, scratch), 2u);
  for (int i = 0; i < 2; ++i)
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(out[i][c], v[i].l2[c] + v[i].w1[c] * 0.5f * (lr0[c] + lr1[c]), 1e-5f);

  // Blocked connections: each path keeps its own walk.
  accel.blocked = [](const Ray&) { return true; };
  out = indirect;
  reuse_paths(accel, slots, begin, v, out, scratch);
  for (int i = 0; i < 2; ++i)
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(out[i][c], indirect[i][c], 1e-6f);
}

TEST(PathReuse, WeightsFollowEachTechniquesDensity) {
  // Path 0's second vertex straight above it (geometry 1/4 from x1_0); x1_1 two units to the
  // side sees it at cosines 1/sqrt(2) and r^2 = 8 (geometry 1/16). Path 1's second vertex is
  // not shared (say glossy): path 1 keeps its own walk and gains its share of path 0's.
  std::vector<ReuseVertices> v = {floor_to_ceiling(Vec3f(0, 0, 0), Vec3f(0, 2, 0)),
                                  floor_to_ceiling(Vec3f(2, 0, 0), Vec3f(2, 2, 0))};
  v[1].shared = false;
  v[0].l2 = v[1].l2 = Color(0.0f);
  const Color lr0(8, 8, 8);
  std::vector<Color> out = {v[0].w1 * lr0, Color(3, 3, 3)};
  const std::vector<uint32_t> slots = {0, 1}, begin = {0, 2};
  FakeAccel accel;
  PathReuseScratch scratch;
  EXPECT_EQ(reuse_paths(accel, slots, begin, v, out, scratch), 1u);
  const float own = 0.25f, other = 1.0f / 16.0f, sum = own + other;
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(out[0][c], v[0].w1[c] * lr0[c] * own / sum, 1e-5f);
    EXPECT_NEAR(out[1][c], 3.0f + v[1].w1[c] * lr0[c] * other / sum, 1e-5f);
  }
}

TEST(PathReuse, InvalidWalksAndOtherPathsAreLeftAlone) {
  std::vector<ReuseVertices> v = {floor_to_ceiling(Vec3f(0, 0, 0), Vec3f(0, 2, 0)),
                                  floor_to_ceiling(Vec3f(0, 0, 0), Vec3f(1, 2, 0)),
                                  floor_to_ceiling(Vec3f(0, 0, 0), Vec3f(1, 2, 0))};
  v[2].technique = false;  // e.g. a mirror at its first hit
  const std::vector<Color> indirect = {Color(std::nanf(""), 1, 1), Color(1, 2, 3), Color(7, 8, 9)};
  std::vector<Color> out = indirect;
  const std::vector<uint32_t> slots = {0, 1, 2}, begin = {0, 3};
  FakeAccel accel;
  PathReuseScratch scratch;
  reuse_paths(accel, slots, begin, v, out, scratch);
  EXPECT_TRUE(std::isnan(out[0].x));  // its own (invalid) value, which finish() drops
  // Path 1 shares with no one but itself: its walk comes back whole.
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(out[1][c], indirect[1][c], 1e-6f);
  EXPECT_EQ(out[2], indirect[2]);
}

// A small image, eight bounces, the PCG sampler.
RenderSettings box_settings(int reuse) {
  RenderSettings s;
  s.width = 40;
  s.height = 30;
  s.max_bounces = 8;
  s.seed = 7;
  s.quality.path_reuse = reuse;
  s.quality.path_reuse_auto = false;  // in every pass, fixed counts too
  return s;
}

double mse_between(const Image& a, const Image& b) {
  double sum = 0;
  for (int y = 0; y < a.height(); ++y)
    for (int x = 0; x < a.width(); ++x) {
      const Color d = a.at(x, y) - b.at(x, y);
      sum += d.x * d.x + d.y * d.y + d.z * d.z;
    }
  return sum / (3.0 * a.width() * a.height());
}

TEST(PathReuse, RendersTheSameImageWithLessNoise) {
  const Scene scene = testing::point_lit_box();
  RenderSettings truth_settings = box_settings(0);
  truth_settings.seed = 99;
  const Image truth = testing::render_image(scene, truth_settings, 1024);
  const Image plain = testing::render_image(scene, box_settings(0), 32);
  const Image reused = testing::render_image(scene, box_settings(16), 32);
  const double plain_mse = mse_between(plain, truth), reused_mse = mse_between(reused, truth);
  EXPECT_LT(reused_mse, 0.5 * plain_mse) << plain_mse << " " << reused_mse;
  // Unbiased: with 8x the samples the error falls towards the truth's 8x lower, where a bias in
  // the pools' weights would leave an error that more samples do not remove. (Reuse moves
  // radiance between a pool's pixels, so the image mean alone could not tell.)
  const Image reused_more = testing::render_image(scene, box_settings(16), 256);
  EXPECT_LT(mse_between(reused_more, truth), 0.3 * reused_mse);
}

TEST(PathReuse, OffWhereItDoesNotApply) {
  // One bounce (no second vertex to share) or a pool of one: the image of reuse off, bit for bit.
  const Scene scene = make_cornell_scene();
  for (const auto& [bounces, pool] : {std::pair{1, 16}, std::pair{8, 1}}) {
    RenderSettings off = box_settings(0), on = box_settings(pool);
    off.max_bounces = on.max_bounces = bounces;
    const Image a = testing::render_image(scene, off, 4), b = testing::render_image(scene, on, 4);
    EXPECT_EQ(mse_between(a, b), 0.0) << bounces << " bounces, pool " << pool;
  }
}

TEST(PathReuse, TheImageDoesNotDependOnTheBatchSize) {
  // Chunks of whole pools: a wave size that does not divide into pools changes nothing.
  const Scene scene = make_cornell_scene();
  RenderSettings a = box_settings(8), b = box_settings(8);
  b.quality.batch_size = 100;
  EXPECT_EQ(mse_between(testing::render_image(scene, a, 2), testing::render_image(scene, b, 2)),
            0.0);
}

}  // namespace
}  // namespace tuneray
