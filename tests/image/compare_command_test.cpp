#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>

#include "common/temp_dir.h"
#include "image/compare_command.h"
#include "image/io.h"

namespace tuneray {
namespace {

struct Result {
  int code;
  std::string out, err;
};

Result compare(const std::string& a, const std::string& b, bool json) {
  std::ostringstream out, err;
  const int code = run_compare(a, b, json, out, err);
  return {code, out.str(), err.str()};
}

TEST(CompareCommand, PrintsRmsePsnrRelmse) {
  testing::TempDir dir;
  const std::string a = dir.file("a.pfm"), b = dir.file("b.exr");
  write_image(a, Image(1, 1, Color(1, 0, 0)));
  write_image(b, Image(1, 1, Color(0)));
  const Result r = compare(a, b, false);
  ASSERT_EQ(r.code, 0) << r.err;
  std::istringstream lines(r.out);
  std::string rmse_label, psnr_label, db, relmse_label;
  double rmse, psnr, relmse;
  lines >> rmse_label >> rmse >> psnr_label >> psnr >> db >> relmse_label >> relmse;
  EXPECT_EQ(rmse_label, "RMSE");
  EXPECT_EQ(psnr_label, "PSNR");
  EXPECT_EQ(db, "dB");
  EXPECT_EQ(relmse_label, "relMSE");
  EXPECT_NEAR(rmse, std::sqrt(1.0 / 3.0), 1e-7);
  EXPECT_NEAR(psnr, 10.0 * std::log10(3.0), 1e-6);
  EXPECT_NEAR(relmse, 100.0 / 3.0, 1e-5);
}

TEST(CompareCommand, JsonOutput) {
  testing::TempDir dir;
  const std::string a = dir.file("a.exr"), b = dir.file("b.exr");
  Image image(3, 2, Color(0.5f));
  write_image(b, image);
  image.at(2, 1) = Color(0.5f, 0.5f, 2.5f);
  write_image(a, image);
  const Result r = compare(a, b, true);
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_DOUBLE_EQ(j["rmse"].get<double>(), std::sqrt(4.0 / 18.0));
  EXPECT_DOUBLE_EQ(j["max_abs"].get<double>(), 2.0);
  EXPECT_DOUBLE_EQ(j["relmse"].get<double>(), 4.0 / 0.26 / 18.0);
  EXPECT_DOUBLE_EQ(j["psnr"].get<double>(), 10.0 * std::log10(18.0 / 4.0));
  EXPECT_EQ(j["width"], 3);
  EXPECT_EQ(j["height"], 2);

  const auto same = nlohmann::json::parse(compare(b, b, true).out);
  EXPECT_TRUE(same["psnr"].is_null());
  EXPECT_EQ(same["rmse"], 0.0);
}

TEST(CompareCommand, PngPairsUseStoredCodes) {
  testing::TempDir dir;
  const std::string a = dir.file("a.png"), b = dir.file("b.png");
  write_image(a, Image(2, 2, Color(0.5f)));  // sRGB code 188
  write_image(b, Image(2, 2, Color(0.0f)));
  const Result r = compare(a, b, true);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NEAR(nlohmann::json::parse(r.out)["rmse"].get<double>(), 188.0 / 255.0, 1e-6);
}

TEST(CompareCommand, MixedLinearAndDisplayFilesAreRefused) {
  testing::TempDir dir;
  const std::string a = dir.file("a.exr"), b = dir.file("b.png");
  write_image(a, Image(1, 1));
  write_image(b, Image(1, 1));
  const Result r = compare(a, b, false);
  EXPECT_EQ(r.code, 1);
  EXPECT_TRUE(r.out.empty());
  EXPECT_NE(r.err.find(a), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(b), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("not on the same scale"), std::string::npos) << r.err;
}

TEST(CompareCommand, SizeMismatchNamesFilesAndSizes) {
  testing::TempDir dir;
  const std::string a = dir.file("a.pfm"), b = dir.file("b.pfm");
  write_image(a, Image(4, 3));
  write_image(b, Image(2, 2));
  const Result r = compare(a, b, false);
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find(a), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(b), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("4x3 vs 2x2"), std::string::npos) << r.err;
}

TEST(CompareCommand, MissingFileIsAnError) {
  testing::TempDir dir;
  const std::string a = dir.file("a.pfm");
  write_image(a, Image(1, 1));
  const Result r = compare(a, dir.file("missing.pfm"), false);
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("missing.pfm: file not found"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace tuneray
