// The equal-time comparison with Embree's pathtracer: its output transform, its option checks,
// reading the pathtracer's benchmark lines (through a stand-in script), what happens without
// it or when it fails, and a tiny real run when embree-tools is installed.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <random>

#include "bench/embree_peer.h"
#include "bench/peers_bench.h"
#include "common/temp_dir.h"

namespace tuneray {
namespace {

// A stand-in for the pathtracer: a shell script printing `output` and exiting with `status`.
std::string fake_pathtracer(const testing::TempDir& dir, const std::string& output, int status) {
  std::string path = dir.write_bytes(
      "pathtracer", "#!/bin/sh\nprintf '" + output + "'\nexit " + std::to_string(status) + "\n");
  chmod(path.c_str(), 0755);
  return path;
}

EmbreePeer fake_peer(const testing::TempDir& dir, const std::string& output, int status) {
  EmbreePeer peer;
  peer.binary = fake_pathtracer(dir, output, status);
  peer.scene = dir.write_bytes("scene.ecs", "");
  return peer;
}

TEST(EmbreePeer, OutputTransformClampsAndQuantisesLikeThePathtracer) {
  Image in(6, 1);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  in.at(0, 0) = Color(0.5f, 1.0f, 2.0f);
  in.at(1, 0) = Color(-1.0f, 0.999f, 0.0f);
  in.at(2, 0) = Color(nan, 0.002f, 0.0039f);
  Image out = embree_output_transform(in);
  EXPECT_FLOAT_EQ(out.at(0, 0).x, 127.0f / 255.0f);  // floor(127.505)
  EXPECT_FLOAT_EQ(out.at(0, 0).y, 1.0f);             // floor(255.01) = 255
  EXPECT_FLOAT_EQ(out.at(0, 0).z, 1.0f);             // clamped first
  EXPECT_FLOAT_EQ(out.at(1, 0).x, 0.0f);
  EXPECT_FLOAT_EQ(out.at(1, 0).y, 254.0f / 255.0f);  // floor(254.755)
  EXPECT_FLOAT_EQ(out.at(2, 0).x, 0.0f);             // NaN shows as black
  EXPECT_FLOAT_EQ(out.at(2, 0).y, 0.0f);             // floor(0.51)
  EXPECT_FLOAT_EQ(out.at(2, 0).z, 0.0f);             // floor(0.9945)
}

TEST(EmbreePeer, ReadsFrameTimeAndRaysFromTheBenchmarkLines) {
  testing::TempDir dir;
  EmbreePeer peer =
      fake_peer(dir,
                "BENCHMARK_RENDER_MIN 2.0\\nBENCHMARK_RENDER_AVG 2.5\\n"
                "BENCHMARK_RENDER_AVG_SIGMA 0.1\\nBENCHMARK_RENDER_MRAYPS_AVG 7.25\\n",
                0);
  EXPECT_EQ(embree_peer_missing(peer), "");
  EmbreePeerTiming t = embree_peer_benchmark(peer, 4, 2);
  EXPECT_DOUBLE_EQ(t.frame_ms, 400.0);
  EXPECT_DOUBLE_EQ(t.mrays, 7.25);
}

TEST(EmbreePeer, AFailedRunThrowsWithItsOutputAndWritesNothing) {
  testing::TempDir dir;
  EmbreePeer peer = fake_peer(dir, "cannot open display\\n", 3);
  try {
    embree_peer_benchmark(peer, 1, 1);
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("cannot open display"), std::string::npos) << e.what();
  }
  const std::string image = dir.file("out.pfm");
  EXPECT_THROW(embree_peer_render(peer, 1, image), std::runtime_error);
  EXPECT_FALSE(std::filesystem::exists(image));
  size_t files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir.file(""))) {
    (void)entry;
    ++files;
  }
  EXPECT_EQ(files, 2u);  // the script and the scene: no temporary left behind
  EXPECT_THROW(embree_peer_render(peer, 1, dir.file("out.png")), std::invalid_argument);
}

