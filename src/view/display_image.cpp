#include "view/display_image.h"

#include <stdexcept>

#include "image/io.h"
#include "image/srgb.h"

namespace tuneray {

Image display_to_linear(const std::vector<uint8_t>& rgb, int width, int height) {
  if (width <= 0 || height <= 0 || rgb.size() != static_cast<size_t>(width) * height * 3)
    throw std::invalid_argument("display image: " + std::to_string(rgb.size()) +
                                " bytes do not make a " + std::to_string(width) + "x" +
                                std::to_string(height) + " RGB image");
  const auto& table = srgb8_to_linear_table();
  Image image(width, height);
  size_t i = 0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x, i += 3)
      image.at(x, y) = Color(table[rgb[i]], table[rgb[i + 1]], table[rgb[i + 2]]);
  return image;
}

void write_display_image(const std::string& path, const std::vector<uint8_t>& rgb, int width,
                         int height) {
  write_image(path, display_to_linear(rgb, width, height));
}

}  // namespace tuneray
