// `tune` with native Embree in the search space: tuning keys name the space and the scheduler,
// every search measures native, and every camera reports native measured beside the default and
// the chosen configuration.
#include <gtest/gtest.h>

#include "tuning_fixtures.h"

#include <set>
#include <string>

#include "tuner/hardware_signature.h"
#include "tuner/temp_path.h"
#include "tuner/tuning_db.h"
#include "tuning/accel_choice.h"
#include "tuning/bvh_space.h"
#include "tuning/tune_session.h"

namespace tuneray {
namespace {

TuneOptions tiny_session(const std::string& db) {
  TuneOptions o = testing::tiny_tune_session(db);
  o.baseline_repeats = 3;
  o.epsilon = 1;
  return o;
}

TEST(TuneNative, TuningKeyNamesTheSpaceAndTheScheduler) {
  TuneOptions o;
  EXPECT_TRUE(o.native_in_space);
  EXPECT_EQ(o.wavefront, QualityOptions{}.wavefront);  // the renderer's default scheduler
  EXPECT_EQ(tuning_key(o), "backend+bvh/render/320x180/1spp/3b/wavefront");
  // The BVH-only space on tiles keeps the key older databases were written with.
  TuneOptions legacy = o;
  legacy.native_in_space = false;
  legacy.wavefront = false;
  EXPECT_EQ(tuning_key(legacy), "bvh/render/320x180/1spp/3b");
  std::set<std::string> keys;
  for (bool native : {false, true})
    for (bool wave : {false, true})
      for (bool work : {false, true}) {
        TuneOptions k = o;
        k.native_in_space = native;
        k.wavefront = wave;
        k.work_sizes = work;
        keys.insert(tuning_key(k));
      }
  EXPECT_EQ(keys.size(), 8u);
}

TEST(TuneNative, SpaceFollowsTheOptions) {
  TuneOptions o;
  RenderSettings settings;
  EXPECT_EQ(make_tune_space(o, settings).param(0).name, "backend");
  o.native_in_space = false;
  EXPECT_EQ(make_tune_space(o, settings).param(0).name, "quality");
  o.work_sizes = true;
  tuner::Space work = make_tune_space(o, settings);
  EXPECT_EQ(work.param(work.size() - 3).name, "scheduler");
}

// The race always has both yardsticks: a finalist that is a variant of native (quality=low) does
// not stand in for native medium, and the default races even when the tuner ranks it last.
TEST(TuneNative, TheRaceAlwaysHasNativeMediumAndTheDefault) {
  TuneOptions o;
  const tuner::Space space = make_tune_space(o, RenderSettings{});
  const tuner::Config native_low = to_tuner_config(space, AccelChoice::native(BvhQuality::kLow));
  BvhConfig wide;
  wide.branching = 8;
  const tuner::Config tuned_wide = to_tuner_config(space, AccelChoice::tuned(wide));
  auto names = [](const std::vector<tuner::Config>& configs) {
    std::vector<std::string> out;
    for (const tuner::Config& c : configs) out.push_back(to_accel_choice(c).to_string());
    return out;
  };
  const std::vector<std::string> entrants =
      names(race_entrants(space, native_low, {native_low, tuned_wide}, true));
  ASSERT_EQ(entrants.size(), 5u);
  EXPECT_EQ(entrants[0], AccelChoice::native(BvhQuality::kLow).to_string());  // the tuner's best
  EXPECT_EQ(entrants[2], AccelChoice::tuned(wide).to_string());
  EXPECT_EQ(entrants[3], AccelChoice::native().to_string());
  EXPECT_EQ(entrants[4], AccelChoice::tuned(BvhConfig{}).to_string());

  // The search seeds race after the finalists, before the yardsticks.
  const std::vector<tuner::Config> seeds = tuning_seeds(space, false);
  const std::vector<std::string> seeded =
      names(race_entrants(space, native_low, {native_low, tuned_wide}, true, seeds));
  ASSERT_EQ(seeded.size(), 5u + seeds.size());
  for (size_t i = 0; i < seeds.size(); ++i)
    EXPECT_EQ(seeded[3 + i], to_accel_choice(seeds[i]).to_string());
  EXPECT_EQ(seeded[3 + seeds.size()], AccelChoice::native().to_string());

  o.native_in_space = false;
  const tuner::Space tuned_space = make_tune_space(o, RenderSettings{});
  const tuner::Config best = to_tuner_config(tuned_space, AccelChoice::tuned(wide));
  const std::vector<std::string> tuned_only = names(race_entrants(tuned_space, best, {}, false));
  ASSERT_EQ(tuned_only.size(), 2u);
  // (The BVH-only space predates the collapse: its default is the uncollapsed tree.)
  EXPECT_EQ(tuned_only[1], to_accel_choice(tuned_space.default_config()).to_string());
  EXPECT_NE(tuned_only[1], tuned_only[0]);
  for (const std::string& name : tuned_only) EXPECT_EQ(name.find("native"), std::string::npos);
}

// The tuner's choice stands unless the default beat it with the whole interval or native beat it
// by median; then the faster yardstick by median is kept, and native only when it is in the space.
TEST(TuneNative, AChoiceMeasuredSlowerThanAYardstickFallsBackToTheFasterOne) {
  auto interval = [](double ratio, double low, double high) {
    RatioInterval r;
    r.ratio = ratio;
    r.low = low;
    r.high = high;
    return r;
  };
  const RatioInterval even = interval(1.0, 0.97, 1.03);
  const RatioInterval faster = interval(1.08, 1.04, 1.12);
  const RatioInterval slower = interval(0.93, 0.91, 0.95);
  const RatioInterval native_cheaper = interval(0.95, 0.92, 0.98);  // native cost / default cost
  const RatioInterval default_cheaper = interval(1.05, 1.02, 1.08);
  using K = KeepAfterComparison;
  EXPECT_EQ(keep_after_comparison(faster, faster, even, true), K::kChosen);
  EXPECT_EQ(keep_after_comparison(even, even, even, true), K::kChosen);
  // Against the default an interval that reaches 1 is not evidence: the choice stands.
  EXPECT_EQ(keep_after_comparison(interval(0.96, 0.92, 1.0), even, even, true), K::kChosen);
  // Against native the median decides (bmw-m6, camera 0 of the forty-fifth session's run: 0.977
  // [0.949, 1.013]); at exactly 1 the choice stands.
  const RatioInterval a_little_slower = interval(0.977, 0.949, 1.013);
  EXPECT_EQ(keep_after_comparison(even, a_little_slower, native_cheaper, true), K::kNative);
  EXPECT_EQ(keep_after_comparison(even, a_little_slower, native_cheaper, false), K::kChosen);
  // Slower than native (conference, camera 1 of the twelfth session's run): native kept when it
  // is the faster yardstick, the default when that is.
  EXPECT_EQ(keep_after_comparison(even, slower, native_cheaper, true), K::kNative);
  EXPECT_EQ(keep_after_comparison(even, slower, default_cheaper, true), K::kDefault);
  // Slower than the default: the default, unless native is faster still.
  EXPECT_EQ(keep_after_comparison(slower, even, default_cheaper, true), K::kDefault);
  EXPECT_EQ(keep_after_comparison(slower, even, native_cheaper, true), K::kNative);
  // Without native in the space it is never kept, and losing to it is no reason to fall back.
  EXPECT_EQ(keep_after_comparison(even, slower, native_cheaper, false), K::kChosen);
  EXPECT_EQ(keep_after_comparison(slower, slower, native_cheaper, false), K::kDefault);
}

// The first simplex spans both backends, so a search of 13 frames (12 parameters + 1) has
// measured native Embree; and every camera reports it beside default and chosen.
TEST(TuneNative, EverySearchMeasuresNativeAndTheReportHasIt) {
  const tuner::testing::TempPath db_path("tune-native.db");
  TuneOptions o = tiny_session(db_path.str());
  o.iterations = 13;
  TuneReport report = run_tune_session(o);
  ASSERT_EQ(report.cameras.size(), 1u);
  const CameraTuneResult& c = report.cameras[0];
  EXPECT_GT(c.default_ms, 0.0);
  EXPECT_GT(c.native_ms, 0.0);
  EXPECT_GT(c.chosen_ms, 0.0);
  // Costs are in the default's units, so the default's ratio to any configuration is exactly
  // their paired ratio; native's to the chosen one is its own median of the per-round ratios.
  EXPECT_DOUBLE_EQ(c.speedup(), c.default_ms / c.chosen_ms);
  EXPECT_GT(c.vs_native(), 0.0);
  // Interleaved rounds from baseline_repeats to the cap, each ratio inside its interval.
  EXPECT_GE(c.compare_rounds, o.baseline_repeats);
  EXPECT_LE(c.compare_rounds, o.compare_max_rounds);
  EXPECT_TRUE(c.compare_within_target || c.compare_rounds == o.compare_max_rounds);
  EXPECT_LE(c.speedup_low, c.speedup());
  EXPECT_GE(c.speedup_high, c.speedup());
  EXPECT_LE(c.vs_native_low, c.vs_native());
  EXPECT_GE(c.vs_native_high, c.vs_native());
  if (c.compare_within_target) {
    EXPECT_LE(c.vs_native_high / c.vs_native() - 1, o.compare_target + 1e-12);
    EXPECT_LE(c.speedup_high / c.speedup() - 1, o.compare_target + 1e-12);
  }
  EXPECT_TRUE(c.backend == "tuned" || c.backend == "native") << c.backend;
  EXPECT_EQ(c.config.rfind("backend=" + c.backend, 0), 0u) << c.config;

  tuner::TuningDb db(db_path.str());
  auto sig = db.find_signature(tuning_key(o), tuner::hardware_signature());
  ASSERT_TRUE(sig.has_value());
  int native = 0, tuned = 0;
  for (const auto& s : db.samples(*sig)) {
    native += s.config.find("backend=native") != std::string::npos;
    tuned += s.config.find("backend=tuned") != std::string::npos;
  }
  EXPECT_GT(native, 0);
  EXPECT_GT(tuned, 0);
}

// A search of one frame measures only its start, the default configuration, and chooses it:
// compared with itself it must report exactly 1, whatever the noise of the interleaved frames.
TEST(TuneNative, AConfigurationComparedWithItselfReportsExactlyOne) {
  const tuner::testing::TempPath db_path("tune-itself.db");
  TuneOptions o = tiny_session(db_path.str());
  o.iterations = 1;
  o.finalists = 0;  // no race: native could win it
  TuneReport report = run_tune_session(o);
  ASSERT_EQ(report.cameras.size(), 1u);
  const CameraTuneResult& c = report.cameras[0];
  EXPECT_EQ(c.race_candidates, 0);
  EXPECT_EQ(c.race_frames, 0);
  const std::string default_config = AccelChoice::tuned(BvhConfig{}).to_string();
  if (c.fallback.empty()) {
    ASSERT_EQ(c.config, default_config);
    EXPECT_EQ(c.speedup(), 1.0);
    EXPECT_EQ(c.speedup_low, 1.0);
    EXPECT_EQ(c.speedup_high, 1.0);
    EXPECT_EQ(c.default_ms, c.chosen_ms);
    EXPECT_NE(c.native_ms, c.chosen_ms);  // native is another configuration, measured apart
  } else {
    // The default measured slower than native (whole interval below 1; a slow machine, or a
    // sanitizer build): native is kept, and it is now native that is compared with itself.
    ASSERT_EQ(c.fallback, "native");
    EXPECT_EQ(c.rejected, default_config);
    EXPECT_LT(c.rejected_vs_native, 1.0);
    ASSERT_EQ(c.config, AccelChoice::native().to_string());
    EXPECT_EQ(c.vs_native(), 1.0);
    EXPECT_EQ(c.vs_native_low, 1.0);
    EXPECT_EQ(c.vs_native_high, 1.0);
    EXPECT_EQ(c.native_ms, c.chosen_ms);
    EXPECT_NE(c.default_ms, c.chosen_ms);
  }
}

// After a one-frame search the tuner's only measured configuration is the default, so the race
// is the default against native Embree: two candidates, an untimed frame and race_rounds rounds
// each, and the chosen configuration is the default unless the race says it changed the choice,
// and then native. The race's rounds are reported to the tuner like every measurement.
TEST(TuneNative, TheFinalistsRaceNativeAndTheWinnerIsChosen) {
  const tuner::testing::TempPath db_path("tune-race.db");
  TuneOptions o = tiny_session(db_path.str());
  o.iterations = 1;
  o.finalists = 3;
  o.race_rounds = 2;
  TuneReport report = run_tune_session(o);
  ASSERT_EQ(report.cameras.size(), 1u);
  const CameraTuneResult& c = report.cameras[0];
  // One frame, so the tuner's best is the default; it races native and the search seeds.
  const tuner::Space space = make_tune_space(o, RenderSettings{});
  const std::vector<tuner::Config> seeds = tuning_seeds(space, false);
  std::set<std::string> entrants = {AccelChoice::native().to_string(),
                                    AccelChoice::tuned(BvhConfig{}).to_string()};
  for (const tuner::Config& seed : seeds) entrants.insert(to_accel_choice(seed).to_string());
  EXPECT_EQ(c.race_candidates, static_cast<int>(entrants.size()));
  EXPECT_EQ(c.race_frames, c.race_candidates * (2 + 1));
  const std::string raced = c.fallback.empty() ? c.config : c.rejected;
  EXPECT_EQ(entrants.count(raced), 1u) << raced;
  EXPECT_EQ(c.race_changed_choice, raced != AccelChoice::tuned(BvhConfig{}).to_string());
  if (!c.fallback.empty()) {  // the race's winner measured slower than a yardstick afterwards
    EXPECT_EQ(c.config, c.fallback == "native" ? AccelChoice::native().to_string()
                                               : AccelChoice::tuned(BvhConfig{}).to_string());
    EXPECT_NE(c.config, raced);
  }
  // Every timed round of the race is a sample of the database, native's among them.
  {
    tuner::TuningDb db(db_path.str());
    auto sig = db.find_signature(tuning_key(o), tuner::hardware_signature());
    ASSERT_TRUE(sig.has_value());
    int native = 0;
    for (const auto& s : db.samples(*sig))
      native += s.config.find("backend=native") != std::string::npos;
    EXPECT_EQ(native, o.race_rounds);
  }

  // Without native in the space the default races the seeds alone.
  TuneOptions tuned_only = o;
  tuned_only.native_in_space = false;
  const CameraTuneResult t = run_tune_session(tuned_only).cameras.at(0);
  const size_t tuned_seeds =
      tuning_seeds(make_tune_space(tuned_only, RenderSettings{}), false).size();
  EXPECT_EQ(t.race_candidates, static_cast<int>(1 + tuned_seeds));
  EXPECT_EQ(t.race_frames, t.race_candidates * (2 + 1));
  EXPECT_EQ(t.backend, "tuned");
}

// Without the backend in the space, native is still the yardstick, and the samples go under the
// BVH-only key of the same file (which would throw if the keys collided).
TEST(TuneNative, TunedOnlyStillMeasuresNative) {
  const tuner::testing::TempPath db_path("tune-tuned-only.db");
  TuneOptions o = tiny_session(db_path.str());
  o.iterations = 3;
  o.baseline_repeats = 1;
  TuneOptions t = o;
  t.native_in_space = false;
  TuneReport with_native = run_tune_session(o);
  TuneReport tuned_only = run_tune_session(t);
  ASSERT_EQ(tuned_only.cameras.size(), 1u);
  EXPECT_GT(tuned_only.cameras[0].native_ms, 0.0);
  EXPECT_EQ(tuned_only.cameras[0].backend, "tuned");
  tuner::TuningDb db(db_path.str());
  auto sig = db.find_signature(tuning_key(t), tuner::hardware_signature());
  ASSERT_TRUE(sig.has_value());
  for (const auto& s : db.samples(*sig))
    EXPECT_EQ(s.config.find("backend"), std::string::npos) << s.config;
}

}  // namespace
}  // namespace tuneray
