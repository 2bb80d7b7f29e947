#include "tuning/render_space.h"

#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

#include "tuning/bvh_space.h"

namespace tuneray {

namespace {
// `value` when the set holds it, else `fallback` (the renderer's own default).
int64_t member_or(int64_t value, const std::vector<int64_t>& set, int64_t fallback) {
  return std::find(set.begin(), set.end(), value) != set.end() ? value : fallback;
}
}  // namespace

tuner::Space make_render_space(const RenderSettings& defaults, tuner::Space base) {
  const std::vector<int64_t> tiles = {8, 16, 32, 64};
  const std::vector<int64_t> batches = {256, 1024, 4096, 16384, 65536};
  const RenderSettings renderer;
  tuner::Space space = std::move(base);
  space
      .add_enum("scheduler", {"tile", "wavefront"},
                defaults.quality.wavefront ? "wavefront" : "tile")
      .add_int_set("tile_size", tiles, member_or(defaults.tile_size, tiles, renderer.tile_size))
      .add_int_set("batch_size", batches,
                   member_or(defaults.quality.batch_size, batches, renderer.quality.batch_size));
  space.add_condition("tile_size", tuner::Space::when_enum_not("scheduler", {"wavefront"}))
      .add_condition("batch_size", tuner::Space::when_enum_not("scheduler", {"tile"}));
  return space;
}

WorkSizes to_work_sizes(const tuner::Config& c) {
  WorkSizes w;
  w.wavefront = c.get_enum("scheduler") == "wavefront";
  w.tile_size = static_cast<int>(c.get_int("tile_size"));
  w.batch_size = static_cast<int>(c.get_int("batch_size"));
  return w;
}

tuner::Config to_tuner_config(const tuner::Space& space, const BvhConfig& bvh,
                              const WorkSizes& work) {
  return to_tuner_config(space, AccelChoice::tuned(bvh), work);
}

tuner::Config to_tuner_config(const tuner::Space& space, const AccelChoice& choice,
                              const WorkSizes& work) {
  tuner::Config c = to_tuner_config(space, choice);
  // Only the active size is set: the other one may hold any value, the scheduler ignores it.
  c.set_enum("scheduler", work.wavefront ? "wavefront" : "tile");
  if (work.wavefront)
    c.set_int("batch_size", work.batch_size);
  else
    c.set_int("tile_size", work.tile_size);
  return space.canonical(c);
}

}  // namespace tuneray
