#include "view/progressive_view.h"

#include <tbb/parallel_for.h>

#include <cmath>

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
  resolver_.camera_moved();
  film_.clear();
  film_samples_ = 0;
}

FrameResult ProgressiveView::render_frame() {
  // The shown frame is resolved after rendering (filtered when denoising): its time comes out
  // of the same budget.
  FrameResult frame =
      budget_->render_frame(film_, settings_.quality.denoise ? resolver_.expected_ms() : 0.0);
  film_samples_ += static_cast<double>(frame.stats.samples);
  return frame;
}

void ProgressiveView::set_camera(const CameraDesc& camera) {
  camera_ = camera;
  // Moving the camera keeps the integrator and its lights: only the film and the budget's
  // per-film bookkeeping start over. Whether path reuse pays is the scene's: that is kept.
  renderer_->set_camera(camera);
  const ReuseSwitch reuse = budget_->reuse_switch();
  budget_.emplace(*renderer_, frame_ms_, reuse);
  resolver_.camera_moved();
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

Image ProgressiveView::image() const {
  return resolver_.resolve(*renderer_, film_);
}

std::vector<uint8_t> ProgressiveView::display_bytes(float exposure) const {
  const float scale = std::exp2(exposure);
  if (!encoder_ || encoder_->exposure_scale() != scale) encoder_.emplace(scale);
  const DisplayEncoder& encoder = *encoder_;
  const int width = film_.width();
  std::vector<uint8_t> bytes(static_cast<size_t>(width) * film_.height() * 3);
  // Rows in parallel: at 640x360 encoding is a visible part of a 30 fps frame otherwise.
  auto encode = [&](const auto& pixel) {
    tbb::parallel_for(0, film_.height(), [&](int y) {
      uint8_t* out = bytes.data() + static_cast<size_t>(y) * width * 3;
      for (int x = 0; x < width; ++x) {
        const Color c = pixel(x, y);
        *out++ = encoder.encode(c.x);
        *out++ = encoder.encode(c.y);
        *out++ = encoder.encode(c.z);
      }
    });
  };
  if (settings_.quality.denoise) {
    const Image shown = image();
    encode([&](int x, int y) { return shown.at(x, y); });
  } else {
    // The film's means directly: no resolved image to allocate every frame.
    encode([&](int x, int y) {
      const uint32_t n = film_.samples(x, y);
      return n > 0 ? film_.sum(x, y) / static_cast<float>(n) : Color(0.0f);
    });
  }
  return bytes;
}

}  // namespace tuneray
