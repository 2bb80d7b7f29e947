// The command line on good and bad input: bad input gives a clear message naming the file or
// value, a non-zero exit code, and never a crash (a signal).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

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

TEST_F(Cli, BadQualityOptionsAreRejected) {
  expect_clean_failure(run_tuneray({"render", "cornell", "--sky-texels", "rgbx"}), "rgbx");
  expect_clean_failure(run_tuneray({"render", "cornell", "--adaptive", "--quiet"}), "frame-ms");
  expect_clean_failure(run_tuneray({"render", "cornell", "--scheduler", "waves"}), "waves");
  expect_clean_failure(run_tuneray({"render", "cornell", "--materials", "fast"}), "fast");
  expect_clean_failure(run_tuneray({"render", "cornell", "--sampler", "sobol"}), "sobol");
  expect_clean_failure(
      run_tuneray({"render", "cornell", "--frame-ms", "5", "--adaptive", "--no-adaptive"}),
      "contradict");
}

TEST_F(Cli, UnknownCommandFails) {
  CommandResult r = run_tuneray({"frobnicate"});
  EXPECT_FALSE(r.signaled);
  EXPECT_NE(r.exit_code, 0);
}

}  // namespace
}  // namespace tuneray