TEST(PeersBench, WithoutThePathtracerItSkipsAndSaysWhy) {
  testing::TempDir dir;
  PeersBenchOptions o;
  o.peer.binary = dir.file("no-such-pathtracer");
  o.truth_dir = dir.file("truth");
  PeersResult r = run_peers_bench(o);
  EXPECT_TRUE(r.skipped);
  EXPECT_NE(r.reason.find("no-such-pathtracer"), std::string::npos) << r.reason;
  EXPECT_NE(r.reason.find("embree-tools"), std::string::npos) << r.reason;
  EXPECT_FALSE(std::filesystem::exists(o.truth_dir));
}

TEST(PeersBench, RefusesOptionsThatMakeNoSense) {
  auto refused = [](auto change) {
    PeersBenchOptions o;
    change(o);
    return [o] { check_peers_options(o); };
  };
  EXPECT_NO_THROW(refused([](PeersBenchOptions&) {})());
  EXPECT_THROW(refused([](PeersBenchOptions& o) { o.times_s.clear(); })(), std::invalid_argument);
  EXPECT_THROW(refused([](PeersBenchOptions& o) { o.times_s = {1, -2}; })(), std::invalid_argument);
  EXPECT_THROW(refused([](PeersBenchOptions& o) { o.times_s = {std::nan("")}; })(),
               std::invalid_argument);
  EXPECT_THROW(refused([](PeersBenchOptions& o) { o.frame_ms = 0; })(), std::invalid_argument);
  EXPECT_THROW(refused([](PeersBenchOptions& o) { o.peer.width = 0; })(), std::invalid_argument);
  EXPECT_THROW(refused([](PeersBenchOptions& o) { o.reference_spp = 1; })(), std::invalid_argument);
  EXPECT_THROW(refused([](PeersBenchOptions& o) { o.accel = "octree"; })(), std::invalid_argument);
  EXPECT_THROW(refused([](PeersBenchOptions& o) {
                 o.accel = "tuned";
                 o.bvh = "branching=3";
               })(),
               std::invalid_argument);
  EXPECT_NO_THROW(refused([](PeersBenchOptions& o) {
    o.accel = "tuned";
    o.bvh = "int_cost=4";
  })());
  EXPECT_NO_THROW(refused([](PeersBenchOptions& o) { o.path_reuse = 0; })());
  EXPECT_THROW(refused([](PeersBenchOptions& o) { o.path_reuse = 1; })(), std::invalid_argument);
  EXPECT_THROW(refused([](PeersBenchOptions& o) { o.path_reuse = -4; })(), std::invalid_argument);
}

// The nesting correction against a simulation: pixels whose samples are unit Gaussians around
// zero, each frame the mean of the first n of its reference's N samples. The corrected error
// against the reference must match the error against the known truth (zero).
TEST(PeersBench, NestedFrameErrorIsCorrectedToTheErrorAgainstTheTruth) {
  const int n = 16, reference = 64, pixels = 20000;
  std::mt19937 rng(7);
  std::normal_distribution<double> sample;
  double against_reference = 0, against_truth = 0;
  for (int p = 0; p < pixels; ++p) {
    double first = 0, all = 0;
    for (int i = 0; i < reference; ++i) {
      double x = sample(rng);
      if (i < n) first += x;
      all += x;
    }
    double frame = first / n;
    against_reference += std::pow(frame - all / reference, 2);
    against_truth += frame * frame;
  }
  double measured = std::sqrt(against_reference / pixels);
  double truth = std::sqrt(against_truth / pixels);
  EXPECT_LT(measured, 0.9 * truth);  // uncorrected it reads sqrt(3/4) of the truth
  EXPECT_NEAR(peer_rmse_against_truth(measured, n, reference), truth, 0.02 * truth);
  EXPECT_DOUBLE_EQ(peer_rmse_against_truth(0.3, 1, 4), 0.3 / std::sqrt(0.75));
  EXPECT_THROW(peer_rmse_against_truth(0.3, 4, 4), std::invalid_argument);
}

