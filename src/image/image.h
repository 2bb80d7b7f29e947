// A linear-light float RGB image. The film, textures, environment maps and error metrics all
// use it; conversion to and from files lives in image/io.h.
#pragma once

#include <cstddef>
#include <vector>

#include "math/vec.h"

namespace tuneray {

class Image {
 public:
  Image() = default;
  Image(int width, int height, Color fill = Color(0))
      : width_(width), height_(height), pixels_(static_cast<size_t>(width) * height, fill) {}

  int width() const { return width_; }
  int height() const { return height_; }
  bool empty() const { return pixels_.empty(); }
  size_t pixel_count() const { return pixels_.size(); }

  Color& at(int x, int y) { return pixels_[static_cast<size_t>(y) * width_ + x]; }
  const Color& at(int x, int y) const { return pixels_[static_cast<size_t>(y) * width_ + x]; }
  Color* data() { return pixels_.data(); }
  const Color* data() const { return pixels_.data(); }

 private:
  int width_ = 0, height_ = 0;
  std::vector<Color> pixels_;
};

}  // namespace tuneray
