#include "tuning/work_sizes.h"

#include <fmt/core.h>

namespace tuneray {

WorkSizes WorkSizes::of(const RenderSettings& settings) {
  return {settings.quality.wavefront, settings.tile_size, settings.quality.batch_size};
}

std::string WorkSizes::to_string() const {
  return wavefront ? fmt::format("scheduler=wavefront,batch_size={}", batch_size)
                   : fmt::format("scheduler=tile,tile_size={}", tile_size);
}

}  // namespace tuneray
