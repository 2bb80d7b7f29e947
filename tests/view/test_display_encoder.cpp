#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "image/tonemap.h"
#include "view/display_encoder.h"

namespace tuneray {
namespace {

// The table-driven encoder gives the bytes of the exact curve, at every step and in between.
TEST(DisplayEncoder, AgreesWithTheExactCurve) {
  for (float stops : {0.0f, -1.5f, 2.0f}) {
    const float scale = std::exp2(stops);
    DisplayEncoder encoder(scale);
    int mismatches = 0;
    // Dense over the displayable range and beyond, on a logarithmic grid.
    for (int i = 0; i <= 200000; ++i) {
      float v = std::pow(10.0f, -7.0f + 8.0f * static_cast<float>(i) / 200000.0f);
      if (encoder.encode(v) != encode_display_byte(v, scale, false)) ++mismatches;
    }
    EXPECT_EQ(mismatches, 0) << "exposure " << stops;
    for (float v : {0.0f, -1.0f, std::numeric_limits<float>::quiet_NaN(),
                    std::numeric_limits<float>::infinity(), 1e30f})
      EXPECT_EQ(encoder.encode(v), encode_display_byte(v, scale, false)) << v;
  }
}

}  // namespace
}  // namespace tuneray
