// Native Embree on the command line: `tune` reports every camera against native (table, summary
// and JSON), `bench traversal` ends each scene with a render-level run, and a bad scheduler is
// refused with its name by every command that takes one.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <vector>

#include "command_test.h"
#include "run_command.h"

namespace tuneray {
namespace {

using testing::CommandResult;
using testing::run_tuneray;

class NativeCli : public testing::CommandTest {};

std::string fmt_ratio(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3f", v);
  return text;
}

TEST_F(NativeCli, TuneReportsEveryCameraAgainstNative) {
  const std::string db = path("t.db"), json = path("t.json");
  CommandResult r = run_tuneray({"tune", "cornell", "--cameras", "2", "--iterations", "3", "--size",
                                 "32x18", "--db", db, "--json", json, "--quiet"});
  ASSERT_FALSE(r.signaled) << r.output;
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("wavefront scheduler"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("native ms"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("vs native"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("speedup over native Embree (medium): median"), std::string::npos)
      << r.output;

  nlohmann::json j = nlohmann::json::parse(std::ifstream(json));
  EXPECT_EQ(j["scheduler"], "wavefront");
  EXPECT_EQ(j["tuning_key"], "backend+bvh/render/32x18/1spp/3b/wavefront");
  ASSERT_EQ(j["cameras"].size(), 2u);
  std::vector<double> ratios;
  for (const auto& c : j["cameras"]) {
    const double native = c["native_ms"], chosen = c["chosen_ms"];
    EXPECT_GT(native, 0.0);
    EXPECT_GT(chosen, 0.0);
    // The paired estimate (median of the per-round ratios) inside its own interval; the
    // costs' quotient need not be, medians not being transitive.
    const double vs_native = c["vs_native"];
    EXPECT_LE(c["vs_native_ci95"][0].get<double>(), vs_native);
    EXPECT_GE(c["vs_native_ci95"][1].get<double>(), vs_native);
    ratios.push_back(vs_native);
    // The summary table prints the same number.
    EXPECT_NE(r.output.find(fmt_ratio(vs_native)), std::string::npos) << r.output;
  }
  EXPECT_NEAR(j["vs_native"]["median"].get<double>(), 0.5 * (ratios[0] + ratios[1]), 1e-9);
  EXPECT_NEAR(j["vs_native"]["geomean"].get<double>(), std::sqrt(ratios[0] * ratios[1]), 1e-9);
}

TEST_F(NativeCli, TuneOnTilesWithoutNativeInTheSpace) {
  const std::string json = path("t.json");
  CommandResult r = run_tuneray({"tune", "cornell", "--cameras", "1", "--iterations", "2", "--size",
                                 "32x18", "--db", path("t.db"), "--scheduler", "tile",
                                 "--tuned-only", "--json", json, "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("tuned BVH only"), std::string::npos) << r.output;
  nlohmann::json j = nlohmann::json::parse(std::ifstream(json));
  EXPECT_EQ(j["tuning_key"], "bvh/render/32x18/1spp/3b");
  EXPECT_EQ(j["cameras"][0]["backend"], "tuned");
  EXPECT_GT(j["cameras"][0]["native_ms"].get<double>(), 0.0);
}

TEST_F(NativeCli, BenchTraversalEndsWithARenderLevelRun) {
  const std::string json = path("b.json");
  CommandResult r = run_tuneray({"bench", "traversal", "cornell", "--rays", "2000", "--no-sweep",
                                 "--repeats", "2", "--size", "16x12", "--json", json});
  ASSERT_FALSE(r.signaled) << r.output;
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("x native"), std::string::npos) << r.output;
  nlohmann::json j = nlohmann::json::parse(std::ifstream(json));
  const nlohmann::json& run = j["scenes"][0]["render"];
  ASSERT_TRUE(run.is_object()) << j.dump(2);
  // Paired rounds from --repeats on; the speedup is the median of the paired ratios (even
  // count: the geometric mean of the middle two).
  const size_t rounds = run["native_ms"].size();
  ASSERT_GE(rounds, 2u);
  ASSERT_EQ(run["chosen_ms"].size(), rounds);
  std::vector<double> ratios;
  for (size_t k = 0; k < rounds; ++k)
    ratios.push_back(run["native_ms"][k].get<double>() / run["chosen_ms"][k].get<double>());
  std::sort(ratios.begin(), ratios.end());
  const double middle =
      rounds % 2 ? ratios[rounds / 2] : std::sqrt(ratios[rounds / 2 - 1] * ratios[rounds / 2]);
  EXPECT_NEAR(run["speedup_over_native"].get<double>(), middle, 1e-9);
  EXPECT_LE(run["speedup_ci95"][0].get<double>(), run["speedup_over_native"].get<double>());
  EXPECT_NE(r.output.find("95% CI"), std::string::npos) << r.output;
  EXPECT_EQ(run["config"].get<std::string>().rfind("backend=tuned,", 0), 0u);

  // With a database, the configuration is the database's best; a database without the key is
  // refused with its name.
  const std::string db = path("t.db");
  ASSERT_EQ(run_tuneray({"tune", "cornell", "--cameras", "1", "--iterations", "2", "--size",
                         "16x12", "--db", db, "--quiet"})
                .exit_code,
            0);
  CommandResult with_db =
      run_tuneray({"bench", "traversal", "cornell", "--rays", "2000", "--no-sweep", "--repeats",
                   "1", "--size", "16x12", "--db", db, "--json", json});
  ASSERT_EQ(with_db.exit_code, 0) << with_db.output;
  j = nlohmann::json::parse(std::ifstream(json));
  EXPECT_NE(j["scenes"][0]["render"]["source"].get<std::string>().find("best in"),
            std::string::npos);
  CommandResult other_key =
      run_tuneray({"bench", "traversal", "cornell", "--rays", "2000", "--no-sweep", "--repeats",
                   "1", "--size", "16x12", "--spp", "3", "--db", db});
  EXPECT_FALSE(other_key.signaled);
  EXPECT_NE(other_key.exit_code, 0);
  EXPECT_NE(other_key.output.find("t.db"), std::string::npos) << other_key.output;
}

// --cpu-time changes only the clock: every ray set still gets both rates and their ratio. The
// option belongs to traversal; `bench build` refuses it rather than ignoring it.
TEST_F(NativeCli, BenchTraversalTimesByCpuTimeOnRequest) {
  const std::string json = path("cpu.json");
  CommandResult r =
      run_tuneray({"bench", "traversal", "cornell", "--rays", "2000", "--no-sweep", "--no-render",
                   "--repeats", "2", "--threads", "1", "--cpu-time", "--json", json});
  ASSERT_FALSE(r.signaled) << r.output;
  ASSERT_EQ(r.exit_code, 0) << r.output;
  nlohmann::json j = nlohmann::json::parse(std::ifstream(json));
  const nlohmann::json& sets = j["scenes"][0]["configs"][0]["ray_sets"];
  for (const char* name : {"primary", "incoherent", "shadow"}) {
    const nlohmann::json& set = sets[name];
    ASSERT_TRUE(set.is_object()) << j.dump(2);
    EXPECT_GT(set["native_mrays"].get<double>(), 0.0) << name;
    EXPECT_NEAR(set["ratio"].get<double>(),
                set["tuned_mrays"].get<double>() / set["native_mrays"].get<double>(), 1e-9)
        << name;
  }
  CommandResult build = run_tuneray({"bench", "build", "cornell", "--cpu-time"});
  EXPECT_FALSE(build.signaled);
  EXPECT_NE(build.exit_code, 0);
  EXPECT_NE(build.output.find("--cpu-time"), std::string::npos) << build.output;
}

TEST_F(NativeCli, BadSchedulerIsRefusedByEveryCommand) {
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"tune", "cornell", "--scheduler", "waves", "--db", path("x.db")},
        std::vector<std::string>{"eval", "--scheduler", "waves", "--out", path("e")},
        std::vector<std::string>{"bench", "traversal", "cornell", "--scheduler", "waves"}}) {
    CommandResult r = run_tuneray(args);
    EXPECT_FALSE(r.signaled) << r.output;
    EXPECT_NE(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("waves"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("--scheduler"), std::string::npos) << r.output;
  }
  CommandResult size = run_tuneray({"bench", "traversal", "cornell", "--size", "12by7"});
  EXPECT_NE(size.exit_code, 0);
  EXPECT_NE(size.output.find("12by7"), std::string::npos) << size.output;
}

}  // namespace
}  // namespace tuneray
