#include "render/image_size.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <utility>

namespace tuneray {
namespace {

TEST(ImageSize, ReadsWidthAndHeight) {
  EXPECT_EQ(parse_size("640x360"), std::make_pair(640, 360));
  EXPECT_EQ(parse_size("1X16384"), std::make_pair(1, 16384));
}

TEST(ImageSize, RefusesMalformedAndOutOfRangeSizes) {
  for (const char* text : {"", "640", "640x", "x360", "640x360x", "640x36a", "0x360", "640x0",
                           "-5x5", "16385x1", "99999999999x1", " 640x360"})
    EXPECT_THROW(parse_size(text), std::invalid_argument) << text;
}

}  // namespace
}  // namespace tuneray
