// Load-time constant folding of textures: a triangle whose UVs all fall in one texel, and whose
// bilinear lookups therefore read only that texel and its equal neighbours, gets a clone of its
// material with the colour baked in and no texture (no lookup at render time, same image).
#pragma once

#include <cstddef>

#include "scene/scene.h"

namespace tuneray {

struct OneTexelStats {
  size_t candidates = 0;  // textured triangles whose UVs lie in one texel
  size_t collapsed = 0;   // of those, the ones whose whole bilinear footprint is one colour
  size_t materials_added = 0;
};

// Counts and (when `apply`) rewrites material ids. Materials are cloned once per (material,
// colour) pair.
OneTexelStats collapse_one_texel_textures(Scene& scene, bool apply = true);

}  // namespace tuneray