TEST(PeersBench, CachedReferenceNameCoversSizePathLengthAndSpp) {
  PeersBenchOptions o;
  o.truth_dir = "d";
  EXPECT_EQ(embree_reference_path(o), "d/pathtracer-cornell_box-320x240-L8-4096spp.pfm");
  o.peer.max_path_length = 3;
  o.peer.width = 64;
  o.reference_spp = 16;
  EXPECT_EQ(embree_reference_path(o), "d/pathtracer-cornell_box-64x240-L3-16spp.pfm");
}

// A real, tiny run: both references are rendered and cached, the pathtracer's error falls with
// its samples, every row is filled (the denoised columns too), and a second run, without the
// denoiser, reads the cached references.
TEST(PeersBench, TinyRunAgainstTheRealPathtracer) {
  PeersBenchOptions o;
  if (!embree_peer_missing(o.peer).empty()) GTEST_SKIP() << embree_peer_missing(o.peer);
  testing::TempDir dir;
  o.peer.width = 32;
  o.peer.height = 24;
  o.reference_spp = 64;
  o.times_s = {0.005, 0.01};
  o.repeats = 1;
  o.timing_frames = 1;
  o.frame_ms = 1;
  o.truth_dir = dir.file("truth");
  PeersResult r = run_peers_bench(o);
  ASSERT_FALSE(r.skipped) << r.reason;
  ASSERT_TRUE(std::filesystem::exists(r.embree_reference));
  ASSERT_TRUE(std::filesystem::exists(r.ours_reference));
  // A 64-spp reference of a 32x24 image is visibly noisy; its halves say how much.
  EXPECT_GT(r.reference_noise_rmse, 0.001);
  EXPECT_GT(r.reference_noise_rmse_ldr, 0);
  ASSERT_GE(r.embree.size(), 2u);
  for (size_t i = 0; i < r.embree.size(); ++i) {
    EXPECT_EQ(r.embree[i].spp, 1 << i);
    EXPECT_LE(r.embree[i].spp, o.reference_spp / 2);  // a frame at 64 spp would be the reference
    EXPECT_GT(r.embree[i].frame_ms, 0);
  }
  EXPECT_LT(r.embree.back().rmse, r.embree.front().rmse);
  ASSERT_EQ(r.rows.size(), 2u);
  for (const PeersRow& row : r.rows) {
    EXPECT_TRUE(std::isfinite(row.ratio(row.raw)) && row.ratio(row.raw) > 0);
    // The reference's noise comes off every column, and only it: the exact relation.
    for (const OurError* e : {&row.raw, &row.denoised, &row.reused}) {
      EXPECT_LE(e->truth, e->measured);
      EXPECT_NEAR(
          e->truth * e->truth + r.reference_noise_rmse * r.reference_noise_rmse,
          std::max(e->measured * e->measured, r.reference_noise_rmse * r.reference_noise_rmse),
          1e-12);
    }
    EXPECT_TRUE(std::isfinite(row.ratio(row.ldr)) && row.ratio(row.ldr) > 0);
    EXPECT_TRUE(std::isfinite(row.ratio(row.denoised)) && row.ratio(row.denoised) > 0);
    EXPECT_TRUE(std::isfinite(row.ratio(row.denoised_ldr)) && row.ratio(row.denoised_ldr) > 0);
    EXPECT_TRUE(std::isfinite(row.ratio(row.reused_ldr)) && row.ratio(row.reused_ldr) > 0);
    EXPECT_GT(row.ours_spp, 0);
  }
  auto written = std::filesystem::last_write_time(r.embree_reference);
  o.denoise = false;
  o.path_reuse = 0;
  PeersResult again = run_peers_bench(o);
  EXPECT_EQ(again.rows.front().denoised.measured, 0.0);  // the columns were not run
  EXPECT_EQ(again.rows.front().reused.measured, 0.0);
  EXPECT_EQ(std::filesystem::last_write_time(again.embree_reference), written);
  EXPECT_EQ(again.embree.front().rmse, r.embree.front().rmse);  // same seeds, same image
}

}  // namespace
}  // namespace tuneray
