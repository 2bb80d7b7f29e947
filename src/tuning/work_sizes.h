// How a frame's pixels are handed out to the cores: the scheduler and its work size. Neither
// changes the image (the wavefront scheduler is bit-identical to tiles), only the speed, so the
// tuner may pick them beside the BVH parameters (`tuneray tune --work-sizes`).
#pragma once

#include <string>

#include "render/render_settings.h"

namespace tuneray {

struct WorkSizes {
  bool wavefront = false;
  int tile_size = RenderSettings{}.tile_size;    // pixels per tile side (tile scheduler only)
  int batch_size = QualityOptions{}.batch_size;  // paths per wave (wavefront scheduler only)

  static WorkSizes of(const RenderSettings& settings);

  // Only the active size is named, e.g. `scheduler=tile,tile_size=16`, because the other one is
  // ignored by the renderer and the tuner pins it.
  std::string to_string() const;

  bool operator==(const WorkSizes&) const = default;
};

}  // namespace tuneray
