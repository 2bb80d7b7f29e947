// The film's own error estimate against the error measured by comparison with an independent,
// far more converged render: two independent ways to the same number.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

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

// The same numbers a third way: the reference's noise from its two half films
// (reference_noise_mse), which is what `bench peers` takes off our errors; an image's RMSE
// against the truth is then its measured RMSE less that, and its own estimate says what it is.
TEST(Film, HalvesEstimateTheReferenceNoiseThatComesOffTheMeasuredError) {
  Scene scene = load_scene("furnace_ggx");
  RenderSettings s;
  s.width = 96;  // the halves give one squared difference per value: enough values to average
  s.height = 72;
  s.seed = 1000;
  Film reference = render_film(scene, s, 256);
  const double from_halves =
      std::sqrt(reference_noise_mse(reference.resolve_half(0), reference.resolve_half(1)));
  EXPECT_NEAR(from_halves / reference.estimated_rmse(), 1.0, 0.06);
  for (uint64_t seed : {1, 2, 3}) {
    s.seed = seed;
    Film film = render_film(scene, s, 64);
    const double measured = compare_images(film.resolve(), reference.resolve()).rmse;
    const double truth = rmse_without_reference_noise(measured, from_halves * from_halves);
    EXPECT_LT(truth, 0.95 * measured);  // the reference's noise is a quarter of the image's
    EXPECT_NEAR(truth / film.estimated_rmse(), 1.0, 0.1) << "seed " << seed;
  }
}

TEST(Film, HalvesAreTheEvenAndOddSamples) {
  Film film(2, 1);
  film.add_sample(0, 0, Color(1, 2, 3), 0);
  film.add_sample(0, 0, Color(3, 2, 1), 1);
  film.add_sample(0, 0, Color(5, 6, 7), 2);
  film.add_sample(1, 0, Color(4, 4, 4), 1);
  const Image even = film.resolve_half(0), odd = film.resolve_half(1);
  EXPECT_EQ(even.at(0, 0), Color(3, 4, 5));
  EXPECT_EQ(odd.at(0, 0), Color(3, 2, 1));
  EXPECT_EQ(even.at(1, 0), Color(0.0f));  // no even sample yet
  EXPECT_EQ(odd.at(1, 0), Color(4, 4, 4));
  EXPECT_THROW(film.resolve_half(2), std::invalid_argument);
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
