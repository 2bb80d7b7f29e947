#include <gtest/gtest.h>

#include "accel/factory.h"
#include "common/temp_dir.h"
#include "image/io.h"
#include "offline_render.h"
#include "scene/load.h"
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

// With the denoiser switched on, the view shows the filtered film: closer to the converged
// offline render than the raw film at the same low sample count.
TEST_F(ProgressiveViewTest, DenoisedViewIsCloserToTheConvergedImage) {
  const CameraDesc& camera = scene_.cameras[0];
  std::vector<uint8_t> converged = testing::offline_display_bytes(scene_, camera, 64, 36, 256);
  RenderSettings raw_settings = settings_;
  raw_settings.quality.adaptive = false;
  ProgressiveView raw(scene_, *accel_, raw_settings, camera, 5);
  RenderSettings denoised_settings = raw_settings;
  denoised_settings.quality.denoise = true;
  ProgressiveView denoised(scene_, *accel_, denoised_settings, camera, 5);
  while (raw.film_spp() < 4) raw.render_frame();
  while (denoised.film_spp() < 4) denoised.render_frame();
  double raw_error = testing::display_rmse(raw.display_bytes(0), converged);
  double denoised_error = testing::display_rmse(denoised.display_bytes(0), converged);
  EXPECT_LT(denoised_error, 0.8 * raw_error) << raw_error << " " << denoised_error;
  // The key's path: switching the option on starts a new film that shows filtered frames.
  QualityOptions q = raw.settings().quality;
  q.denoise = true;
  raw.set_quality(q);
  EXPECT_EQ(raw.film_spp(), 0);
  EXPECT_TRUE(raw.settings().quality.denoise);
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
