// The tune report's summary and JSON: medians over the cameras, and the cameras that kept a
// yardstick counted and named with what the tuner's rejected choice measured.
#include <gtest/gtest.h>

#include "bench/tune_summary.h"

namespace tuneray {
namespace {

CameraTuneResult camera(int index, double speedup, double vs_native, const std::string& backend) {
  CameraTuneResult c;
  c.camera = index;
  c.mode = "exploit";
  c.speedup_ratio = speedup;
  c.vs_native_ratio = vs_native;
  c.backend = backend;
  c.compare_within_target = true;
  return c;
}

TEST(TuneSummary, CountsTheCamerasThatKeptAYardstick) {
  TuneReport report;
  report.cameras.push_back(camera(0, 1.10, 1.05, "tuned"));
  CameraTuneResult kept = camera(1, 1.02, 1.0, "native");
  kept.fallback = "native";
  kept.rejected = "backend=tuned,quality=medium";
  kept.rejected_vs_native = 0.93;
  kept.rejected_speedup = 0.99;
  report.cameras.push_back(kept);
  report.cameras.push_back(camera(2, 1.20, 1.02, "tuned"));

  const TuneSummary s = summarize_tune(report);
  EXPECT_EQ(s.fallbacks, 1);
  EXPECT_EQ(s.tuned, 2);
  EXPECT_DOUBLE_EQ(s.vs_native_median, 1.02);
  EXPECT_DOUBLE_EQ(s.speedup_median, 1.10);

  const nlohmann::json j =
      tune_report_json(TuneOptions{}, "render", "wavefront", "320x180", report);
  EXPECT_EQ(j["fallbacks"], 1);
  EXPECT_EQ(j["cameras"][0]["fallback"], "");
  EXPECT_EQ(j["cameras"][1]["fallback"], "native");
  EXPECT_EQ(j["cameras"][1]["rejected"], "backend=tuned,quality=medium");
  EXPECT_DOUBLE_EQ(j["cameras"][1]["rejected_vs_native"].get<double>(), 0.93);
  EXPECT_DOUBLE_EQ(j["cameras"][1]["rejected_speedup"].get<double>(), 0.99);
}

}  // namespace
}  // namespace tuneray
