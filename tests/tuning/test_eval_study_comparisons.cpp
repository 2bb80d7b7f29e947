// The study's comparisons on a machine whose load the test controls (loaded_machine.h): ratios
// that a load change cannot move, a best known configuration that is re-measured rather than
// one lucky search sample, and a comparison interrupted mid-way that is measured again whole.
#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>

#include "common/temp_dir.h"
#include "loaded_machine.h"
#include "tuner/tuning_db.h"
#include "tuning/bvh_space.h"
#include "tuning/eval_comparison.h"
#include "tuning/eval_search.h"
#include "tuning/eval_study.h"
#include "tuning/line_log.h"
#include "tuning_fixtures.h"

namespace tuneray {
namespace {

using testing::LoadedMachine;
using testing::MachineLoad;

EvalProfile one_scene_profile() {
  EvalProfile p = eval_profile("quick", {});
  p.scenes = {"cornell"};
  p.objectives = {Objective::kRender};
  p.cameras = 5;
  p.iterations = 8;
  p.repetitions = 2;
  p.synthetic_costs = true;
  p.native_in_space = false;  // more distinct configurations to compare
  p.yardsticks = 0;           // the search window is p.iterations frames (but in the test of them)
  return p;
}

double synthetic_ms(const std::string& config, int camera) {
  return synthetic_frame_cost("cornell", Objective::kRender, camera, parse_accel_choice(config))
      .cost_ms(Objective::kRender);
}

class EvalStudyComparisons : public ::testing::Test {
 protected:
  EvalPaths paths(const std::string& name) const { return {dir_.file(name), ""}; }

  EvalResults run(const std::string& name, const MachineLoad* load) {
    EvalStudyOptions o;
    o.hardware = {"test-cpu x2"};
    if (load)
      o.make_costs = [load](const EvalScene& scene, Objective objective) {
        return std::make_unique<LoadedMachine>(scene.name, objective, *load);
      };
    return run_eval_study(p_, paths(name), nullptr, o);
  }

  // Every configuration of a camera's stored comparison.
  std::vector<std::string> compared(const std::string& name, int camera) const {
    const std::string run_key = eval_run_key(p_, "cornell", Objective::kRender);
    LineLog log(eval_comparisons_path(paths(name)), run_key + '\t');
    const auto line = log.find(run_key + '\t' + std::to_string(camera));
    return line ? parse_eval_comparison(*line).configs : std::vector<std::string>{};
  }

