// Frame-budget frames as a viewer shows them, for the equal-time benchmarks (`bench quality`,
// `bench peers`): each frame's image is the film's estimate, through the denoiser when the
// settings switch it on, and the filtering counts as frame time (a denoised frame is ready only
// once it is filtered).
#pragma once

#include <functional>

#include "accel/accel.h"
#include "image/image.h"
#include "render/frame_budget.h"
#include "render/render_settings.h"
#include "scene/scene.h"

namespace tuneray {

struct ShownFrame {
  const Image& image;
  const FrameResult& frame;  // the budget renderer's own account (render time, spp, rays)
  double time_ms = 0;        // cumulative: rendering plus, when denoising, filtering
  double spp = 0;            // cumulative samples per pixel
};

// Renders frames of `frame_ms` with the sampler the settings name, seeded with `seed`, and
// calls `after_frame` after each one until it returns false.
void run_shown_frames(const Scene& scene, const Accel& accel, const CameraDesc& camera,
                      const RenderSettings& settings, uint64_t seed, double frame_ms,
                      const std::function<bool(const ShownFrame&)>& after_frame);

}  // namespace tuneray
