#include <gtest/gtest.h>

#include "accel/factory.h"
#include "common/temp_dir.h"
#include "scene/load.h"
#include "tuner/hardware_signature.h"
#include "tuner/tuning_db.h"
#include "tuning/tune_session.h"
#include "view/progressive_view.h"
#include "view/view_tuner.h"

namespace tuneray {
namespace {

// The viewer's tuner stores under the key `tune --size 64x36 --spp 1` uses, reports every
// frame but the two yardsticks, and measures those after the camera has stood still.
TEST(ViewTuner, TunesFrameByFrameUnderTheKeyOfTune) {
  testing::TempDir dir;
  Scene scene = load_scene("cornell");
  RenderSettings settings;
  settings.width = 64;
  settings.height = 36;
  ViewTuneOptions options;
  options.db_path = dir.file("tuning.db");
  TuneOptions as_tune;
  as_tune.width = 64;
  as_tune.height = 36;
  as_tune.spp = 1;
  const int frames = 12;
  {
    ViewTuner tuner(scene, settings, options);
    EXPECT_EQ(tuner.tuning_key(), tuning_key(as_tune));
    std::unique_ptr<Accel> first = make_accel("native");
    first->build({scene.positions.data(), scene.positions.size(), scene.triangles.data(),
                  scene.triangles.size()});
    ProgressiveView view(scene, *first, settings, scene.cameras[0], 5);
    tuner.set_camera(scene.cameras[0]);
    for (int f = 0; f < frames; ++f) {
      view.set_accel(tuner.next_accel());
      const std::string mode = tuner.status().mode;
      if (f == 8)
        EXPECT_EQ(mode, "default");
      else if (f == 9)
        EXPECT_EQ(mode, "native");
      else  // nothing is known about the first state: the tuner searches
        EXPECT_EQ(mode, "search") << "frame " << f;
      tuner.report(view.render_frame());
    }
    EXPECT_GT(tuner.status().default_ms, 0);
    EXPECT_GT(tuner.status().native_ms, 0);
    EXPECT_GT(tuner.status().speedup(), 0);
    EXPECT_EQ(tuner.failed_builds(), 0);
    // A camera change forgets the yardsticks until they are measured again.
    tuner.set_camera(scene.camera_paths[0].keyframes[1]);
    EXPECT_EQ(tuner.status().default_ms, 0);
  }
  tuner::TuningDb db(options.db_path);
  std::optional<int64_t> signature =
      db.find_signature(tuning_key(as_tune), tuner::hardware_signature());
  ASSERT_TRUE(signature.has_value());
  EXPECT_EQ(db.samples(*signature).size(), static_cast<size_t>(frames - 2));
}

}  // namespace
}  // namespace tuneray