  EvalProfile p_ = one_scene_profile();
  testing::TempDir dir_;
};

TEST_F(EvalStudyComparisons, ALoadChangingFromRoundToRoundMovesNoRatio) {
  const EvalResults quiet = run("quiet", nullptr);
  MachineLoad busy;
  busy.search_frames = p_.iterations;
  busy.load = {1.0, 2.0, 1.3, 3.1, 0.9, 1.7};
  const EvalResults loaded = run("busy", &busy);
  ASSERT_EQ(quiet.cameras.size(), 5u);
  ASSERT_EQ(loaded.cameras.size(), quiet.cameras.size());
  auto same = [](const RatioInterval& a, const RatioInterval& b) {
    EXPECT_NEAR(a.ratio, b.ratio, 1e-12 * b.ratio);
    EXPECT_NEAR(a.low, b.low, 1e-12 * b.ratio);
    EXPECT_NEAR(a.high, b.high, 1e-12 * b.ratio);
  };
  for (size_t i = 0; i < quiet.cameras.size(); ++i) {
    const CameraRecord &q = quiet.cameras[i], &l = loaded.cameras[i];
    SCOPED_TRACE("camera " + std::to_string(q.camera));
    same(l.search_speedup, q.search_speedup);
    same(l.native_speedup, q.native_speedup);
    EXPECT_EQ(l.best_config, q.best_config);
    EXPECT_EQ(l.rounds, p_.compare_min_rounds);  // a common load leaves no spread
    EXPECT_TRUE(l.within_target);
    // The costs carry the load of their rounds (the median of 2, 1.3, 3.1, 0.9, 1.7 and 1 is
    // 1.5); their ratios do not.
    EXPECT_NEAR(l.default_ms, 1.5 * q.default_ms, 1e-12 * q.default_ms);
    // The yardstick measured in both windows says so: the searches ran unloaded, so the search
    // window was 1 / 1.5 as loaded as the comparison's (and exactly as loaded when quiet).
    const double default_frame =
        synthetic_ms(AccelChoice::tuned(testing::bvh_only_defaults()).to_string(), q.camera);
    EXPECT_DOUBLE_EQ(q.search_default_ms, default_frame);
    EXPECT_DOUBLE_EQ(l.search_default_ms, default_frame);
    EXPECT_NEAR(q.search_window_load, 1.0, 1e-12);
    EXPECT_NEAR(l.search_window_load, 1 / 1.5, 1e-12);
    EXPECT_NEAR(
        q.search_speedup.ratio,
        synthetic_ms(AccelChoice::tuned(testing::bvh_only_defaults()).to_string(), q.camera) /
            synthetic_ms(q.converged_config, q.camera),
        1e-12);
  }
  ASSERT_EQ(loaded.predictions.size(), quiet.predictions.size());
  ASSERT_FALSE(quiet.predictions.empty());
  for (size_t i = 0; i < quiet.predictions.size(); ++i) {
    EXPECT_EQ(loaded.predictions[i].config, quiet.predictions[i].config);
    same(loaded.predictions[i].roofline, quiet.predictions[i].roofline);
    same(loaded.predictions[i].native_speedup, quiet.predictions[i].native_speedup);
  }
}

TEST_F(EvalStudyComparisons, TheBestKnownIsReMeasuredNotALuckySearchSample) {
  MachineLoad lucky;
  lucky.search_frames = p_.iterations;
  lucky.lucky_frame = 3;  // at every camera, the fourth search frame measured at 1 % of its cost
  lucky.lucky_factor = 0.01;
  const EvalResults r = run("lucky", &lucky);
  tuner::TuningDb db(eval_db_path(paths("lucky")));
  const tuner::Space space = eval_space(p_);
  const std::string run_key = eval_run_key(p_, "cornell", Objective::kRender);
  for (const CameraRecord& c : r.cameras) {
    SCOPED_TRACE("camera " + std::to_string(c.camera));
    const auto signature = db.find_signature(eval_tuning_key(p_, run_key, c.camera), "test-cpu x2");
    ASSERT_TRUE(signature.has_value());
    const std::string lucky_config =
        to_accel_choice(space.parse(db.samples(*signature).at(3).config)).to_string();
    // The lucky sample is the search's cheapest, and its configuration is compared...
    EXPECT_EQ(*std::min_element(c.search_ms.begin(), c.search_ms.end()), c.search_ms[3]);
    const std::vector<std::string> configs = compared("lucky", c.camera);
    EXPECT_NE(std::find(configs.begin(), configs.end(), lucky_config), configs.end());
    // ...at what it really costs: the best known is the comparison's fastest.
    EXPECT_GT(c.best_ms, c.search_ms[3]);
    double fastest = synthetic_ms(configs.front(), c.camera);
    for (const std::string& config : configs)
      fastest = std::min(fastest, synthetic_ms(config, c.camera));
    EXPECT_NEAR(c.best_ms, fastest, 1e-12);
    EXPECT_NEAR(synthetic_ms(c.best_config, c.camera), fastest, 1e-12);
  }
  for (const PredictionRecord& pr : r.predictions) EXPECT_LE(pr.roofline.ratio, 1.0 + 1e-12);
}

TEST_F(EvalStudyComparisons, AnInterruptedComparisonIsMeasuredAgainWholeInOneWindow) {
  MachineLoad load;
  load.search_frames = p_.iterations;
  load.load = {1.0, 2.0, 1.3, 3.1, 0.9, 1.7};
  const EvalResults whole = run("whole", &load);

  // The machine goes down at the 7th frame of camera 2's comparison, after frames that a result
  // using them would betray (each configuration off by its own factor).
  MachineLoad failing = load;
  failing.fail_camera = 2;
  failing.fail_at = 6;
  EXPECT_THROW(run("resumed", &failing), std::runtime_error);
  EXPECT_EQ(compared("resumed", 1).size(), static_cast<size_t>(whole.cameras[1].candidates));
  EXPECT_TRUE(compared("resumed", 2).empty());  // nothing of the partial window is stored

  // Resumed: the searches are stored, so every frame the machine gives is a comparison's, with
  // the loads of the uninterrupted run's comparisons from their first round on.
  MachineLoad restarted = load;
  restarted.search_frames = 0;
  const EvalResults resumed = run("resumed", &restarted);
  ASSERT_EQ(resumed.cameras.size(), whole.cameras.size());
  for (size_t i = 0; i < whole.cameras.size(); ++i) {
    const CameraRecord &w = whole.cameras[i], &r = resumed.cameras[i];
    SCOPED_TRACE("camera " + std::to_string(w.camera));
    EXPECT_EQ(r.search_ms, w.search_ms);
    EXPECT_EQ(r.default_ms, w.default_ms);
    EXPECT_EQ(r.converged_ms, w.converged_ms);
    EXPECT_EQ(r.native_ms, w.native_ms);
    EXPECT_EQ(r.best_ms, w.best_ms);
    EXPECT_EQ(r.search_speedup.ratio, w.search_speedup.ratio);
    EXPECT_EQ(r.native_speedup.low, w.native_speedup.low);
    EXPECT_EQ(r.rounds, w.rounds);
  }
  ASSERT_EQ(resumed.predictions.size(), whole.predictions.size());
  for (size_t i = 0; i < whole.predictions.size(); ++i) {
    EXPECT_EQ(resumed.predictions[i].predicted_ms, whole.predictions[i].predicted_ms);
    EXPECT_EQ(resumed.predictions[i].roofline.ratio, whole.predictions[i].roofline.ratio);
  }
}

TEST_F(EvalStudyComparisons, TheYardstickPutsTheSearchFramesInTheComparisonsWindow) {
  const EvalResults quiet = run("quiet", nullptr);
  // The same study with the searches run on a machine twice as slow, and one of the yardstick
  // frames stopped 30 times longer than it should take.
  p_.yardsticks = 3;
  int window = p_.iterations;
  std::vector<int> after;  // the search frames a yardstick follows
  for (int k = 0; k < p_.iterations; ++k)
    if (yardstick_after_frame(p_, k)) after.push_back(k);
  ASSERT_EQ(after, (std::vector<int>{2, 5, 7}));  // evenly spread, the last after the last frame
  window += static_cast<int>(after.size());
  MachineLoad slow_search;
  slow_search.search_frames = window;
  slow_search.search_load = 2;
  slow_search.lucky_frame = after[0] + 1;  // the window's frame after search frame 2
  slow_search.lucky_factor = 30;
  const EvalResults slow = run("slow", &slow_search);
  ASSERT_EQ(slow.cameras.size(), quiet.cameras.size());
  for (size_t i = 0; i < quiet.cameras.size(); ++i) {
    const CameraRecord &q = quiet.cameras[i], &s = slow.cameras[i];
    SCOPED_TRACE("camera " + std::to_string(q.camera));
    // The first frame (the default) and three yardsticks, one of them stopped: their median is
    // twice the comparison's cost of the default.
    EXPECT_EQ(s.search_default_frames, 4);
    EXPECT_NEAR(s.search_window_load, 2.0, 1e-12);
    EXPECT_TRUE(s.search_calibrated);
    ASSERT_EQ(s.search_ms.size(), q.search_ms.size());
    for (size_t k = 0; k < q.search_ms.size(); ++k) {
      EXPECT_NEAR(s.search_ms[k], 2 * q.search_ms[k], 1e-9 * q.search_ms[k]);  // as measured
      EXPECT_NEAR(s.search_ms_in_comparison_window()[k], q.search_ms[k], 1e-9 * q.search_ms[k]);
    }
    EXPECT_FALSE(q.search_calibrated);  // one frame of the default only
    EXPECT_NEAR(q.search_window_load, 1.0, 1e-12);
  }
  // So the figures that set the search against the comparison are those of the quiet machine.
  ASSERT_EQ(slow.predictions.size(), quiet.predictions.size());
  for (size_t i = 0; i < quiet.predictions.size(); ++i) {
    const PredictionRecord &q = quiet.predictions[i], &s = slow.predictions[i];
    EXPECT_EQ(s.config, q.config);
    EXPECT_NEAR(s.speedup, q.speedup, 1e-9 * q.speedup);
    EXPECT_NEAR(s.overhead_reduction, q.overhead_reduction, 1e-9);
    EXPECT_EQ(s.break_even, q.break_even);
  }
}

TEST_F(EvalStudyComparisons, ASeededStudyMeasuresTunesSeedsFirstUnderItsOwnKey) {
  const tuner::Space space = eval_space(p_);
  const std::vector<tuner::Config> seeds = tuning_seeds(space, false);
  ASSERT_GE(seeds.size(), 2u);
  // The seeds' frames at camera 0, in a run without and with --seeded.
  auto seeds_measured = [&](const std::string& name) {
    run(name, nullptr);
    tuner::TuningDb db(eval_db_path(paths(name)));
    const std::string key = eval_tuning_key(p_, eval_run_key(p_, "cornell", Objective::kRender), 0);
    const auto signature = db.find_signature(key, "test-cpu x2");
    EXPECT_TRUE(signature.has_value()) << key;
    if (!signature) return size_t{0};
    const auto samples = db.samples(*signature);
    // The first simplex: the default and one point per dimension, the seeds among them.
    const size_t first_simplex = std::min(samples.size(), space.size() + 1);
    size_t found = 0;
    for (const tuner::Config& seed : seeds)
      for (size_t i = 0; i < first_simplex; ++i)
        if (samples[i].config == seed.to_string()) {
          ++found;
          break;
        }
    return found;
  };
  p_.iterations = static_cast<int>(space.size()) + 1;
  EXPECT_EQ(seeds_measured("unseeded"), 0u);
  p_.seeded = true;
  EXPECT_NE(eval_tuning_key(p_, "k", 0).find("+seeded"), std::string::npos);
  EXPECT_EQ(seeds_measured("seeded"), seeds.size());
}

}  // namespace
}  // namespace tuneray
