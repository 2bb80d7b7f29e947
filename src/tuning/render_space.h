// A BVH space extended with the renderer's work sizes (`tuneray tune --work-sizes`): the
// parameters of `base` (make_bvh_space() or make_backend_space() of bvh_space.h), then
//   scheduler   {tile, wavefront}, default from the RenderSettings given (wavefront if on);
//   tile_size   {8, 16, 32, 64}, active only under the tile scheduler;
//   batch_size  {256, 1024, 4096, 16384, 65536}, active only under wavefront;
// each size's default is the settings' when its set holds it, else the renderer's default.
// The inactive size is pinned to its default, so the search does not spend measurements on a
// size the scheduler ignores. Opt-in: the BVH-only space (and its database signature) is
// unchanged, and the extended one is stored under another tuning key.
#pragma once

#include "accel/bvh_config.h"
#include "render/render_settings.h"
#include "tuner/config.h"
#include "tuner/space.h"
#include "tuning/accel_choice.h"
#include "tuning/bvh_space.h"
#include "tuning/work_sizes.h"

namespace tuneray {

tuner::Space make_render_space(const RenderSettings& defaults,
                               tuner::Space base = make_bvh_space());

// The scheduler and sizes of a configuration of make_render_space(); the BVH part is read with
// to_bvh_config() as for the BVH-only space.
WorkSizes to_work_sizes(const tuner::Config& config);
// The tuner's configuration for a BVH and work sizes (conditions applied, so the size the
// scheduler ignores comes back as its default). Throws std::invalid_argument when the active size
// is outside its set.
tuner::Config to_tuner_config(const tuner::Space& space, const BvhConfig& bvh,
                              const WorkSizes& work);
// The same for an accelerator choice (the space's base must have the backend parameter when the
// choice is native).
tuner::Config to_tuner_config(const tuner::Space& space, const AccelChoice& choice,
                              const WorkSizes& work);

}  // namespace tuneray
