// The tuned BVH's packet traversal of coherent batches (bvh_packet.cpp) against its single-ray
// kernels: every ray must get the same hit bit for bit, so the wavefront image (camera rays as
// packets) stays the tile image (single rays). Each test runs with each copy of the stream
// kernels this CPU can run (AVX2; AVX-512 where there is one), chosen as a user would choose
// them, through TUNERAY_KERNEL_ISA.
#include <gtest/gtest.h>

#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "accel/kernel_isa.h"
#include "accel/tuned_bvh.h"
#include "batch_check.h"
#include "kernel_isa_cap.h"
#include "test_geometry.h"

namespace tuneray::test {
namespace {

using bvh::KernelIsa;

// Runs each test with TUNERAY_KERNEL_ISA set to its copy; trees built meanwhile select it.
class TunedPackets : public ::testing::TestWithParam<KernelIsa> {
 protected:
  void SetUp() override {
    if (GetParam() == KernelIsa::kAvx512 && !bvh::cpu_has_avx512())
      GTEST_SKIP() << "this CPU has no AVX-512";
    cap_.emplace(bvh::to_string(GetParam()));
    ASSERT_EQ(bvh::kernel_isa(), GetParam());
  }
  void TearDown() override { cap_.reset(); }

 private:
  std::optional<KernelIsaCap> cap_;
};

INSTANTIATE_TEST_SUITE_P(KernelIsas, TunedPackets,
                         ::testing::Values(KernelIsa::kAvx2, KernelIsa::kAvx512),
                         [](const ::testing::TestParamInfo<KernelIsa>& info) {
                           return std::string(bvh::to_string(info.param));
                         });

// A pinhole camera's rays in pixel order, from `eye` through a grid around the axis `forward`;
// the grid spans four direction octants, so the batch splits into several packet groups.
std::vector<Ray> camera_rays(Vec3f eye, Vec3f forward, int width, int height, float tfar = kInf,
                             float half_extent = 0.7f) {
  const Vec3f up = std::fabs(forward.y) < 0.9f ? Vec3f(0, 1, 0) : Vec3f(1, 0, 0);
  const Vec3f right = normalize(cross(forward, up));
  const Vec3f down = cross(forward, right);
  std::vector<Ray> rays;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const float sx = half_extent * (-1.0f + 2.0f * (x + 0.5f) / width);
      const float sy = half_extent * (-1.0f + 2.0f * (y + 0.5f) / height);
      rays.push_back(Ray{eye, 0, normalize(forward + right * sx + down * sy), tfar});
    }
  return rays;
}

// For each tree configuration: the coherent batch gets the single-ray hits, and it has both hits
// and misses (or the comparison means little).
template <class Configs>
void expect_streams_match_single_rays(const Mesh& mesh, const std::vector<Ray>& rays,
                                      const Configs& configs) {
  for (const char* text : configs) {
    SCOPED_TRACE(text);
    TunedBvhAccel tuned(parse_bvh_config(text));
    tuned.build(mesh.view());
    const size_t hits = expect_batch_hits_are_single_ray_hits(tuned, rays, RayCoherence::kCoherent);
    EXPECT_GT(hits, rays.size() / 4);
    EXPECT_LT(hits, rays.size());
  }
}

TEST_P(TunedPackets, CoherentBatchesFindTheSingleRayHitsBitForBit) {
  const Mesh mesh = make_soup(4000, 11, 0.08f);
  std::vector<Ray> rays = camera_rays(Vec3f(0.5f, 0.45f, -1.5f), Vec3f(0, 0, 1), 64, 48);
  // From inside the soup, looking back, with a finite range (rays that end before their hit).
  const std::vector<Ray> inside =
      camera_rays(Vec3f(0.52f, 0.5f, 0.6f), normalize(Vec3f(0.2f, -0.1f, -1)), 48, 40, 0.35f);
  rays.insert(rays.end(), inside.begin(), inside.end());
  expect_streams_match_single_rays(mesh, rays, kBatchKernelConfigs);
}

// The wavefront hands its rays over as planes: the tuned backend's hits from them are those of
// its batch calls on records, for every batch kernel and both coherences.
TEST_P(TunedPackets, PlanesFindTheRecordsHits) {
  const Mesh mesh = make_soup(4000, 11, 0.08f);
  const std::vector<Ray> rays = camera_rays(Vec3f(0.5f, 0.45f, -1.5f), Vec3f(0, 0, 1), 29, 23);
  for (const char* text : kBatchKernelConfigs) {
    SCOPED_TRACE(text);
    TunedBvhAccel tuned(parse_bvh_config(text));
    tuned.build(mesh.view());
    for (RayCoherence coherence : {RayCoherence::kCoherent, RayCoherence::kIncoherent})
      expect_plane_hits_are_batch_hits(tuned, rays, coherence);
  }
}

// A direction component of -0 puts a ray in the negative octant of its axis, and +0 in the
// positive one, whether the batch comes as records or as planes (whose octants are read from the
// planes' sign bits): axis-parallel rays in runs of +0 and -0 components (a run of each length
// kind: partial packets, full streams, longer runs) find the records' and the single rays' hits.
TEST_P(TunedPackets, SignedZeroDirectionsTakeTheirOctantFromPlanesAsFromRecords) {
  const Mesh mesh = make_soup(4000, 11, 0.08f);
  std::vector<Ray> rays;
  const int run_lengths[] = {16, 20, 64, 13, 70, 33, 17, 40};
  int k = 0;
  for (int b = 0; b < 8; ++b) {
    const float zx = (b & 1) ? -0.0f : 0.0f, zy = (b & 2) ? -0.0f : 0.0f;
    for (int i = 0; i < run_lengths[b]; ++i, ++k) {
      const Vec3f org(0.1f + 0.8f * static_cast<float>(k % 23) / 23.0f,
                      0.1f + 0.8f * static_cast<float>(k / 23) / 12.0f, -1.5f);
      rays.push_back(Ray{org, 0, Vec3f(zx, zy, 1.0f), kInf});
    }
  }
  for (const char* text : kBatchKernelConfigs) {
    SCOPED_TRACE(text);
    TunedBvhAccel tuned(parse_bvh_config(text));
    tuned.build(mesh.view());
    expect_plane_hits_are_batch_hits(tuned, rays, RayCoherence::kCoherent);
    const size_t hits = expect_batch_hits_are_single_ray_hits(tuned, rays, RayCoherence::kCoherent);
    EXPECT_GT(hits, rays.size() / 4);
  }
}

// Coherent batches are cut into runs of consecutive rays of one octant: runs of every length
// (single rays below 4, partial packets, full streams and runs longer than a stream) and octant
// changes at every position must leave each ray its single-ray hit.
TEST_P(TunedPackets, RunsOfEveryLengthFindTheSingleRayHits) {
  const Mesh mesh = make_soup(4000, 11, 0.08f);
  const std::vector<Ray> ahead = camera_rays(Vec3f(0.5f, 0.45f, -1.5f), Vec3f(0, 0, 1), 40, 30);
  const std::vector<Ray> back =
      camera_rays(Vec3f(0.5f, 0.45f, 2.5f), Vec3f(0, 0, -1), 40, 30, kInf, 0.3f);
  // Rays of the two views (opposite z signs, so every switch is an octant change) in runs of
  // 1, 2, 3, ..., 70 rays in turn.
  std::vector<Ray> rays;
  size_t a = 0, b = 0;
  for (int run = 1; a < ahead.size() || b < back.size(); run = run % 70 + 1) {
    const std::vector<Ray>& from = run % 2 ? ahead : back;
    size_t& at = run % 2 ? a : b;
    for (int k = 0; k < run && at < from.size(); ++k) rays.push_back(from[at++]);
  }
  expect_streams_match_single_rays(mesh, rays, kBatchKernelConfigs);
}

// A stream's frustum culls a node's children for all its rays at once; it must never cull a box
// one of them enters. Narrow views (rays of a stream nearly parallel, so the frustum is tight)
// onto a finely tessellated cube, whose triangles lie on the faces of their leaves' boxes: the
// rays at a frustum's edge enter boxes by a hair.
TEST_P(TunedPackets, TheStreamFrustumNeverCullsABoxARayEnters) {
  const Mesh cube = make_grid_box(48);
  std::vector<Ray> rays;
  const Vec3f eyes[] = {Vec3f(-1.3f, -1.1f, -1.7f), Vec3f(1.4f, 0.9f, -1.2f),
                        Vec3f(0.3f, 1.6f, 1.1f)};
  for (const Vec3f& eye : eyes) {
    // Aimed at points near the cube's edges and corners, where faces meet.
    for (const Vec3f target : {Vec3f(-0.5f, -0.5f, -0.45f), Vec3f(0.5f, 0.2f, -0.5f),
                               Vec3f(0.1f, 0.5f, 0.5f), Vec3f(0.02f, -0.03f, 0.01f)}) {
      const std::vector<Ray> view = camera_rays(eye, normalize(target - eye), 256, 12, kInf, 0.03f);
      rays.insert(rays.end(), view.begin(), view.end());
    }
  }
  const char* const configs[] = {"branching=8,sah_block_size=4,min_leaf=4,max_leaf=28",
                                 "branching=4,max_leaf=2", "branching=8,max_leaf=1",
                                 "branching=2,collapse=1"};
  expect_streams_match_single_rays(cube, rays, configs);
}

TEST_P(TunedPackets, EqualDistancesGoToTheLowerTriangleOnBothPaths) {
  // Every triangle twice (same vertices, consecutive indices): each hit is a tie, which both
  // paths must give to the lower (even) index whatever order they visit the leaves in.
  const Mesh soup = make_soup(1500, 5, 0.1f);
  Mesh twice;
  for (const Triangle& t : soup.triangles) {
    for (int copy = 0; copy < 2; ++copy)
      twice.add(soup.positions[t.v[0]], soup.positions[t.v[1]], soup.positions[t.v[2]]);
  }
  const std::vector<Ray> rays = camera_rays(Vec3f(0.4f, 0.55f, -1.2f), Vec3f(0, 0, 1), 64, 48);
  for (const char* text : {"branching=8,sah_block_size=4,min_leaf=4,max_leaf=28",
                           "branching=4,max_leaf=2", "branching=8,max_leaf=1"}) {
    SCOPED_TRACE(text);
    TunedBvhAccel tuned(parse_bvh_config(text));
    tuned.build(twice.view());
    EXPECT_GT(expect_batch_hits_are_single_ray_hits(tuned, rays, RayCoherence::kCoherent),
              rays.size() / 4);
    std::vector<Hit> hits(rays.size());
    tuned.intersect_batch(rays, hits, RayCoherence::kCoherent);
    for (const Hit& h : hits) {
      if (h.valid()) {
        EXPECT_EQ(h.prim % 2, 0u) << "prim " << h.prim;
      }
    }
  }
}

TEST_P(TunedPackets, ATieAtTheEntryOfASiblingLeafGoesToTheLowerTriangle) {
  // Pairs of axis-aligned triangles on the plane z = 0.5, one triangle a leaf: a small one and a
  // larger one around it (another box, so the build may put either first), the lower index
  // alternating between them from pair to pair. Rays along +z through the small one hit both at
  // exactly t = 0.5, which is also where they enter both (flat) leaf boxes. Whichever leaf a
  // node tests first, the other must still be tested, not culled as lying beyond the hit found,
  // so that the lower index wins on every path. Coordinates are multiples of 1/64 and the rays
  // pass off every edge: all products are exact and t is 0.5 to the bit.
  Mesh pairs;
  std::vector<uint32_t> lower;  // per pair, the index every ray through it must get
  const float step = 1.0f / 64.0f, z = 0.5f;
  const int cells = 10, spacing = 6;
  for (int j = 0; j < cells; ++j)
    for (int i = 0; i < cells; ++i) {
      const float x = static_cast<float>(spacing * i + 2) * step;
      const float y = static_cast<float>(spacing * j + 1) * step;
      auto at = [&](float u, float v) { return Vec3f(x + u * step, y + v * step, z); };
      const uint32_t first = static_cast<uint32_t>(pairs.triangles.size());
      if ((i + j) % 2 == 0) {
        pairs.add(at(0, 0), at(1, 0), at(0, 1));      // small
        pairs.add(at(-2, -1), at(2, -1), at(-2, 3));  // large, around it
      } else {
        pairs.add(at(-2, -1), at(2, -1), at(-2, 3));
        pairs.add(at(0, 0), at(1, 0), at(0, 1));
      }
      lower.push_back(first);
    }
  std::vector<Ray> rays;
  std::vector<uint32_t> expected;
  for (int j = 0; j < cells; ++j)
    for (int i = 0; i < cells; ++i)
      for (const float u : {0.125f, 0.375f, 0.625f})
        for (const float v : {0.125f, 0.25f}) {
          const float x = (static_cast<float>(spacing * i + 2) + u) * step;
          const float y = (static_cast<float>(spacing * j + 1) + v) * step;
          rays.push_back(Ray{Vec3f(x, y, 0.0f), 0, Vec3f(0, 0, 1), kInf});
          expected.push_back(lower[static_cast<size_t>(j * cells + i)]);
        }
  for (const char* text : {"branching=8,max_leaf=1", "branching=4,max_leaf=1,collapse=0"}) {
    SCOPED_TRACE(text);
    TunedBvhAccel tuned(parse_bvh_config(text));
    tuned.build(pairs.view());
    for (size_t r = 0; r < rays.size(); ++r) {
      Hit h;
      ASSERT_TRUE(tuned.intersect(rays[r], h)) << "ray " << r;
      EXPECT_EQ(h.t, 0.5f) << "ray " << r;
      EXPECT_EQ(h.prim, expected[r]) << "ray " << r;
    }
    EXPECT_EQ(expect_batch_hits_are_single_ray_hits(tuned, rays, RayCoherence::kCoherent),
              rays.size());
  }
}

TEST_P(TunedPackets, ARayWithANanDirectionLeadingItsPacketChangesNoOtherHit) {
  const Mesh mesh = make_soup(4000, 43, 0.08f);
  // A NaN x component has a clear sign bit, so the ray joins the camera rays going towards +x;
  // first in the batch, it leads their packet. It enters no box and hits nothing.
  std::vector<Ray> rays = {
      Ray{Vec3f(0.5f), 0, Vec3f(std::numeric_limits<float>::quiet_NaN(), 0.1f, 1), kInf}};
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) {
      const Vec3f d(0.01f + 0.02f * static_cast<float>(x), 0.01f + 0.02f * static_cast<float>(y),
                    1);
      rays.push_back(Ray{Vec3f(0.35f, 0.35f, -0.5f), 0, normalize(d), kInf});
    }
  TunedBvhAccel tuned(parse_bvh_config("branching=8,sah_block_size=4,min_leaf=4,max_leaf=28"));
  tuned.build(mesh.view());
  EXPECT_GT(expect_batch_hits_are_single_ray_hits(tuned, rays, RayCoherence::kCoherent), 20u);
}

}  // namespace
}  // namespace tuneray::test
