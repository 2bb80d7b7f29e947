// The command line on good and bad input: bad input gives a clear message naming the file or
// value, a non-zero exit code, and never a crash (a signal).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>

#include "command_test.h"
#include "run_command.h"

namespace tuneray {
namespace {

using testing::CommandResult;
using testing::run_tuneray;

class Cli : public testing::CommandTest {};

void expect_clean_failure(const CommandResult& r, const std::string& must_mention) {
  EXPECT_FALSE(r.signaled) << "killed by signal " << r.signal << "\n" << r.output;
  EXPECT_NE(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find(must_mention), std::string::npos)
      << "message does not mention '" << must_mention << "':\n"
      << r.output;
}

TEST_F(Cli, RendersTheDefaultSceneAndWritesEveryRequestedFormat) {
  std::string png = path("c.png"), exr = path("c.exr"), pfm = path("c.pfm"),
              report = path("r.json");
  CommandResult r = run_tuneray({"render", "cornell", "--spp", "2", "--size", "32x24", "--out", png,
                                 "--out", exr, "--out", pfm, "--report", report, "--quiet"});
  ASSERT_FALSE(r.signaled) << r.output;
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const auto& f : {png, exr, pfm, report}) EXPECT_GT(std::filesystem::file_size(f), 0u) << f;
}

TEST_F(Cli, MissingSceneFileIsNamed) {
  expect_clean_failure(run_tuneray({"render", path("nope.obj"), "--quiet"}), "nope.obj");
}

TEST_F(Cli, MalformedObjIsNamed) {
  std::string obj = write("bad.obj", "v 0 0 0\nv 1 0 0\nf 1 2 7\n");
  expect_clean_failure(run_tuneray({"info", obj}), "bad.obj");
}

TEST_F(Cli, NanVertexIsNamed) {
  std::string obj = write("nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n");
  expect_clean_failure(run_tuneray({"info", obj}), "nan.obj");
}

TEST_F(Cli, EmptyFileIsNamed) {
  std::string obj = write("empty.obj", "");
  expect_clean_failure(run_tuneray({"info", obj}), "empty.obj");
}

TEST_F(Cli, UnknownExtensionIsNamed) {
  std::string f = write("scene.xyz", "hello");
  expect_clean_failure(run_tuneray({"info", f}), "scene.xyz");
}

TEST_F(Cli, BadJsonIsNamed) {
  std::string f = write("scene.json", "{ \"mesh\": ");
  expect_clean_failure(run_tuneray({"info", f}), "scene.json");
}

TEST_F(Cli, BadOptionValuesAreRejected) {
  expect_clean_failure(run_tuneray({"render", "cornell", "--size", "12by7"}), "12by7");
  expect_clean_failure(run_tuneray({"render", "cornell", "--spp", "-3"}), "spp");
  expect_clean_failure(run_tuneray({"render", "cornell", "--accel", "octree"}), "octree");
  expect_clean_failure(run_tuneray({"render", "cornell", "--camera", "99", "--quiet"}), "camera");
  expect_clean_failure(run_tuneray({"render", "cornell", "--bvh", "quality"}), "quality");
  expect_clean_failure(run_tuneray({"render", "cornell", "--out", path("x.bmp"), "--spp", "1",
                                    "--size", "8x8", "--quiet"}),
                       "x.bmp");
}

TEST_F(Cli, FrameBudgetRenderReportsEveryFrame) {
  std::string exr = path("f.exr"), report = path("f.json");
  CommandResult r = run_tuneray({"render", "cornell", "--size", "16x12", "--frame-ms", "5",
                                 "--frames", "3", "--scheduler", "tile", "--clamp", "4",
                                 "--adaptive", "--out", exr, "--report", report, "--quiet"});
  ASSERT_FALSE(r.signaled) << r.output;
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::ifstream f(report);
  std::string text((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("\"frames\""), std::string::npos) << text;
  EXPECT_NE(text.find("\"frame\": 2"), std::string::npos) << text;
}

TEST_F(Cli, PathReuseTakesAPoolOffOrAuto) {
  // Forced on, every frame's samples are traced with reuse, off none; auto (the default)
  // starts with reuse and reports how many were.
  for (const std::string& reuse :
       {std::string("16"), std::string("auto"), std::string("off"), std::string("default")}) {
    const std::string report = path("r" + reuse + ".json");
    std::vector<std::string> args = {"render",   "cornell",  "--size", "16x12", "--frame-ms",
                                     "5",        "--frames", "3",      "--out", path("r.exr"),
                                     "--report", report,     "--quiet"};
    if (reuse != "default") args.insert(args.end(), {"--path-reuse", reuse});
    CommandResult r = run_tuneray(args);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    std::ifstream f(report);
    const nlohmann::json j = nlohmann::json::parse(f);
    ASSERT_EQ(j["frames"].size(), 3u) << j.dump(2);
    for (const auto& frame : j["frames"]) {
      const double reused = frame["reused_spp"].get<double>(), spp = frame["spp"].get<double>();
      if (reuse == "16") {
        EXPECT_DOUBLE_EQ(reused, spp) << j.dump(2);
      }
      if (reuse == "off") {
        EXPECT_EQ(reused, 0.0) << j.dump(2);
      }
      EXPECT_LE(reused, spp) << j.dump(2);
    }
    if (reuse == "auto" || reuse == "default") {
      EXPECT_GT(j["frames"][0]["reused_spp"].get<double>(), 0.0) << j.dump(2);
    }
  }
  for (const char* bad : {"1", "65", "-2", "16x", "sometimes"}) {
    CommandResult r = run_tuneray({"render", "cornell", "--size", "16x12", "--spp", "1",
                                   "--path-reuse", bad, "--out", path("b.exr")});
    EXPECT_FALSE(r.signaled) << r.output;
    EXPECT_NE(r.exit_code, 0) << bad;
    EXPECT_NE(r.output.find("--path-reuse"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(bad), std::string::npos) << r.output;
  }
}

TEST_F(Cli, PhaseProfileSplitsTheRenderTime) {
  std::string report = path("p.json");
  CommandResult r = run_tuneray({"render", "cornell", "--size", "16x12", "--spp", "2",
                                 "--profile-phases", "--out", path("p.exr"), "--report", report});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("phases    intersect"), std::string::npos) << r.output;
  std::ifstream f(report);
  nlohmann::json j = nlohmann::json::parse(f);
  ASSERT_TRUE(j.contains("phases_ms")) << j.dump(2);
  EXPECT_GT(j["phases_ms"]["intersect"].get<double>(), 0.0);
  EXPECT_GT(j["phases_ms"]["shading"].get<double>(), 0.0);
  EXPECT_GE(j["phases_ms"]["shadow"].get<double>(), 0.0);
}

TEST_F(Cli, BadQualityOptionsAreRejected) {
  expect_clean_failure(run_tuneray({"render", "cornell", "--sky-texels", "rgbx"}), "rgbx");
  expect_clean_failure(run_tuneray({"render", "cornell", "--sky-sampling", "bsdff"}), "bsdff");
  expect_clean_failure(run_tuneray({"render", "cornell", "--adaptive", "--quiet"}), "frame-ms");
  expect_clean_failure(run_tuneray({"render", "cornell", "--scheduler", "waves"}), "waves");
  expect_clean_failure(run_tuneray({"render", "cornell", "--materials", "fast"}), "fast");
  expect_clean_failure(run_tuneray({"render", "cornell", "--sampler", "sobol"}), "sobol");
  expect_clean_failure(
      run_tuneray({"render", "cornell", "--frame-ms", "5", "--adaptive", "--no-adaptive"}),
      "contradict");
}

TEST_F(Cli, NonFiniteNumbersAreRejected) {
  expect_clean_failure(run_tuneray({"render", "cornell", "--frame-ms", "nan", "--frames", "2"}),
                       "'nan' is not a finite number");
  expect_clean_failure(run_tuneray({"render", "cornell", "--exposure", "-inf"}), "exposure");
  expect_clean_failure(run_tuneray({"render", "cornell", "--clamp-rel", "NaN"}), "clamp-rel");
  expect_clean_failure(run_tuneray({"render", "cornell", "--until-rmse", "nan"}), "until-rmse");
  expect_clean_failure(run_tuneray({"tune", "cornell", "--epsilon", "nan"}), "epsilon");
}

constexpr const char* kTriangleObj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";

// A little-endian RGB PFM of width x 1 texels, all set to `value`.
std::string pfm_row(int width, float value) {
  std::string bytes = "PF\n" + std::to_string(width) + " 1\n-1.0\n";
  for (int i = 0; i < 3 * width; ++i)
    bytes.append(reinterpret_cast<const char*>(&value), sizeof value);
  return bytes;
}

TEST_F(Cli, EnvironmentMapWithNanTexelsIsRefusedNamingTheTexel) {
  write("tri.obj", kTriangleObj);
  write("nan.pfm", pfm_row(4, std::numeric_limits<float>::quiet_NaN()));
  std::string scene = write("s.json", R"({"mesh": "tri.obj", "environment": {"map": "nan.pfm"}})");
  CommandResult r = run_tuneray({"render", scene, "--spp", "1", "--size", "8x8", "--quiet"});
  expect_clean_failure(r, "nan.pfm");
  expect_clean_failure(r, "texel (0, 0)");
}

TEST_F(Cli, EnvironmentMapWithNegativeTexelsIsRefused) {
  write("tri.obj", kTriangleObj);
  write("neg.pfm", pfm_row(2, -0.5f));
  std::string scene = write("s.json", R"({"mesh": "tri.obj", "environment": {"map": "neg.pfm"}})");
  expect_clean_failure(run_tuneray({"render", scene, "--spp", "1", "--size", "8x8", "--quiet"}),
                       "-0.5");
}

TEST_F(Cli, TextureWithNanTexelsIsRefusedNamingTheTexture) {
  write("bad.pfm", pfm_row(3, std::numeric_limits<float>::quiet_NaN()));
  write("m.mtl", "newmtl t\nKd 1 1 1\nmap_Kd bad.pfm\n");
  std::string obj = write("t.obj", std::string("mtllib m.mtl\nusemtl t\nvt 0 0\nvt 1 0\nvt 0 1\n") +
                                       "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/1 2/2 3/3\n");
  CommandResult r = run_tuneray({"render", obj, "--spp", "1", "--size", "8x8", "--quiet"});
  expect_clean_failure(r, "bad.pfm");
  expect_clean_failure(r, "texel (0, 0)");
}

TEST_F(Cli, GeometryBeyondFloatRangeIsRefused) {
  std::string obj = write("far.obj", "v 0 0 0\nv 1e38 0 0\nv 0 1 0\nf 1 2 3\n");
  CommandResult r = run_tuneray({"render", obj, "--spp", "1", "--size", "8x8", "--quiet"});
  expect_clean_failure(r, "far.obj");
  expect_clean_failure(r, "vertex 1");
  // Large but representable coordinates still render.
  std::string big = write("big.obj", "v 0 0 0\nv 1e12 0 0\nv 0 1e12 0\nf 1 2 3\n");
  CommandResult ok = run_tuneray(
      {"render", big, "--spp", "1", "--size", "8x8", "--out", path("big.exr"), "--quiet"});
  EXPECT_EQ(ok.exit_code, 0) << ok.output;
}

TEST_F(Cli, ImagesLargerThanMemoryAreRefusedWithTheFigure) {
  // 16384 x 16384 pixels need 32 GiB at the film's bound: more than a CI machine has available
  // (the check is skipped where /proc/meminfo cannot be read).
  std::ifstream meminfo("/proc/meminfo");
  std::string key, unit;
  uint64_t available_kib = 0;
  while (meminfo >> key >> available_kib >> unit && key != "MemAvailable:") {
  }
  if (key != "MemAvailable:") GTEST_SKIP() << "no MemAvailable in /proc/meminfo";
  if (available_kib > (30ull << 20)) GTEST_SKIP() << "more than 30 GiB available";
  expect_clean_failure(
      run_tuneray({"render", "cornell", "--spp", "1", "--size", "16384x16384", "--quiet"}),
      "MiB, more than");
}

TEST_F(Cli, TooManyThreadsAreClampedWithANote) {
  CommandResult r = run_tuneray({"render", "cornell", "--spp", "1", "--size", "8x8", "--threads",
                                 "1024", "--out", path("t.exr"), "--quiet"});
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("clamped"), std::string::npos) << r.output;
}

TEST_F(Cli, UnknownCommandFails) {
  CommandResult r = run_tuneray({"frobnicate"});
  EXPECT_FALSE(r.signaled);
  EXPECT_NE(r.exit_code, 0);
}

}  // namespace
}  // namespace tuneray
