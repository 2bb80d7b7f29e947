// What the viewer window shows, without the window: a scene rendered progressively in
// frame-budget mode from a camera that may move. Every camera or quality change starts a new
// film; frames in between keep accumulating into it. The viewer, its scripted mode and the
// tests all drive this one class.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "accel/accel.h"
#include "image/image.h"
#include "render/denoiser_frame.h"
#include "render/film.h"
#include "render/frame_budget.h"
#include "render/render_settings.h"
#include "render/sampler.h"
#include "render/tile_renderer.h"
#include "scene/scene.h"
#include "view/display_encoder.h"

namespace tuneray {

class ProgressiveView {
 public:
  // `scene` and `accel` (built over the scene) must outlive the view.
  ProgressiveView(const Scene& scene, const Accel& accel, const RenderSettings& settings,
                  const CameraDesc& camera, double frame_ms);

  // One frame of the budget, added to the film.
  FrameResult render_frame();

  void set_camera(const CameraDesc& camera);
  // Renders the next frames with another accelerator over the same scene (the tuner's choice):
  // the image does not change, so the film keeps its samples.
  void set_accel(const Accel& accel);
  const CameraDesc& camera() const { return camera_; }
  // Switches quality options (adaptive sampling, sampler, ...): a new film, since samples of
  // different generators or placements do not belong in one estimate.
  void set_quality(const QualityOptions& quality);
  const RenderSettings& settings() const { return settings_; }
  double frame_ms() const { return frame_ms_; }

  // Samples per pixel in the film (mean over pixels).
  double film_spp() const { return film_samples_ / pixel_count(); }
  // The film's estimate, through the denoiser when the quality options switch it on.
  Image image() const;
  // The film's own estimate, unfiltered (unbiased) whatever the options say.
  Image raw_image() const { return film_.resolve(); }
  // The image as the window shows it: 8-bit sRGB, 3 bytes a pixel, rows top to bottom, scaled
  // by 2^exposure and clamped (what `render --out F.png` writes).
  std::vector<uint8_t> display_bytes(float exposure) const;

 private:
  double pixel_count() const { return static_cast<double>(settings_.width) * settings_.height; }
  // Rebuilds what depends on the settings and camera, and empties the film.
  void restart();

  const Scene& scene_;
  const Accel* accel_;
  RenderSettings settings_;
  CameraDesc camera_;
  double frame_ms_;
  std::unique_ptr<Sampler> sampler_;
  // The budget renderer refers to the tile renderer, which refers to the sampler and the
  // accelerator. A new accelerator is emplaced in the same storage, so the budget renderer's
  // reference (and its per-film bookkeeping) carries over to it.
  std::optional<TileRenderer> renderer_;
  std::optional<FrameBudgetRenderer> budget_;
  Film film_;
  double film_samples_ = 0;
  mutable std::optional<DisplayEncoder> encoder_;  // of the last exposure shown
  mutable FrameResolver resolver_;  // keeps the denoiser's guides while the camera stays
};

}  // namespace tuneray
