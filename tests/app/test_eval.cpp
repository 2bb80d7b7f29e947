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

  // Every summary row appears in the report with the same numbers.
  auto summary = read_csv(out / "summary.csv");
  ASSERT_GE(summary.size(), 5u);  // header + 2 scenes x 2 objectives
  for (size_t i = 1; i < summary.size(); ++i) {
    const auto& row = summary[i];
    std::string expected =
        "| " + row[0] + " | " + row[2] + " | " + row[3] + " | " + row[4] + " | " + row[5] + " |";
    EXPECT_NE(report.find(expected), std::string::npos) << "missing in report: " << expected;
  }

  // The summary's search speedup is the median of the per-camera values in cameras.csv.
  auto cameras = read_csv(out / "cameras.csv");
  std::map<std::string, std::vector<double>> speedups;
  for (size_t i = 1; i < cameras.size(); ++i)
    speedups[cameras[i][0] + "/" + cameras[i][1]].push_back(std::stod(cameras[i][6]));
  for (size_t i = 1; i < summary.size(); ++i) {
    auto v = speedups[summary[i][0] + "/" + summary[i][1]];
    ASSERT_EQ(v.size(), 6u);  // quick profile: 6 cameras
    std::sort(v.begin(), v.end());
    double median = 0.5 * (v[2] + v[3]);
    EXPECT_NEAR(std::stod(summary[i][3]), median, 1.5e-3) << summary[i][0];
  }

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
