#include "view/progressive_view.h"

#include <cmath>

#include "image/tonemap.h"
#include "render/blue_noise_sampler.h"

namespace tuneray {

ProgressiveView::ProgressiveView(const Scene& scene, const Accel& accel,
                                 const RenderSettings& settings, const CameraDesc& camera,
                                 double frame_ms)
    : scene_(scene),
      accel_(&accel),
      settings_(settings),
      camera_(camera),
      frame_ms_(frame_ms),
      film_(settings.width, settings.height) {
  restart();
}

void ProgressiveView::restart() {
  // The budget renderer refers to the tile renderer, which refers to the sampler: drop them in
  // that order before building new ones.
  budget_.reset();
  renderer_.reset();
  sampler_ = make_sampler(settings_.quality.sampler, settings_.seed);
  renderer_.emplace(scene_, *accel_, camera_, settings_, *sampler_);
  budget_.emplace(*renderer_, frame_ms_);
  film_.clear();
  film_samples_ = 0;
}

FrameResult ProgressiveView::render_frame() {
  FrameResult frame = budget_->render_frame(film_);
  film_samples_ += static_cast<double>(frame.stats.samples);
  return frame;
}

void ProgressiveView::set_camera(const CameraDesc& camera) {
  camera_ = camera;
  // Moving the camera keeps the integrator and its lights: only the film and the budget's
  // per-film bookkeeping start over.
  renderer_->set_camera(camera);
  budget_.emplace(*renderer_, frame_ms_);
  film_.clear();
  film_samples_ = 0;
}

void ProgressiveView::set_accel(const Accel& accel) {
  if (&accel == accel_) return;
  accel_ = &accel;
  renderer_.emplace(scene_, accel, camera_, settings_, *sampler_);
}

void ProgressiveView::set_quality(const QualityOptions& quality) {
  settings_.quality = quality;
  restart();
}

std::vector<uint8_t> ProgressiveView::display_bytes(float exposure) const {
  Image image = film_.resolve();
  const float scale = std::exp2(exposure);
  std::vector<uint8_t> bytes(static_cast<size_t>(image.width()) * image.height() * 3);
  size_t i = 0;
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) {
      const Color& c = image.at(x, y);
      bytes[i++] = encode_display_byte(c.x, scale, false);
      bytes[i++] = encode_display_byte(c.y, scale, false);
      bytes[i++] = encode_display_byte(c.z, scale, false);
    }
  return bytes;
}

}  // namespace tuneray
