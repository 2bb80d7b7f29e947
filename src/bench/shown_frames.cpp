#include "bench/shown_frames.h"

#include <memory>

#include "render/blue_noise_sampler.h"
#include "render/denoiser_frame.h"
#include "render/film.h"
#include "render/tile_renderer.h"

namespace tuneray {

void run_shown_frames(const Scene& scene, const Accel& accel, const CameraDesc& camera,
                      const RenderSettings& settings, uint64_t seed, double frame_ms,
                      const std::function<bool(const ShownFrame&)>& after_frame) {
  std::unique_ptr<Sampler> sampler = make_sampler(settings.quality.sampler, seed);
  TileRenderer renderer(scene, accel, camera, settings, *sampler);
  Film film(settings.width, settings.height);
  FrameBudgetRenderer budget(renderer, frame_ms);
  FrameResolver resolver;
  double t = 0, spp = 0;
  for (;;) {
    const FrameResult frame =
        budget.render_frame(film, settings.quality.denoise ? resolver.expected_ms() : 0.0);
    const Image image = resolver.resolve(renderer, film);
    t += frame.ms + (settings.quality.denoise ? resolver.last_ms() : 0.0);
    spp += frame.spp;
    if (!after_frame({image, frame, t, spp})) return;
  }
}

}  // namespace tuneray
