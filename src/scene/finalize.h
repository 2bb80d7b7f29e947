// What every loaded scene gets before it is handed out: a camera, some light, a mesh range,
// and a check of the invariants the renderer relies on.
#pragma once

#include "scene/scene.h"

namespace tuneray {

// A camera looking at the centre of `box` from a diagonal direction (above, in front, to the
// right, y up), far enough that the bounding sphere fits a vertical field of view of `vfov_deg`.
CameraDesc frame_bounds(const BBox& box, float vfov_deg = 45.0f);

// Adds an automatic camera (and an automatic camera path) when the scene has none and a constant
// sky of radiance 1 when it has no emissive triangle, point light or environment; each such
// decision is recorded in scene.notes. Throws SceneError naming scene.source when an invariant
// is broken (normals or uvs of the wrong size, indices or material ids out of range).
void finalize_scene(Scene& scene);

}  // namespace tuneray
