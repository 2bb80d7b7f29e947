// Texture lookups with repeat (wrap) addressing.
//
// Coordinates follow the OBJ convention: uv (0,0) is the bottom-left corner of the image as
// displayed and (1,1) the top-right. Images store their top row first, so texel (x, row) has its
// centre at u = (x + 0.5) / width, v = 1 - (row + 0.5) / height. Any real uv is accepted
// (negative or beyond 1 repeats); a non-finite uv or an empty image gives black.
#pragma once

#include "image/image.h"
#include "math/vec.h"

namespace tuneray {

Color sample_nearest_wrap(const Image& img, Vec2f uv);
Color sample_bilinear_wrap(const Image& img, Vec2f uv);

}  // namespace tuneray
