#include "view/path_recorder.h"

#include <nlohmann/json.hpp>
#include <stdexcept>

#include "image/atomic_file.h"

namespace tuneray {

namespace {

bool same_view(const CameraDesc& a, const CameraDesc& b) {
  return a.position == b.position && a.target == b.target && a.up == b.up &&
         a.vfov_deg == b.vfov_deg && a.lens_radius == b.lens_radius &&
         a.focus_distance == b.focus_distance;
}

nlohmann::ordered_json vec3_json(Vec3f v) {
  return {v.x, v.y, v.z};
}

}  // namespace

void PathRecorder::add(const CameraDesc& camera) {
  if (!path_.keyframes.empty() && same_view(path_.keyframes.back(), camera)) return;
  path_.keyframes.push_back(camera);
}

std::string PathRecorder::to_json() const {
  if (path_.keyframes.empty())
    throw std::runtime_error("the recorded camera path '" + path_.name + "' has no keyframe");
  nlohmann::ordered_json keys = nlohmann::ordered_json::array();
  for (const CameraDesc& c : path_.keyframes) {
    nlohmann::ordered_json k = {{"position", vec3_json(c.position)},
                                {"target", vec3_json(c.target)},
                                {"up", vec3_json(c.up)},
                                {"fov", c.vfov_deg}};
    // Only a thin lens needs its aperture and focus; pinholes stay short.
    if (c.lens_radius > 0) {
      k["lens_radius"] = c.lens_radius;
      k["focus_distance"] = c.focus_distance;
    }
    keys.push_back(std::move(k));
  }
  nlohmann::ordered_json path = {{"name", path_.name}, {"keyframes", std::move(keys)}};
  return path.dump(2) + "\n";
}

void PathRecorder::write(const std::string& file) const {
  write_text_file(file, to_json());
}

}  // namespace tuneray
