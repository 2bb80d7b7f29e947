// quality=high: spatial splits duplicate references, yet every triangle is still found, and
// found once (a duplicated reference never yields a second, different answer).
#include <gtest/gtest.h>

#include <array>
#include <string>
#include <vector>

#include "accel/bvh_build.h"
#include "accel/tuned_bvh.h"
#include "test_geometry.h"

namespace tuneray::test {
namespace {

// Every triangle of `mesh` is hit by a ray along its normal through its centroid, with both
// queries, for each configuration.
void expect_every_triangle_found(const Mesh& mesh, const std::vector<const char*>& configs) {
  for (const char* text : configs) {
    TunedBvhAccel accel(parse_bvh_config(text));
    accel.build(mesh.view());
    if (accel.config().quality == BvhQuality::kHigh) {
      ASSERT_GT(accel.tree_stats().references, mesh.triangles.size()) << "no split: " << text;
    }
    size_t missing = 0;
    for (uint32_t i = 0; i < mesh.triangles.size(); ++i) {
      const Triangle& t = mesh.triangles[i];
      Vec3f a = mesh.positions[t.v[0]], b = mesh.positions[t.v[1]], c = mesh.positions[t.v[2]];
      Vec3f n = normalize(cross(b - a, c - a));
      Vec3f centroid = (a + b + c) / 3.0f;
      const float offset = 1e-4f * std::max(1.0f, length(centroid));
      Ray r{centroid + n * offset, 0, -n, 2 * offset};
      // Found: the closest hit is this triangle at t = offset, or another triangle crossing the
      // soup even closer (the soup's triangles intersect each other).
      Hit h;
      const float at = offset * (1.0f + 1e-2f);
      if (!accel.intersect(r, h) || (h.prim != i && h.t > at)) ++missing;
      if (!accel.occluded(r)) ++missing;
    }
    EXPECT_EQ(missing, 0u) << text;
  }
}

TEST(SpatialSplits, EveryTriangleIsFound) {
  expect_every_triangle_found(
      make_soup(10000, 31, 0.08f),
      {"quality=medium", "quality=high", "quality=high,branching=8,compact=1",
       "quality=high,branching=4,robust=1,max_leaf=1"});
}

// Far from the origin the crossing points round at a coarser grid: the split boxes must still
// contain the clipped triangle (a missed triangle here means the padding is too small).
TEST(SpatialSplits, EveryTriangleIsFoundFarFromTheOrigin) {
  Mesh mesh = make_soup(10000, 32, 0.08f);
  for (Vec3f& p : mesh.positions) p = p * 50.0f + Vec3f(3000.0f, -7000.0f, 1500.0f);
  expect_every_triangle_found(mesh, {"quality=high", "quality=high,branching=8,max_leaf=1"});
}

// split_bounds against the exact clipping (in double): both halves contain every vertex of the
// exact part of the triangle on their side (conservative), and exceed its bounds by no more
// than the padding (tight). Also for fragments: the left half of a first split split again.
using Poly = std::vector<std::array<double, 3>>;

// The part of `poly` with coordinate `dim` <= pos (keep_below) or >= pos, exactly in double
// (the crossing points are the exact ones up to double rounding, ~1e-16 relative).
Poly clip(const Poly& poly, int dim, double pos, bool keep_below) {
  Poly out;
  auto inside = [&](const std::array<double, 3>& p) {
    return keep_below ? p[dim] <= pos : p[dim] >= pos;
  };
  for (size_t i = 0; i < poly.size(); ++i) {
    const auto& p = poly[i];
    const auto& q = poly[(i + 1) % poly.size()];
    if (inside(p)) out.push_back(p);
    if ((p[dim] < pos && q[dim] > pos) || (p[dim] > pos && q[dim] < pos)) {
      double t = (pos - p[dim]) / (q[dim] - p[dim]);
      std::array<double, 3> x;
      for (int a = 0; a < 3; ++a) x[a] = p[a] + (q[a] - p[a]) * t;
      x[dim] = pos;
      out.push_back(x);
    }
  }
  return out;
}

// Counts vertices of `exact` outside `box`, and box faces farther from them than a few times the
// padding (which grows with the triangle's coordinates and extent, `scale` per axis).
void check_box(const Poly& exact, const RTCBounds& box, const std::array<double, 3>& scale,
               size_t& outside, size_t& loose) {
  const float lo[3] = {box.lower_x, box.lower_y, box.lower_z};
  const float hi[3] = {box.upper_x, box.upper_y, box.upper_z};
  for (int a = 0; a < 3; ++a) {
    double e_lo = 1e300, e_hi = -1e300;
    for (const auto& p : exact) {
      if (p[a] < lo[a] || p[a] > hi[a]) ++outside;
      e_lo = std::min(e_lo, p[a]);
      e_hi = std::max(e_hi, p[a]);
    }
    const double slack = 2e-6 * scale[a];
    if (e_lo - lo[a] > slack || hi[a] - e_hi > slack) ++loose;
  }
}

TEST(SpatialSplits, SplitBoundsAreConservativeAndTight) {
  Pcg32 rng(77);
  size_t outside = 0, loose = 0, checked = 0;
  for (int n = 0; n < 20000; ++n) {
    const float scale = std::pow(10.0f, -2.0f + 6.0f * rng.next_float());  // 0.01 .. 10^4
    const Vec3f offset = random_direction(rng) * scale * 10.0f * rng.next_float();
    bvh::SplitTriangle tri{};
    Poly poly;
    RTCBuildPrimitive prim{};
    prim.lower_x = prim.lower_y = prim.lower_z = kInf;
    prim.upper_x = prim.upper_y = prim.upper_z = -kInf;
    for (int k = 0; k < 3; ++k) {
      Vec3f p = offset + random_direction(rng) * scale * rng.next_float();
      for (int a = 0; a < 3; ++a) tri.v[k][a] = p[a];
      poly.push_back({p.x, p.y, p.z});
      prim.lower_x = std::min(prim.lower_x, p.x);
      prim.lower_y = std::min(prim.lower_y, p.y);
      prim.lower_z = std::min(prim.lower_z, p.z);
      prim.upper_x = std::max(prim.upper_x, p.x);
      prim.upper_y = std::max(prim.upper_y, p.y);
      prim.upper_z = std::max(prim.upper_z, p.z);
    }
    std::array<double, 3> scale_of{};  // max |coordinate| + extent, per axis
    for (int a = 0; a < 3; ++a) {
      const float* lo = &prim.lower_x;
      const float* hi = &prim.upper_x;
      scale_of[a] = std::max(std::fabs(lo[a]), std::fabs(hi[a])) + (hi[a] - lo[a]);
    }
    // A plane through the box (so the triangle is cut), then a second one through the left half.
    auto plane = [&](const RTCBuildPrimitive& box, int dim) {
      const float* lo = &box.lower_x;
      const float* hi = &box.upper_x;
      return lo[dim] + (hi[dim] - lo[dim]) * (0.05f + 0.9f * rng.next_float());
    };
    const int dim1 = static_cast<int>(rng.next_u32() % 3);
    const float pos1 = plane(prim, dim1);
    RTCBounds left{}, right{};
    bvh::split_bounds(tri, prim, dim1, pos1, left, right);
    const Poly exact_left = clip(poly, dim1, pos1, true);
    const Poly exact_right = clip(poly, dim1, pos1, false);
    check_box(exact_left, left, scale_of, outside, loose);
    check_box(exact_right, right, scale_of, outside, loose);

    RTCBuildPrimitive fragment = prim;
    std::copy_n(&left.lower_x, 3, &fragment.lower_x);
    std::copy_n(&left.upper_x, 3, &fragment.upper_x);
    const int dim2 = static_cast<int>(rng.next_u32() % 3);
    if (!(fragment.upper_x >= fragment.lower_x)) continue;
    const float pos2 = plane(fragment, dim2);
    RTCBounds left2{}, right2{};
    bvh::split_bounds(tri, fragment, dim2, pos2, left2, right2);
    const Poly l2 = clip(exact_left, dim2, pos2, true), r2 = clip(exact_left, dim2, pos2, false);
    size_t ignored_loose = 0;  // a fragment's box may be looser than the exact part (by design)
    check_box(l2, left2, scale_of, outside, ignored_loose);
    check_box(r2, right2, scale_of, outside, ignored_loose);
    ++checked;
  }
  EXPECT_GT(checked, 19000u);
  EXPECT_EQ(outside, 0u);
  EXPECT_EQ(loose, 0u);
}

bvh::BuildResult build_result(const Mesh& mesh, const std::string& text, bvh::Tree& tree) {
  bvh::PrimitiveCache cache;
  return bvh::build_tree(mesh.view(), parse_bvh_config(text), *EmbreeDevice::shared(), cache, tree);
}

// The split count is what the splits added: references beyond one per triangle (not the
// number of splitPrimitive calls, which Embree also makes to evaluate splits it then rejects).
TEST(SpatialSplits, SplitCountIsTheAddedReferences) {
  Mesh mesh = make_soup(10000, 31, 0.08f);
  for (const char* text : {"quality=high", "quality=high,branching=8,max_leaf=4"}) {
    bvh::Tree tree;
    bvh::BuildResult r = build_result(mesh, text, tree);
    const size_t in_leaves = bvh::measure_tree(tree, 1, 1).references;
    EXPECT_EQ(r.references, in_leaves) << text;
    EXPECT_GT(r.spatial_splits, 0u) << text;
    EXPECT_EQ(r.spatial_splits, in_leaves - mesh.triangles.size()) << text;
    EXPECT_EQ(r.notes, "") << text;

    TunedBvhAccel accel(parse_bvh_config(text));
    BuildStats stats = accel.build(mesh.view());
    EXPECT_NE(stats.notes.find("spatial splits: " + std::to_string(r.spatial_splits) +
                               ", references " + std::to_string(r.references)),
              std::string::npos)
        << stats.notes;
  }
}

// A sphere and a box of quads: Embree evaluates spatial splits there (tens of thousands of
// splitPrimitive calls) but keeps none, as cutting never pays on a closed surface of even
// triangles. The build must then say it fell back to medium (it used to count the calls and
// report them as splits).
TEST(SpatialSplits, NoKeptSplitNotesTheFallBack) {
  for (const Mesh& mesh : {make_icosphere(3), make_grid_box(10)}) {
    bvh::Tree tree;
    bvh::BuildResult r = build_result(mesh, "quality=high", tree);
    EXPECT_EQ(r.references, mesh.triangles.size());
    EXPECT_EQ(r.spatial_splits, 0u);
    EXPECT_NE(r.notes.find("fell back to medium"), std::string::npos) << r.notes;

    TunedBvhAccel accel(parse_bvh_config("quality=high"));
    const std::string notes = accel.build(mesh.view()).notes;
    EXPECT_NE(notes.find("fell back to medium"), std::string::npos) << notes;
    EXPECT_NE(notes.find("spatial splits: 0,"), std::string::npos) << notes;
    TunedBvhAccel medium(parse_bvh_config("quality=medium"));
    EXPECT_EQ(medium.build(mesh.view()).notes.find("fell back"), std::string::npos);
  }
}

}  // namespace
}  // namespace tuneray::test
