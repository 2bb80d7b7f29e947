// The film's own error estimate against the error measured by comparison with an independent,
// far more converged render: two independent ways to the same number.
#include <gtest/gtest.h>

#include <cmath>

#include "image/metrics.h"
#include "render/film.h"
#include "render_helpers.h"
#include "scene/load.h"

namespace tuneray {
namespace {

Film render_film(const Scene& scene, const RenderSettings& s, uint32_t spp) {
  return testing::render_film(scene, s, PcgSampler(s.seed), spp);
}

// E[RMSE^2] of an image against its limit is the mean variance of its pixel means. Against an
// independent reference with its own noise, the measured RMSE^2 adds the reference's.
TEST(Film, EstimatedRmseMatchesTheMeasuredError) {
  Scene scene = load_scene("furnace_ggx");
  RenderSettings s;
  s.width = 48;
  s.height = 36;
  s.seed = 1000;
  Film reference = render_film(scene, s, 2048);
  const double ref_error = reference.estimated_rmse();
  for (uint64_t seed : {1, 2, 3}) {
    s.seed = seed;
    Film film = render_film(scene, s, 16);
    double estimated =
        std::sqrt(film.estimated_rmse() * film.estimated_rmse() + ref_error * ref_error);
    double measured = compare_images(film.resolve(), reference.resolve()).rmse;
    EXPECT_NEAR(measured / estimated, 1.0, 0.1) << "seed " << seed;
  }
}

TEST(Film, EstimatedRmseOfAConstantImageIsZero) {
  Film film(3, 2);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 3; ++x)
      for (int i = 0; i < 4; ++i) film.add(x, y, Color(0.5f), 1, SquareSum::of(Color(0.5f)));
  EXPECT_NEAR(film.estimated_rmse(), 0.0, 1e-9);
  EXPECT_NEAR(film.mean_value_length(), 0.5 * std::sqrt(3.0), 1e-6);
  film.clear();
  EXPECT_EQ(film.mean_value_length(), 0.0);
  EXPECT_EQ(film.samples(2, 1), 0u);
}

}  // namespace
}  // namespace tuneray
