#include <gtest/gtest.h>

#include "accel/factory.h"
#include "common/temp_dir.h"
#include "image/io.h"
#include "image/metrics.h"
#include "offline_render.h"
#include "render/film.h"
#include "render/sampler.h"
#include "render/tile_renderer.h"
#include "scene/load.h"
#include "view/display_encoder.h"
#include "view/display_image.h"
#include "view/progressive_view.h"

namespace tuneray {
namespace {

class ProgressiveViewTest : public ::testing::Test {
 protected:
  ProgressiveViewTest() : scene_(load_scene("cornell")), accel_(make_accel("native")) {
    accel_->build({scene_.positions.data(), scene_.positions.size(), scene_.triangles.data(),
                   scene_.triangles.size()});
    settings_.width = 64;
    settings_.height = 36;
  }
  Scene scene_;
  std::unique_ptr<Accel> accel_;
  RenderSettings settings_;
};

TEST_F(ProgressiveViewTest, FilmCountsEveryFramesSamplesAndRestartsOnChanges) {
  ProgressiveView view(scene_, *accel_, settings_, scene_.cameras[0], 5);
  double spp = 0;
  for (int i = 0; i < 4; ++i) spp += view.render_frame().spp;
  EXPECT_GT(spp, 0);
  EXPECT_NEAR(view.film_spp(), spp, 1e-9);
  view.set_camera(scene_.camera_paths[0].keyframes[1]);
  EXPECT_EQ(view.film_spp(), 0);
  EXPECT_EQ(view.camera().position, scene_.camera_paths[0].keyframes[1].position);
  double after = view.render_frame().spp;
  EXPECT_NEAR(view.film_spp(), after, 1e-9);
  QualityOptions q = view.settings().quality;
  q.adaptive = !q.adaptive;
  view.set_quality(q);
  EXPECT_EQ(view.film_spp(), 0);
  EXPECT_EQ(view.settings().quality.adaptive, q.adaptive);
}

// The view converges to what an offline render of its camera shows, and not to another camera.
TEST_F(ProgressiveViewTest, ConvergesToTheOfflineRenderOfItsCamera) {
  const CameraDesc& camera = scene_.camera_paths[0].keyframes[2];
  ProgressiveView view(scene_, *accel_, settings_, scene_.cameras[0], 20);
  view.set_camera(camera);
  while (view.film_spp() < 256) view.render_frame();
  std::vector<uint8_t> shown = view.display_bytes(0);
  double same =
      testing::display_rmse(shown, testing::offline_display_bytes(scene_, camera, 64, 36, 256));
  double other = testing::display_rmse(
      shown, testing::offline_display_bytes(scene_, scene_.cameras[0], 64, 36, 256));
  EXPECT_LT(same, 0.04);
  EXPECT_GT(other, 3 * same);
}

// As the window shows it (8-bit sRGB, clamped).
std::vector<uint8_t> display(const Image& image) {
  DisplayEncoder encoder(1.0f);
  std::vector<uint8_t> bytes;
  for (size_t i = 0; i < image.pixel_count(); ++i)
    for (float c : {image.data()[i].x, image.data()[i].y, image.data()[i].z})
      bytes.push_back(encoder.encode(c));
  return bytes;
}

// With the denoiser switched on, the view shows the filtered film, which on screen is closer to
// the converged image than the same film unfiltered (about 0.7x at a few spp; the bound is
// 0.9x; in linear RMSE the raw light's rim dominates both).
TEST_F(ProgressiveViewTest, DenoisedViewIsCloserToTheConvergedImage) {
  const CameraDesc& camera = scene_.cameras[0];
  PcgSampler sampler(7);
  TileRenderer offline(scene_, *accel_, camera, settings_, sampler);
  Film converged_film(settings_.width, settings_.height);
  offline.render_pass(converged_film, 0, 512);
  const Image converged = converged_film.resolve();

  RenderSettings settings = settings_;
  settings.quality.adaptive = false;
  settings.quality.denoise = true;
  ProgressiveView view(scene_, *accel_, settings, camera, 5);
  while (view.film_spp() < 2) view.render_frame();
  const std::vector<uint8_t> target = display(converged);
  const double raw = testing::display_rmse(display(view.raw_image()), target);
  const double shown = testing::display_rmse(display(view.image()), target);
  EXPECT_LT(shown, 0.9 * raw) << raw << " " << shown;
  // The key's path: switching the option off starts a new film that shows the raw estimate.
  QualityOptions q = view.settings().quality;
  q.denoise = false;
  view.set_quality(q);
  EXPECT_EQ(view.film_spp(), 0);
  view.render_frame();
  EXPECT_EQ(compare_images(view.image(), view.raw_image()).rmse, 0.0);
}

TEST(DisplayImage, PngHoldsTheShownBytes) {
  testing::TempDir dir;
  std::vector<uint8_t> bytes(4 * 3 * 3);
  for (size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<uint8_t>(i * 7);
  write_display_image(dir.file("shot.png"), bytes, 4, 3);
  ReadOptions raw;
  raw.srgb_to_linear = false;
  Image back = read_image(dir.file("shot.png"), raw);
  ASSERT_EQ(back.width(), 4);
  ASSERT_EQ(back.height(), 3);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 4; ++x)
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(back.at(x, y)[c] * 255.0f, bytes[(y * 4 + x) * 3 + c], 1e-3f);
  EXPECT_THROW(write_display_image(dir.file("bad.png"), bytes, 5, 3), std::invalid_argument);
}

}  // namespace
}  // namespace tuneray
