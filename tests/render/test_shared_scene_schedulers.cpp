// The wavefront image is the tile image bit for bit with the tuned BVH on a real scene. The
// wavefront traces its camera rays as streams and the tile scheduler one ray at a time, so this
// checks at the level of the image that a stream gives each ray its single-ray hit. With the
// camera streams of before the fortieth session (one entry distance per pushed node for all its
// rays) conference's image differed.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "accel/tuned_bvh.h"
#include "render/blue_noise_sampler.h"
#include "render/film.h"
#include "render/tile_renderer.h"
#include "scene/load.h"

namespace tuneray {
namespace {

Image render_with(const Scene& scene, const Accel& accel, bool wavefront) {
  RenderSettings s;
  s.width = 320;
  s.height = 180;
  s.quality.wavefront = wavefront;
  const BlueNoiseSampler sampler(s.seed);
  TileRenderer renderer(scene, accel, scene.cameras.at(0), s, sampler);
  Film film(s.width, s.height);
  renderer.render_pass(film, 0, 2);
  return film.resolve();
}

TEST(SharedSceneSchedulers, TunedWavefrontGivesTheTileImageOnConference) {
  const std::string dir = std::string(TUNERAY_SHARED_DIR) + "/scenes";
  if (!std::filesystem::exists(dir + "/conference/conference.obj"))
    GTEST_SKIP() << "shared scene not found: " << dir << "/conference/conference.obj";
  const Scene scene =
      load_scene(std::string(TUNERAY_SOURCE_DIR) + "/scenes/conference.json", {dir});
  TunedBvhAccel tuned(
      parse_bvh_config("branching=2,sah_block_size=4,min_leaf=4,max_leaf=28,static=1,optimal_"
                       "collapse=1,reinsert=1"));
  tuned.build({scene.positions.data(), scene.positions.size(), scene.triangles.data(),
               scene.triangles.size()});
  const Image tiles = render_with(scene, tuned, false);
  const Image wave = render_with(scene, tuned, true);
  size_t differing = 0;
  for (int y = 0; y < tiles.height(); ++y)
    for (int x = 0; x < tiles.width(); ++x) differing += !(tiles.at(x, y) == wave.at(x, y));
  EXPECT_EQ(differing, 0u);
}

}  // namespace
}  // namespace tuneray
