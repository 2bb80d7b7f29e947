// Procedural scenes that need no files. Each has a camera, at least one camera path of four or
// more keyframes (near and far views) and at least one light or environment.
#pragma once

#include "scene/scene.h"

namespace tuneray {

Scene make_cornell_scene();      // the default: Cornell box with an anisotropic metal tall box
Scene make_voxels_scene();       // unit-cube heightfield terrain, sky and a sun-like point light
Scene make_mixed_scene();        // ~100k-triangle torus on a huge two-triangle floor, area light
Scene make_furnace_scene();      // unit Lambert sphere (albedo 1, material "diffuse") in radiance 1
Scene make_furnace_ggx_scene();  // same with a GGX sphere (F0 1, roughness 0.5)
Scene make_sky_scene();          // every material type under a procedural HDR sky with a sun

// A camera keyframe looking from `position` at `target` (y up).
CameraDesc look_at(const std::string& name, Vec3f position, Vec3f target, float vfov_deg);

}  // namespace tuneray
