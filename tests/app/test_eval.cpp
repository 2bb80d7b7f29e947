// `tuneray eval --profile quick` end to end: the report, raw data and plots exist, and the
// numbers in the report are the ones the CSV files hold.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "run_command.h"

namespace tuneray {
namespace {

namespace fs = std::filesystem;

std::string read_file(const fs::path& p) {
  std::ifstream f(p);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

std::vector<std::vector<std::string>> read_csv(const fs::path& p) {
  std::vector<std::vector<std::string>> rows;
  std::ifstream f(p);
  std::string line;
  while (std::getline(f, line)) {
    std::vector<std::string> cells;
    std::string cell;
    bool quoted = false;
    for (char c : line) {
      if (c == '"')
        quoted = !quoted;
      else if (c == ',' && !quoted)
        cells.push_back(cell), cell.clear();
      else
        cell += c;
    }
    cells.push_back(cell);
    rows.push_back(cells);
  }
  return rows;
}

TEST(Eval, QuickProfileProducesAConsistentReport) {
  fs::path out = fs::temp_directory_path() / ("tuneray-eval-" + std::to_string(::getpid()));
  fs::remove_all(out);
  testing::CommandResult r =
      testing::run_tuneray({"eval", "--profile", "quick", "--out", out.string(), "--quiet"});
  ASSERT_FALSE(r.signaled) << r.output;
  ASSERT_EQ(r.exit_code, 0) << r.output;

  std::string report = read_file(out / "report.md");
  ASSERT_FALSE(report.empty());
  for (const char* obj : {"render", "total"})
    for (const char* plot : {"search_speedup", "predictor_speedup", "roofline", "break_even"})
      for (const char* ext : {".png", ".svg"}) {
        fs::path p = out / "plots" / (std::string(plot) + "_" + obj + ext);
        ASSERT_TRUE(fs::exists(p)) << p;
        EXPECT_GT(fs::file_size(p), 1000u) << p;
      }

  // Every summary row appears in the report with the same numbers, in the report's order.
  auto summary = read_csv(out / "summary.csv");
  ASSERT_GE(summary.size(), 5u);  // header + 2 scenes x 2 objectives
  auto col = [](const std::vector<std::string>& header, const std::string& name) {
    auto it = std::find(header.begin(), header.end(), name);
    EXPECT_NE(it, header.end()) << name;
    return static_cast<size_t>(it - header.begin());
  };
  const auto& sh = summary[0];
  for (size_t i = 1; i < summary.size(); ++i) {
    const auto& row = summary[i];
    auto c = [&](const std::string& name) { return row[col(sh, name)]; };
    // A ratio with its typical 95 % interval: "1.234 [1.200, 1.270]".
    auto ci = [&](const std::string& ratio, const std::string& bounds) {
      return c(ratio) + " [" + c(bounds + "_low") + ", " + c(bounds + "_high") + "]";
    };
    std::string expected =
        "| " + c("scene") + " | " + c("cameras") + " | " + c("within_target") + " of " +
        c("cameras") + ", median " + c("rounds_median") + " rounds | " +
        ci("search_speedup_median", "search_speedup") + " | " +
        ci("search_native_speedup_median", "search_native_speedup") + " | " +
        c("nn_speedup_geomean") + " | " + c("rbf_speedup_geomean") + " | " +
        c("nn_overhead_reduction_median") + " | " + c("rbf_overhead_reduction_median") + " | " +
        ci("nn_roofline_mean", "nn_roofline") + " | " + ci("rbf_roofline_mean", "rbf_roofline") +
        " | " + c("nn_break_even_median") + " (" + c("nn_never") + ") | " +
        c("rbf_break_even_median") + " (" + c("rbf_never") + ") | " +
        ci("nn_native_speedup_median", "nn_native_speedup") + " | " +
        ci("rbf_native_speedup_median", "rbf_native_speedup") + " |\n";
    EXPECT_NE(report.find(expected), std::string::npos) << "missing in report: " << expected;
  }
  EXPECT_NE(report.find("search speedup over native Embree"), std::string::npos);
  EXPECT_NE(report.find("comparisons whose every 95 % interval reached ±3 % before the cap of"),
            std::string::npos);

  // The summary's speedups over default and over native are the medians of the per-camera
  // values in cameras.csv, and each camera's search speedup is its default / converged cost
  // (costs are in units of the default's median cost, so their ratio to it is the paired
  // median), inside its interval. Every comparison ran at least the 6 rounds of a median's 95 %
  // interval and at most its cap of rounds.
  auto cameras = read_csv(out / "cameras.csv");
  const auto& ch = cameras[0];
  std::map<std::string, std::vector<double>> speedups, native_speedups;
  for (size_t i = 1; i < cameras.size(); ++i) {
    const auto& row = cameras[i];
    const std::string key = row[col(ch, "scene")] + "/" + row[col(ch, "objective")];
    speedups[key].push_back(std::stod(row[col(ch, "search_speedup")]));
    const double native = std::stod(row[col(ch, "native_speedup")]);
    native_speedups[key].push_back(native);
    const double native_ms = std::stod(row[col(ch, "native_ms")]);
    const double converged_ms = std::stod(row[col(ch, "converged_ms")]);
    const double default_ms = std::stod(row[col(ch, "default_ms")]);
    EXPECT_GT(native_ms, 0.0);
    EXPECT_LE(std::stod(row[col(ch, "native_speedup_low")]), native) << key;
    EXPECT_GE(std::stod(row[col(ch, "native_speedup_high")]), native) << key;
    const double search = std::stod(row[col(ch, "search_speedup")]);
    EXPECT_NEAR(search, default_ms / converged_ms, 2e-3 * (1 + search)) << key;
    EXPECT_LE(std::stod(row[col(ch, "search_speedup_low")]), search) << key;
    EXPECT_GE(std::stod(row[col(ch, "search_speedup_high")]), search) << key;
    const int rounds = std::stoi(row[col(ch, "rounds")]);
    EXPECT_GE(rounds, 6) << key;
    EXPECT_LE(rounds, 30) << key;
    // Below the cap, the comparison stopped because every interval was within ±3 %.
    if (rounds < 30) {
      EXPECT_EQ(row[col(ch, "ci_within_target")], "1") << key;
    }
    EXPECT_LE(std::stod(row[col(ch, "best_ms")]), converged_ms) << key;
    // Every search measures the default first: the yardstick of both windows.
    const double search_default_ms = std::stod(row[col(ch, "search_default_ms")]);
    EXPECT_GT(search_default_ms, 0.0) << key;
    EXPECT_NEAR(std::stod(row[col(ch, "search_window_load")]), search_default_ms / default_ms,
                2e-3 * (1 + search_default_ms / default_ms))
        << key;
    // The quick profile's 3 yardsticks and the search's own first frame: calibrated.
    EXPECT_GE(std::stoi(row[col(ch, "search_default_frames")]), 4) << key;
    EXPECT_EQ(row[col(ch, "search_calibrated")], "1") << key;
  }
  auto median_of = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
  };
  for (size_t i = 1; i < summary.size(); ++i) {
    const std::string key = summary[i][0] + "/" + summary[i][1];
    ASSERT_EQ(speedups[key].size(), 6u);  // quick profile: 6 cameras
    EXPECT_NEAR(std::stod(summary[i][col(sh, "search_speedup_median")]), median_of(speedups[key]),
                1.5e-3)
        << key;
    EXPECT_NEAR(std::stod(summary[i][col(sh, "search_native_speedup_median")]),
                median_of(native_speedups[key]), 1.5e-3)
        << key;
  }

  // The predictors' over-native medians come from predictions.csv.
  auto predictions = read_csv(out / "predictions.csv");
  const auto& ph = predictions[0];
  std::map<std::string, std::vector<double>> predicted_native;
  for (size_t i = 1; i < predictions.size(); ++i) {
    const auto& row = predictions[i];
    predicted_native[row[col(ph, "scene")] + "/" + row[col(ph, "objective")] + "/" +
                     row[col(ph, "predictor")]]
        .push_back(std::stod(row[col(ph, "native_speedup")]));
  }
  for (size_t i = 1; i < summary.size(); ++i)
    for (const char* predictor : {"nn", "rbf"}) {
      auto v = predicted_native[summary[i][0] + "/" + summary[i][1] + "/" + predictor];
      if (v.empty()) continue;
      EXPECT_NEAR(std::stod(summary[i][col(sh, std::string(predictor) + "_native_speedup_median")]),
                  median_of(v), 1.5e-3)
          << summary[i][0] << " " << predictor;
    }

  // The search plot shows both series per scene: 2 scenes x (over default, over native).
  const std::string plot_script = read_file(out / "plots" / "search_speedup_render.png.gp");
  EXPECT_NE(plot_script.find("index 3 "), std::string::npos) << plot_script;
  EXPECT_NE(plot_script.find("over native"), std::string::npos) << plot_script;

  // A second run resumes from the database: the searches are complete, so no frame is measured
  // again and the recorded search costs (noisy timings) come back identical.
  auto frames_before = read_csv(out / "search_frames.csv");
  testing::CommandResult again =
      testing::run_tuneray({"eval", "--profile", "quick", "--out", out.string(), "--quiet"});
  EXPECT_EQ(again.exit_code, 0) << again.output;
  EXPECT_EQ(read_csv(out / "search_frames.csv"), frames_before);
  fs::remove_all(out);
}

}  // namespace
}  // namespace tuneray
