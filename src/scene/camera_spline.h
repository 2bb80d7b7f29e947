// Camera paths: a smooth curve through keyframes, sampled at N positions, and an automatic path
// for scenes that bring none.
#pragma once

#include <vector>

#include "scene/camera.h"
#include "scene/scene.h"

namespace tuneray {

// Centripetal Catmull-Rom through the keyframes' positions and targets (no cusps or
// self-intersections within a segment, unlike the uniform variant); fov and lens are
// interpolated linearly. The first and last samples are the first and last keyframes.
// Throws std::invalid_argument for an empty path or count < 1.
std::vector<CameraDesc> sample_camera_path(const CameraPath& path, int count);

// A path that flies from far outside the scene to close to its geometry and back, around the
// bounding box at varying heights, so the visible geometry changes a lot along it.
CameraPath automatic_camera_path(const Scene& scene);

// The `count` cameras that `tune` and `eval` measure: sampled along the scene's camera path
// `path_index`, or along automatic_camera_path for path 0 of a scene that brings none. Throws
// std::invalid_argument for a path the scene does not have and for count < 1.
std::vector<CameraDesc> cameras_along_path(const Scene& scene, int path_index, int count);

}  // namespace tuneray
