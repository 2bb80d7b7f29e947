// Records the cameras a flight passes through as a camera path in the form scene files read
// (an element of a JSON scene's "camera_paths": {"name", "keyframes": [cameras]}).
#pragma once

#include <string>
#include <vector>

#include "scene/camera.h"

namespace tuneray {

class PathRecorder {
 public:
  explicit PathRecorder(std::string name) : path_{std::move(name), {}} {}

  // Adds `camera` unless it equals the last keyframe: a path through repeated points has
  // zero-length segments, which a centripetal spline cannot parametrise.
  void add(const CameraDesc& camera);

  const CameraPath& path() const { return path_; }
  // The path as JSON text (two-space indented). Throws std::runtime_error when the path has
  // no keyframe, since scene files reject empty paths.
  std::string to_json() const;
  // Writes to_json() to `file` through the atomic writer.
  void write(const std::string& file) const;

 private:
  CameraPath path_;
};

}  // namespace tuneray
