#include "render/image_size.h"

#include <charconv>
#include <stdexcept>

namespace tuneray {

std::pair<int, int> parse_size(const std::string& text) {
  size_t x = text.find_first_of("xX");
  auto bad = [&] {
    return std::invalid_argument("bad --size '" + text +
                                 "': expected WIDTHxHEIGHT, each 1..16384, e.g. 640x360");
  };
  if (x == std::string::npos) throw bad();
  int w = 0, h = 0;
  auto r1 = std::from_chars(text.data(), text.data() + x, w);
  auto r2 = std::from_chars(text.data() + x + 1, text.data() + text.size(), h);
  if (r1.ec != std::errc() || r1.ptr != text.data() + x || r2.ec != std::errc() ||
      r2.ptr != text.data() + text.size() || w < 1 || h < 1 || w > 16384 || h > 16384)
    throw bad();
  return {w, h};
}

}  // namespace tuneray
