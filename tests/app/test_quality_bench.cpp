// `bench quality` and the ground-truth cache end to end: every configuration row is produced
// for every frame, the unbiased rows have no bias, `render --truth-dir` finds the truth the
// benchmark rendered (one cache, one key), and bad requests fail cleanly.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "command_test.h"
#include "run_command.h"

namespace tuneray {
namespace {

using testing::CommandResult;
using testing::run_tuneray;

class QualityBench : public testing::CommandTest {};

void expect_success(const CommandResult& r) {
  ASSERT_FALSE(r.signaled) << r.output;
  ASSERT_EQ(r.exit_code, 0) << r.output;
}

TEST_F(QualityBench, EveryConfigurationGetsARowPerFrameAndTheTruthIsShared) {
  const std::string truth = path("truth"), json = path("q.json"), plot = path("plot/rmse");
  CommandResult r = run_tuneray(
      {"bench", "quality",   "cornell", "--size",      "24x16", "--target-spp", "2", "--frames",
       "2",     "--repeats", "2",       "--truth-spp", "8",     "--bias-spp",   "2", "--truth-dir",
       truth,   "--json",    json,      "--plot",      plot});
  expect_success(r);
  EXPECT_NE(r.output.find("rendered: 8 spp"), std::string::npos) << r.output;

  nlohmann::json out = nlohmann::json::parse(std::ifstream(json));
  ASSERT_EQ(out["scenes"].size(), 1u);
  const nlohmann::json& configs = out["scenes"][0]["configs"];
  std::vector<std::string> names;
  for (const auto& c : configs) {
    names.push_back(c["config"]);
    EXPECT_EQ(c["rmse"].size(), 2u) << c["config"];
    EXPECT_EQ(c["rmse_repeats"].size(), 2u) << c["config"];
    EXPECT_GT(c["rmse"][1].get<double>(), 0.0) << c["config"];
    EXPECT_GT(c["rmse_at_budget"].get<double>(), 0.0) << c["config"];
    EXPECT_GT(c["time_over_budget"].get<double>(), 0.0) << c["config"];
  }
  const std::vector<std::string> expected = {"baseline",       "wavefront",
                                             "sky-rgba",       "one-texel",
                                             "branchless",     "bluenoise",
                                             "bsdf-sky",       "adaptive",
                                             "lowres-sky",     "regularize",
                                             "clamp",          "denoise",
                                             "cache",          "reuse",
                                             "reuse-auto",     "unbiased",
                                             "defaults",       "defaults+denoise",
                                             "defaults+cache", "defaults+reuse",
                                             "defaults-reuse", "all"};
  EXPECT_EQ(names, expected);
  const std::vector<std::string> biased = {"lowres-sky",     "regularize", "clamp",
                                           "denoise",        "cache",      "defaults+denoise",
                                           "defaults+cache", "all"};
  for (const auto& c : configs) {
    if (std::find(biased.begin(), biased.end(), c["config"]) == biased.end()) {
      EXPECT_EQ(c["bias"].get<double>(), 0.0) << c["config"];
    }
  }
  EXPECT_DOUBLE_EQ(configs[0]["rmse_vs_baseline"].get<double>(), 1.0);
  EXPECT_TRUE(std::filesystem::exists(plot + ".dat"));
  EXPECT_TRUE(std::filesystem::exists(plot + ".gp"));

  // The same scene, camera, size, bounces and spp through `render`: read from the cache.
  CommandResult again = run_tuneray({"render", "cornell", "--size", "24x16", "--spp", "8",
                                     "--truth-dir", truth, "--out", path("t.exr")});
  expect_success(again);
  EXPECT_NE(again.output.find("(cached)"), std::string::npos) << again.output;
  EXPECT_NE(again.output.find(out["scenes"][0]["truth"].get<std::string>()), std::string::npos)
      << again.output;
  EXPECT_GT(std::filesystem::file_size(path("t.exr")), 0u);
}

TEST_F(QualityBench, UnknownConfigurationIsNamed) {
  CommandResult r = run_tuneray({"bench", "quality", "cornell", "--only", "baseline", "--only",
                                 "sharpen", "--truth-dir", path("truth")});
  EXPECT_FALSE(r.signaled) << r.output;
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find("sharpen"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(path("truth")));  // refused before any rendering
}

TEST_F(QualityBench, TruthRefusesBiasedOptions) {
  for (std::vector<std::string> flag : std::vector<std::vector<std::string>>{
           {"--clamp-rel", "4"}, {"--clamp", "4"}, {"--regularize"}, {"--lowres-sky"}}) {
    std::vector<std::string> args = {"render", "cornell", "--size",      "24x16",
                                     "--spp",  "4",       "--truth-dir", path("truth")};
    args.insert(args.end(), flag.begin(), flag.end());
    CommandResult r = run_tuneray(args);
    EXPECT_FALSE(r.signaled) << r.output;
    EXPECT_NE(r.exit_code, 0) << flag[0];
    EXPECT_NE(r.output.find("unbiased"), std::string::npos) << r.output;
  }
}

// A ground truth without --spp gets the 4096 samples of a converged reference, not render's 16;
// the report lands in a folder that did not exist.
TEST_F(QualityBench, TruthDefaultsTo4096Spp) {
  const std::string report = path("sub/r.json");
  CommandResult r = run_tuneray({"render", "cornell", "--size", "4x3", "--truth-dir", path("truth"),
                                 "--report", report, "--quiet"});
  expect_success(r);
  nlohmann::json out = nlohmann::json::parse(std::ifstream(report));
  EXPECT_EQ(out["spp"].get<int>(), 4096);
  EXPECT_TRUE(out["rendered"].get<bool>());
}

// --until-rmse stops a render once its own error estimate is low enough, before --spp.
TEST_F(QualityBench, UntilRmseStopsEarly) {
  const std::string report = path("r.json");
  CommandResult r =
      run_tuneray({"render", "furnace", "--size", "24x16", "--spp", "100000", "--until-rmse",
                   "0.05", "--report", report, "--out", path("f.exr"), "--quiet"});
  expect_success(r);
  nlohmann::json out = nlohmann::json::parse(std::ifstream(report));
  EXPECT_LT(out["spp"].get<double>(), 100000.0);
  EXPECT_LT(out["estimated_rmse"].get<double>(), 0.05);
}

}  // namespace
}  // namespace tuneray
