#include "tuning/render_space.h"

#include "tuning/bvh_space.h"

namespace tuneray {

tuner::Space make_render_space(const RenderSettings& defaults) {
  tuner::Space space = make_bvh_space();
  space
      .add_enum("scheduler", {"tile", "wavefront"},
                defaults.quality.wavefront ? "wavefront" : "tile")
      .add_int_set("tile_size", {8, 16, 32, 64}, 32)
      .add_int_set("batch_size", {256, 1024, 4096, 16384, 65536}, 4096);
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
  tuner::Config c = to_tuner_config(space, bvh);
  // Only the active size is set: the other one may hold any value, the scheduler ignores it.
  c.set_enum("scheduler", work.wavefront ? "wavefront" : "tile");
  if (work.wavefront)
    c.set_int("batch_size", work.batch_size);
  else
    c.set_int("tile_size", work.tile_size);
  return space.canonical(c);
}

}  // namespace tuneray
