// `tuneray render --denoise` through the binary: it writes the filtered image.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <string>

#include "common/temp_dir.h"
#include "image/io.h"

namespace tuneray {
namespace {

int run_render(const std::string& args) {
  const char* bin = std::getenv("TUNERAY_BIN");
  if (!bin) return -1;
  return std::system((std::string("\"") + bin + "\" render cornell --size 64x48 --spp 4 --quiet " +
                      args + " > /dev/null 2>&1")
                         .c_str());
}

// Mean absolute difference of horizontal neighbours: the noise shows up as roughness.
double roughness(const Image& image) {
  double sum = 0;
  for (int y = 0; y < image.height(); ++y)
    for (int x = 1; x < image.width(); ++x)
      sum += std::abs(luminance(image.at(x, y)) - luminance(image.at(x - 1, y)));
  return sum / (image.height() * (image.width() - 1));
}

TEST(DenoiserCli, RenderWithDenoiseWritesASmootherImage) {
  if (!std::getenv("TUNERAY_BIN")) GTEST_SKIP() << "TUNERAY_BIN is not set (run through ctest)";
  testing::TempDir dir;
  std::string raw = dir.file("raw.pfm"), filtered = dir.file("denoised.pfm");
  ASSERT_EQ(run_render("--out \"" + raw + "\""), 0);
  ASSERT_EQ(run_render("--denoise --out \"" + filtered + "\""), 0);
  Image a = read_image(raw), b = read_image(filtered);
  ASSERT_EQ(a.width(), b.width());
  EXPECT_LT(roughness(b), 0.7 * roughness(a)) << roughness(a) << " -> " << roughness(b);
}

}  // namespace
}  // namespace tuneray
