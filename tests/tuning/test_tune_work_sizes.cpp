// `tune --work-sizes` in process: its samples go under their own tuning key, so they never mix
// with BVH-only samples of the same database, and the BVH-only key is the one it always was.
#include <gtest/gtest.h>

#include "tuning_fixtures.h"

#include "tuner/hardware_signature.h"
#include "tuner/temp_path.h"
#include "tuner/tuning_db.h"
#include "tuning/tune_session.h"

namespace tuneray {
namespace {

TEST(TuneWorkSizes, TuningKeyDiffersOnlyWithWorkSizes) {
  TuneOptions o;
  EXPECT_EQ(tuning_key(o), "backend+bvh/render/320x180/1spp/3b/wavefront");
  o.native_in_space = false;
  o.wavefront = false;
  EXPECT_EQ(tuning_key(o), "bvh/render/320x180/1spp/3b");  // existing databases stay valid
  TuneOptions w = o;
  w.work_sizes = true;
  EXPECT_NE(tuning_key(w), tuning_key(o));
  w.objective = Objective::kTotal;
  o.objective = Objective::kTotal;
  EXPECT_NE(tuning_key(w), tuning_key(o));
}

TEST(TuneWorkSizes, SamplesAreStoredApartFromBvhOnlyOnes) {
  const tuner::testing::TempPath db_path("tune-work-sizes.db");
  TuneOptions o = testing::tiny_tune_session(db_path.str());
  o.iterations = 4;
  o.baseline_repeats = 1;
  o.epsilon = 1;
  o.finalists = 0;  // exactly the search's samples (a race adds its rounds)
  TuneOptions w = o;
  w.work_sizes = true;

  TuneReport bvh_only = run_tune_session(o);
  // The same file, the same objective and size: would throw if the keys (and thus the space
  // descriptions checked on opening) collided.
  TuneReport with_work = run_tune_session(w);
  ASSERT_EQ(bvh_only.cameras.size(), 1u);
  ASSERT_EQ(with_work.cameras.size(), 1u);
  EXPECT_EQ(bvh_only.cameras[0].config.find("scheduler="), std::string::npos);
  EXPECT_NE(with_work.cameras[0].config.find("scheduler="), std::string::npos)
      << with_work.cameras[0].config;

  {
    tuner::TuningDb db(db_path.str());
    const std::string hw = tuner::hardware_signature();
    auto bvh_sig = db.find_signature(tuning_key(o), hw);
    auto work_sig = db.find_signature(tuning_key(w), hw);
    ASSERT_TRUE(bvh_sig.has_value());
    ASSERT_TRUE(work_sig.has_value());
    EXPECT_NE(*bvh_sig, *work_sig);
    auto bvh_samples = db.samples(*bvh_sig);
    auto work_samples = db.samples(*work_sig);
    EXPECT_EQ(bvh_samples.size(), 4u);
    EXPECT_EQ(work_samples.size(), 4u);
    for (const auto& s : bvh_samples)
      EXPECT_EQ(s.config.find("scheduler="), std::string::npos) << s.config;
    for (const auto& s : work_samples) {
      EXPECT_NE(s.config.find("scheduler="), std::string::npos) << s.config;
      EXPECT_NE(s.config.find("tile_size="), std::string::npos) << s.config;
      EXPECT_NE(s.config.find("batch_size="), std::string::npos) << s.config;
    }
  }
}

}  // namespace
}  // namespace tuneray
