// The automatic path-reuse choice (render/reuse_switch.h): the decision rule on made-up moments,
// the moments of real passes against the films' own variance estimates, and the wiring into
// fixed-count and frame-budget rendering.
#include <gtest/gtest.h>

#include <cmath>

#include "render/frame_budget.h"
#include "render/reuse_switch.h"
#include "render_helpers.h"

namespace tuneray {
namespace {

// Moments of `samples` samples whose variances per sample are `own` and `reused`, from passes
// that cost `cost_ratio` times what they would without reuse.
ReuseMoments moments(double own, double reused, uint64_t samples, double cost_ratio) {
  ReuseMoments m;
  m.traced_ms = 10 * cost_ratio;
  m.pool_ms = 10 * (cost_ratio - 1);
  m.samples = samples;
  m.weights = static_cast<double>(samples);
  m.own = own * static_cast<double>(samples);
  m.removed = (own - reused) * static_cast<double>(samples);
  return m;
}

TEST(ReuseSwitch, MomentsCompareDeviationsFromThePixelsEarlierMean) {
  // One pixel with samples 1 and 3 (mean 2, n = 2) in every channel, then a sample whose own
  // estimate is 5 and reused one 3: deviations 3 and 1 per channel.
  Film film(1, 1);
  film.add_sample(0, 0, Color(1.0f), 0);
  film.add_sample(0, 0, Color(3.0f), 1);
  ReuseMoments m;
  m.add_sample(film, 0, 0, Color(5.0f), Color(3.0f), 100.0f);
  EXPECT_EQ(m.samples, 1u);
  EXPECT_DOUBLE_EQ(m.own_variance(), 27.0 * 2 / 3);    // 3 x 3^2, n / (n + 1)
  EXPECT_DOUBLE_EQ(m.reused_variance(), 18.0 - 24.0);  // less 27 - 3 x 1^2
  // A deviation beyond the clip counts at the clip: sqrt(27) -> 3.
  ReuseMoments clipped;
  clipped.add_sample(film, 0, 0, Color(5.0f), Color(2.0f), 3.0f);
  EXPECT_DOUBLE_EQ(clipped.own_variance(), 6.0);
  EXPECT_DOUBLE_EQ(clipped.reused_variance(), 6.0 - 9.0);
  // A pixel without samples has no mean to compare with.
  Film empty(1, 1);
  ReuseMoments none;
  none.add_sample(empty, 0, 0, Color(5.0f), Color(3.0f), 100.0f);
  EXPECT_EQ(none.samples, 0u);
  EXPECT_DOUBLE_EQ(none.own_variance(), 0.0);
  m.add(clipped);
  EXPECT_EQ(m.samples, 2u);
  EXPECT_DOUBLE_EQ(m.own_variance(), (18.0 + 6.0) / 2);
  EXPECT_DOUBLE_EQ(m.cost_ratio(), 0.0);  // no time yet
  m.traced_ms = 3;
  m.pool_ms = 1;
  EXPECT_DOUBLE_EQ(m.cost_ratio(), 1.5);
  m.pool_ms = 3;  // nothing but pools: no cost without reuse to compare with
  EXPECT_DOUBLE_EQ(m.cost_ratio(), 0.0);
  EXPECT_FLOAT_EQ(ReuseMoments::clip_length(0.5), 4.0f);
  EXPECT_TRUE(std::isinf(ReuseMoments::clip_length(0.0)));
}

TEST(ReuseSwitch, PixelMomentsSumEachPixelsDeviation) {
  // A 2x1 film: pixel 1 has samples 1 and 3 (mean 2); a sample of own estimate 5 (deviation 3
  // per channel, 27 in all, 18 after n / (n + 1)) and reused 3 (1 per channel, 3 in all).
  Film film(2, 1);
  film.add_sample(1, 0, Color(1.0f), 0);
  film.add_sample(1, 0, Color(3.0f), 1);
  ReusePixelMoments pixels(2);
  ReuseMoments m;
  m.add_sample(film, 1, 0, Color(5.0f), Color(3.0f), 100.0f, &pixels);
  m.add_sample(film, 0, 0, Color(5.0f), Color(3.0f), 100.0f, &pixels);  // no mean: not counted
  ReusePixelMoments::Deviations d = pixels.deviations();
  EXPECT_EQ(d.pixels, 1u);
  EXPECT_NEAR(d.own, std::sqrt(18.0), 1e-5);
  EXPECT_DOUBLE_EQ(d.reused, 0.0);  // 18 - 24 < 0 counts as none
  // By hand: sigma 2 and 1 without reuse, 1 and 1 with it, over two samples each.
  ReusePixelMoments hand(3);
  hand.add(0, 4, 3);
  hand.add(0, 4, 3);
  hand.add(2, 1, 0);
  hand.add(2, 1, 0);
  d = hand.deviations();
  EXPECT_EQ(d.pixels, 2u);
  EXPECT_DOUBLE_EQ(d.own, 3.0);
  EXPECT_DOUBLE_EQ(d.reused, 2.0);
}

TEST(ReuseSwitch, PixelDeviationsOfAWholeFilmMatchThePixelByPixelSums) {
  // 37 pixels (four blocks of eight and a tail), some without samples, some whose reused
  // variance would be negative: the sums agree with each pixel's own arithmetic in double.
  ReusePixelMoments pixels(37);
  double own = 0, reused = 0;
  size_t with_samples = 0;
  for (size_t p = 0; p < 37; ++p) {
    const int count = static_cast<int>(p % 5);  // 0 .. 4 samples
    const double o = 0.5 + static_cast<double>((p * 7) % 11), r = (p % 3 == 0) ? o + 1 : 0.3 * o;
    for (int k = 0; k < count; ++k) pixels.add(p, o, o - r);
    if (count == 0) continue;
    ++with_samples;
    // The film's sums are floats: take them as stored.
    const double own_sum = static_cast<float>(static_cast<float>(o) * count);
    const double removed_sum = static_cast<float>(static_cast<float>(o - r) * count);
    own += std::sqrt(own_sum / count);
    reused += std::sqrt(std::max(0.0, (own_sum - removed_sum) / count));
  }
  const ReusePixelMoments::Deviations d = pixels.deviations();
  EXPECT_EQ(d.pixels, with_samples);
  EXPECT_NEAR(d.own, own, 1e-5 * own);
  EXPECT_NEAR(d.reused, reused, 1e-5 * reused);
}

TEST(ReuseSwitch, WithAdaptiveSamplingThePixelsDeviationsDecide) {
  // One very noisy pixel reuse leaves alone (variance 100) and ten whose variance it cuts from
  // 1 to 0.01, at 1.5 times the cost. The mean variance falls only to 0.91 of what it was
  // (1.37 per unit of time: off); the sum of deviations from 20 to 11 ((11 / 20)^2 x 1.5 =
  // 0.45: on), and with adaptive sampling the latter is what the error follows.
  ReusePixelMoments pixels(11);
  pixels.add(0, 100, 0);
  for (size_t p = 1; p <= 10; ++p) pixels.add(p, 1, 0.99);
  const ReuseMoments mean = moments(110.0 / 11, 100.1 / 11, 10000, 1.5);
  ReuseSwitch uniform, adaptive;
  uniform.after_reuse_pass(mean, 2.0);
  adaptive.after_reuse_pass(mean, 2.0, 0.0, &pixels);
  EXPECT_FALSE(uniform.on());
  EXPECT_TRUE(adaptive.on());
}

TEST(ReuseSwitch, StartsOn) {
  ReuseSwitch s;
  EXPECT_TRUE(s.next_on(0.0));
  EXPECT_TRUE(s.on());
  EXPECT_FALSE(s.probing());
}

TEST(ReuseSwitch, StaysOnWhereTheVarianceFallsMoreThanTheCostRises) {
  // Variance 0.4 of 1 at twice the cost: 0.8 of the squared error per unit of time.
  ReuseSwitch s;
  s.after_reuse_pass(moments(1.0, 0.4, 10000, 2.0), 1.5);
  EXPECT_TRUE(s.on());
  EXPECT_FALSE(s.probing());
  EXPECT_TRUE(s.next_on(1.5));
  // Later passes may show otherwise: they weigh as much as the first, and at four times the
  // cost the two together (three times) give 1.2.
  s.after_reuse_pass(moments(1.0, 0.4, 10000, 4.0), 3.0);
  EXPECT_FALSE(s.on());
}

TEST(ReuseSwitch, OffWhereItDoesNotPayAndProbedAgainWhenTheSamplesDouble) {
  ReuseSwitch s;
  s.after_reuse_pass(moments(1.0, 0.4, 10000, 3.0), 3.0);  // 1.2 of the error per time
  EXPECT_FALSE(s.on());
  EXPECT_TRUE(s.probing());
  EXPECT_FALSE(s.next_on(5.9));
  EXPECT_TRUE(s.next_on(6.0));
  // A probe that finds it paying after all (both passes together: variance 0.25 at 2.375
  // times the cost, 0.59): on.
  s.after_reuse_pass(moments(1.0, 0.1, 10000, 1.75), 7.0);
  EXPECT_TRUE(s.on());
  // Whole passes that cost more than the pools' share says: the larger ratio decides (variance
  // 0.4 at 2.5 times the cost, where the pools alone say 2).
  ReuseSwitch whole;
  whole.after_reuse_pass(moments(1.0, 0.4, 10000, 2.0), 1.5, 1.5);
  EXPECT_TRUE(whole.on());
  whole.after_reuse_pass(moments(1.0, 0.4, 10000, 2.0), 3.0, 2.5);
  EXPECT_FALSE(whole.on());
  // A probe that adds too few samples to move the moments is no new decision; it only sets
  // the next probe (at twice the film's samples).
  s.after_reuse_pass(moments(0.0, 0.0, 100, 1.0), 20.0);
  EXPECT_TRUE(s.on());
  s.after_reuse_pass(moments(1.0, 1.0, 10000, 4.0), 30.0);
  EXPECT_FALSE(s.on());
  s.after_reuse_pass(moments(1.0, 0.0, 100, 1.0), 70.0);
  EXPECT_FALSE(s.on());
  EXPECT_FALSE(s.next_on(139.0));
  EXPECT_TRUE(s.next_on(140.0));
  // Nothing gained (no diffuse first hits) at hardly any cost: off.
  ReuseSwitch level;
  level.after_reuse_pass(moments(1.0, 1.0, 10000, 1.02), 2.0);
  EXPECT_FALSE(level.on());
}

TEST(ReuseSwitch, StaysOnUntilItHasEnoughSamplesAndACost) {
  // Moments that say off, but too few of them, then enough without a time.
  ReuseSwitch s;
  s.after_reuse_pass(moments(1.0, 1.0, ReuseSwitch::kMinSamples - 1, 2.0), 1.2);
  EXPECT_TRUE(s.on());
  // Enough samples but no time measured (a pass too short for the clock): on.
  ReuseMoments untimed = moments(1.0, 1.0, ReuseSwitch::kMinSamples, 2.0);
  untimed.traced_ms = untimed.pool_ms = 0;
  ReuseSwitch t;
  t.after_reuse_pass(untimed, 1.2);
  EXPECT_TRUE(t.on());
  t.after_reuse_pass(moments(1.0, 1.0, 1, 2.0), 1.4);  // now both: off
  EXPECT_FALSE(t.on());
  // With adaptive sampling, pixels with a mean are needed too (a new view's first pass has none).
  ReuseSwitch v;
  const ReusePixelMoments no_pixels(4);
  v.after_reuse_pass(moments(1.0, 1.0, ReuseSwitch::kMinSamples, 2.0), 1.0, 0.0, &no_pixels);
  EXPECT_TRUE(v.on());
}

// The point-lit box (render_helpers.h) on Embree's BVH.
struct PointLitBox {
  Scene scene = testing::point_lit_box();
  EmbreeNativeAccel accel;
  PointLitBox() {
    accel.build({scene.positions.data(), scene.positions.size(), scene.triangles.data(),
                 scene.triangles.size()});
  }
};

RenderSettings box_settings() {
  RenderSettings s;
  s.width = 40;
  s.height = 30;
  s.max_bounces = 8;
  s.seed = 3;
  s.quality.path_reuse = QualityOptions::kReusePool;
  s.quality.path_reuse_auto = false;  // in every pass, fixed counts too
  return s;
}

// Mean over pixels of the variance of one sample, r, g and b summed, as the film estimates it.
double film_sample_variance(const Film& film) {
  double sum = 0;
  for (int y = 0; y < film.height(); ++y)
    for (int x = 0; x < film.width(); ++x)
      sum += 3.0 * film.variance_of_mean(x, y) * film.samples(x, y);
  return sum / (film.width() * film.height());
}

TEST(ReuseSwitch, PassMomentsAgreeWithEachFilmsVariance) {
  // The moments of reuse passes against an independent estimate: the variance among each
  // pixel's samples of a film rendered with reuse, and of one rendered without it from the same
  // random numbers (whose samples are the reuse passes' own estimates).
  const PointLitBox box;
  const Scene& scene = box.scene;
  const EmbreeNativeAccel& accel = box.accel;
  RenderSettings off_settings = box_settings();
  off_settings.quality.path_reuse = 0;
  const PcgSampler sampler(7);
  TileRenderer with(scene, accel, scene.cameras.at(0), box_settings(), sampler);
  TileRenderer without(scene, accel, scene.cameras.at(0), off_settings, sampler);
  Film reused(40, 30), plain(40, 30);
  ReuseMoments m;
  uint64_t reused_samples = 0;
  for (uint32_t i = 0; i < 48; ++i) {
    const PassStats pass = with.render_pass(reused, i, 1);
    m.add(pass.reuse);
    reused_samples += pass.reused_samples;
    EXPECT_EQ(without.render_pass(plain, i, 1).reused_samples, 0u);
  }
  EXPECT_EQ(reused_samples, 48u * 40 * 30);
  EXPECT_EQ(m.samples, 47u * 40 * 30);  // the first pass's pixels had no mean before
  // Clipping takes most of both variances here (the walls next to the point light), and alike:
  // the share of the variance reuse removes is the films' share.
  const double films_share = film_sample_variance(reused) / film_sample_variance(plain);
  EXPECT_NEAR(m.reused_variance() / m.own_variance(), films_share, 0.1 * films_share);
  EXPECT_LT(m.reused_variance(), 0.6 * m.own_variance());
}

TEST(ReuseSwitch, FixedSampleCountsTraceWithoutReuse) {
  const Scene scene = testing::point_lit_box();
  RenderSettings automatic = box_settings(), off = box_settings();
  automatic.quality.path_reuse_auto = true;
  off.quality.path_reuse = 0;
  PassStats stats;
  const Image a = testing::render_image(scene, automatic, 4, &stats);
  const Image b = testing::render_image(scene, off, 4);
  EXPECT_EQ(stats.reused_samples, 0u);
  for (int y = 0; y < a.height(); ++y)
    for (int x = 0; x < a.width(); ++x) ASSERT_EQ(a.at(x, y), b.at(x, y)) << x << " " << y;
}

TEST(ReuseSwitch, FrameBudgetRenderingStartsWithReuseAndMeasuresIt) {
  const PointLitBox box;
  const Scene& scene = box.scene;
  const EmbreeNativeAccel& accel = box.accel;
  for (const int bounces : {8, 1}) {
    RenderSettings s = box_settings();
    s.max_bounces = bounces;
    s.quality.path_reuse_auto = true;
    const PcgSampler sampler(5);
    TileRenderer renderer(scene, accel, scene.cameras.at(0), s, sampler);
    Film film(s.width, s.height);
    FrameBudgetRenderer budget(renderer, 5.0);
    EXPECT_EQ(budget.reuse_auto(), bounces > 1) << bounces;  // one bounce: nothing to share
    const PassStats first = budget.render_frame(film).stats;
    PassStats total = first;
    for (int frame = 0; frame < 200 && total.samples < 8u * 40 * 30; ++frame)
      total.accumulate(budget.render_frame(film).stats);
    if (bounces == 1) {
      EXPECT_EQ(total.reused_samples, 0u);
      continue;
    }
    EXPECT_GT(first.reused_samples, 0u);  // from the first pass on
    // The switch's moments are all those of the passes with reuse, less the samples of pixels
    // that had none before (the first pass's).
    EXPECT_EQ(budget.reuse_switch().moments().samples, total.reuse.samples);
    EXPECT_GT(total.reuse.samples, 0u);
    EXPECT_LT(total.reuse.samples, total.reused_samples);
    // And their costs: the pools' connection rays are a share of the passes' time.
    EXPECT_GT(total.reuse.pool_ms, 0.0);
    EXPECT_LT(total.reuse.pool_ms, total.reuse.traced_ms);
    EXPECT_GT(total.reuse.cost_ratio(), 1.0);
  }
}

TEST(ReuseSwitch, AFrameBudgetRendererStartsFromTheSwitchItIsGiven) {
  // A view's camera moved: the switch of the scene's earlier view, which found reuse not to pay
  // and probes again at 2,000 spp, is where the new one starts.
  const PointLitBox box;
  const Scene& scene = box.scene;
  const EmbreeNativeAccel& accel = box.accel;
  RenderSettings s = box_settings();
  s.quality.path_reuse_auto = true;
  ReuseSwitch earlier;
  earlier.after_reuse_pass(moments(1.0, 1.0, 10000, 2.0), 1000.0);
  ASSERT_FALSE(earlier.on());
  const PcgSampler sampler(5);
  TileRenderer renderer(scene, accel, scene.cameras.at(0), s, sampler);
  Film film(s.width, s.height);
  FrameBudgetRenderer budget(renderer, 5.0, earlier);
  PassStats total;
  for (int frame = 0; frame < 3; ++frame) total.accumulate(budget.render_frame(film).stats);
  EXPECT_GT(total.samples, 0u);
  EXPECT_EQ(total.reused_samples, 0u);
  EXPECT_FALSE(budget.reuse_switch().on());
  // A fresh one starts on.
  Film fresh_film(s.width, s.height);
  FrameBudgetRenderer fresh(renderer, 5.0);
  EXPECT_GT(fresh.render_frame(fresh_film).stats.reused_samples, 0u);
}

}  // namespace
}  // namespace tuneray
