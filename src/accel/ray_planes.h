// A batch of rays as planes, one array per component: the form the wavefront scheduler keeps
// its paths in. A backend that traces from planes skips the copy into Ray records.
#pragma once

#include <array>
#include <cstddef>
#include <span>

#include "math/ray.h"

namespace tuneray {

// Every ray spans [0, inf). Each array holds at least `size` floats.
struct RayPlanes {
  std::array<const float*, 3> org{};
  std::array<const float*, 3> dir{};
  size_t size = 0;

  Ray ray(size_t i) const {
    Ray r;
    r.org = {org[0][i], org[1][i], org[2][i]};
    r.dir = {dir[0][i], dir[1][i], dir[2][i]};
    return r;
  }
};

// The rays as records; out.size() == planes.size.
void rays_from_planes(const RayPlanes& planes, std::span<Ray> out);

}  // namespace tuneray
