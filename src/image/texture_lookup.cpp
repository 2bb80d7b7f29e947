#include "image/texture_lookup.h"

#include <cmath>

namespace tuneray {

namespace {

int wrap(int i, int n) {
  // The lookups below only ask for i in [-1, n]: one comparison each way instead of an integer
  // division (four divisions were most of a bilinear lookup's time).
  if (i >= 0 && i < n) return i;
  if (i == -1) return n - 1;
  if (i == n) return 0;
  const int r = i % n;
  return r < 0 ? r + n : r;
}

// Fractional part in [0, 1]; may round up to exactly 1 for tiny negative inputs, which the
// integer wrap absorbs.
float repeat(float t) {
  return t - std::floor(t);
}

bool usable(const Image& img, Vec2f uv) {
  return !img.empty() && std::isfinite(uv.x) && std::isfinite(uv.y);
}

}  // namespace

Color sample_nearest_wrap(const Image& img, Vec2f uv) {
  if (!usable(img, uv)) return Color(0);
  const int x = wrap(static_cast<int>(repeat(uv.x) * img.width()), img.width());
  const int from_bottom = wrap(static_cast<int>(repeat(uv.y) * img.height()), img.height());
  return img.at(x, img.height() - 1 - from_bottom);
}

Color sample_bilinear_wrap(const Image& img, Vec2f uv) {
  if (!usable(img, uv)) return Color(0);
  // Continuous texel coordinates with texel centres at integers; y counts rows from the bottom.
  const float x = repeat(uv.x) * img.width() - 0.5f;
  const float y = repeat(uv.y) * img.height() - 0.5f;
  const float x_floor = std::floor(x), y_floor = std::floor(y);
  const float fx = x - x_floor, fy = y - y_floor;
  const int x0 = wrap(static_cast<int>(x_floor), img.width());
  const int x1 = wrap(x0 + 1, img.width());
  const int row0 = img.height() - 1 - wrap(static_cast<int>(y_floor), img.height());
  const int row1 = img.height() - 1 - wrap(static_cast<int>(y_floor) + 1, img.height());
  const Color bottom = lerp(img.at(x0, row0), img.at(x1, row0), fx);
  const Color top = lerp(img.at(x0, row1), img.at(x1, row1), fx);
  return lerp(bottom, top, fy);
}

}  // namespace tuneray
