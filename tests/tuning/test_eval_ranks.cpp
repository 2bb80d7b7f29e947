// The study spread over ranks, without MPI: in-process ranks (fake_ranks.h) running the real
// coordinator and workers with synthetic costs must give exactly the results of the single-rank
// study, resume from what rank 0 stored with any number of ranks, and refuse to mix machines.
#include <gtest/gtest.h>

#include <filesystem>
#include <set>
#include <thread>

#include "common/temp_dir.h"
#include "fake_ranks.h"
#include "tuner/hybrid_tuner.h"
#include "tuner/tuning_db.h"
#include "tuning/eval_ranks.h"
#include "tuning/eval_scene.h"
#include "tuning/eval_search.h"
#include "tuning/rank_cores.h"
#include "tuning/tuner_state.h"

namespace tuneray {
namespace {

using testing::FakeRanks;
using testing::InterruptedTransport;

EvalProfile small_profile() {
  EvalProfile p = eval_profile("quick", {});
  p.scenes = {"cornell", "voxels"};
  p.cameras = 5;
  p.iterations = 8;
  p.repetitions = 2;
  p.synthetic_costs = true;
  // With native Embree in the space every search converges to it at these sizes and the
  // predictors pick nothing new; the BVH alone gives the comparisons predictions to measure.
  p.native_in_space = false;
  return p;
}

struct RankRun {
  int workers = 2;
  std::vector<std::string> hardware = {"test-cpu x2"};  // of the workers, cycled
  bool mix = false;
  int interrupt_after = -1;  // results rank 0 stores before it "dies" (< 0: never)
  int* jobs_sent = nullptr;  // receives the number of jobs rank 0 handed out
};

// Runs the coordinator (this thread) and `run.workers` in-process workers (threads).
EvalResults run_on_ranks(const EvalProfile& p, const EvalPaths& paths, const RankRun& run = {}) {
  FakeRanks ranks(run.workers + 1);
  std::vector<std::thread> threads;
  for (int r = 1; r <= run.workers; ++r)
    threads.emplace_back([&, r] {
      auto t = ranks.transport(r);
      run_eval_worker(p, *t, run.hardware[static_cast<size_t>(r - 1) % run.hardware.size()]);
    });
  auto inner = ranks.transport(0);
  InterruptedTransport coordinator(*inner, run.interrupt_after);
  struct Join {  // the workers end on the coordinator's stop, whether it returns or throws
    std::vector<std::thread>& threads;
    ~Join() {
      for (auto& th : threads) th.join();
    }
  };
  auto report = [&] {
    if (run.jobs_sent) *run.jobs_sent = coordinator.jobs_sent;
  };
  Join join{threads};
  try {
    EvalResults results = run_eval_coordinator(p, paths, coordinator, run.mix, nullptr, nullptr);
    report();
    return results;
  } catch (...) {
    report();
    throw;
  }
}

void expect_same_results(const EvalResults& a, const EvalResults& b) {
  ASSERT_EQ(a.cameras.size(), b.cameras.size());
  for (size_t i = 0; i < a.cameras.size(); ++i) {
    const CameraRecord &x = a.cameras[i], &y = b.cameras[i];
    SCOPED_TRACE(x.scene + " " + x.objective + " camera " + std::to_string(x.camera));
    EXPECT_EQ(x.scene, y.scene);
    EXPECT_EQ(x.objective, y.objective);
    EXPECT_EQ(x.camera, y.camera);
    EXPECT_EQ(x.search_ms, y.search_ms);
    EXPECT_EQ(x.converged_config, y.converged_config);
    EXPECT_EQ(x.converged, y.converged);
    EXPECT_EQ(x.default_ms, y.default_ms);
    EXPECT_EQ(x.converged_ms, y.converged_ms);
    EXPECT_EQ(x.native_ms, y.native_ms);
    EXPECT_EQ(x.best_ms, y.best_ms);
    EXPECT_EQ(x.best_config, y.best_config);
    EXPECT_EQ(x.search_speedup.ratio, y.search_speedup.ratio);
    EXPECT_EQ(x.search_speedup.low, y.search_speedup.low);
    EXPECT_EQ(x.native_speedup.high, y.native_speedup.high);
    EXPECT_EQ(x.candidates, y.candidates);
    EXPECT_EQ(x.rounds, y.rounds);
    EXPECT_EQ(x.within_target, y.within_target);
  }
  ASSERT_EQ(a.predictions.size(), b.predictions.size());
  for (size_t i = 0; i < a.predictions.size(); ++i) {
    const PredictionRecord &x = a.predictions[i], &y = b.predictions[i];
    EXPECT_EQ(x.camera, y.camera);
    EXPECT_EQ(x.repetition, y.repetition);
    EXPECT_EQ(x.predictor, y.predictor);
    EXPECT_EQ(x.config, y.config);
    EXPECT_EQ(x.predicted_ms, y.predicted_ms);
    EXPECT_EQ(x.speedup, y.speedup);
    EXPECT_EQ(x.roofline.ratio, y.roofline.ratio);
    EXPECT_EQ(x.native_speedup.ratio, y.native_speedup.ratio);
  }
}

class EvalRanks : public ::testing::Test {
 protected:
  EvalPaths paths(const std::string& name) const { return {dir_.file(name), ""}; }
  EvalResults sequential(const EvalProfile& p) {
    EvalStudyOptions o;
    o.hardware = {"test-cpu x2"};
    return run_eval_study(p, paths("sequential"), nullptr, o);
  }
  testing::TempDir dir_;
};

TEST_F(EvalRanks, TwoAndThreeWorkersGiveTheSingleRankResults) {
  const EvalProfile p = small_profile();
  const EvalResults reference = sequential(p);
  ASSERT_EQ(reference.cameras.size(), 2u * 2u * 5u);
  ASSERT_FALSE(reference.predictions.empty());
  RankRun two;
  expect_same_results(reference, run_on_ranks(p, paths("two"), two));
  RankRun three;
  three.workers = 3;
  expect_same_results(reference, run_on_ranks(p, paths("three"), three));
  // A finished study asks nothing more of its ranks.
  int jobs = -1;
  two.jobs_sent = &jobs;
  expect_same_results(reference, run_on_ranks(p, paths("two"), two));
  EXPECT_EQ(jobs, 0);
}

TEST_F(EvalRanks, ResumesWithAnotherRankCountAndRedoesNothingStored) {
  const EvalProfile p = small_profile();
  const EvalResults reference = sequential(p);
  RankRun killed;
  killed.workers = 3;
  killed.interrupt_after = 7;
  EXPECT_THROW(run_on_ranks(p, paths("resume"), killed), std::runtime_error);
  // What rank 0 stored before it "died" is in the database...
  {
    tuner::TuningDb db(eval_db_path(paths("resume")));
    int complete = 0;
    for (const std::string scene : {"cornell", "voxels"})
      for (Objective o : p.objectives)
        for (int c = 0; c < p.cameras; ++c) {
          const auto rows =
              db.hardware_with_samples(eval_tuning_key(p, eval_run_key(p, scene, o), c));
          if (!rows.empty() && rows[0].samples == p.iterations) ++complete;
        }
    EXPECT_EQ(complete, 7);
  }
  // ...and a resumed run with another number of ranks hands out all but those 7 jobs.
  int fresh_jobs = 0, resumed_jobs = 0;
  RankRun fresh;
  fresh.jobs_sent = &fresh_jobs;
  expect_same_results(reference, run_on_ranks(p, paths("fresh"), fresh));
  RankRun resumed;
  resumed.jobs_sent = &resumed_jobs;
  expect_same_results(reference, run_on_ranks(p, paths("resume"), resumed));
  EXPECT_EQ(fresh_jobs, 2 * (2 * 2 * 5));  // the searches, then the comparisons
  EXPECT_EQ(resumed_jobs, fresh_jobs - 7);
}

TEST_F(EvalRanks, ContinuesASearchTheDatabaseHoldsInPart) {
  const EvalProfile p = small_profile();
  const EvalResults reference = sequential(p);
  // Three frames of one camera's search, as a single-rank run killed mid-search leaves them.
  const std::unique_ptr<EvalScene> scene = load_eval_scene(p, "voxels");
  const std::string run_key = eval_run_key(p, "voxels", Objective::kTotal);
  tuner::TunerOptions options = eval_tuner_options(p, Objective::kTotal, run_key, 2);
  options.db_path = eval_db_path(paths("partial"));
  options.hardware = "test-cpu x2";
  std::filesystem::create_directories(paths("partial").out_dir);
  {
    tuner::HybridTuner tuner(eval_space(p), make_indicator_schema(), options);
    auto costs = make_eval_costs(p, *scene, Objective::kTotal);
    for (int k = 0; k < 3; ++k)
      measure_search_frame(p, k, tuner, scene->states[2], *costs, Objective::kTotal, 2);
  }
  expect_same_results(reference, run_on_ranks(p, paths("partial")));
}

TEST_F(EvalRanks, RefusesRanksOfDifferentMachinesUnlessTold) {
  const EvalProfile p = small_profile();
  RankRun mixed_ranks;
  mixed_ranks.hardware = {"cpu-a x2", "cpu-b x8"};
  try {
    run_on_ranks(p, paths("mixed"), mixed_ranks);
    FAIL() << "mixed ranks accepted";
  } catch (const EvalSignatureError& e) {
    EXPECT_NE(std::string(e.what()).find("cpu-b x8 (ranks 2)"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("--mix-signatures"), std::string::npos);
  }
  mixed_ranks.mix = true;
  const EvalResults mixed = run_on_ranks(p, paths("mixed"), mixed_ranks);
  expect_same_results(sequential(p), mixed);  // synthetic costs do not depend on the machine
  // Every sample is kept with the machine that measured it.
  tuner::TuningDb db(eval_db_path(paths("mixed")));
  std::set<std::string> machines;
  for (Objective o : p.objectives)
    for (int c = 0; c < p.cameras; ++c)
      for (const auto& row :
           db.hardware_with_samples(eval_tuning_key(p, eval_run_key(p, "cornell", o), c)))
        machines.insert(row.hardware);
  EXPECT_EQ(machines, (std::set<std::string>{"cpu-a x2", "cpu-b x8"}));
}

TEST_F(EvalRanks, RefusesADatabaseWithSamplesOfAnotherMachineUnlessTold) {
  const EvalProfile p = small_profile();
  EvalStudyOptions other;
  other.hardware = {"other-cpu x64"};
  run_eval_study(p, paths("study"), nullptr, other);
  EvalStudyOptions here;
  here.hardware = {"test-cpu x2"};
  try {
    run_eval_study(p, paths("study"), nullptr, here);
    FAIL() << "samples of another machine accepted";
  } catch (const EvalSignatureError& e) {
    EXPECT_NE(std::string(e.what()).find("other-cpu x64"), std::string::npos) << e.what();
  }
  EXPECT_THROW(run_on_ranks(p, paths("study")), EvalSignatureError);
  // Told to mix, the complete searches of the other machine are used as they are.
  here.mix_signatures = true;
  expect_same_results(sequential(p), run_eval_study(p, paths("study"), nullptr, here));
}

// What a worker answers a job with, `job_text` sent after its hello (it stops after an error).
RankMessage worker_answer(const EvalProfile& p, const std::string& job_text) {
  FakeRanks ranks(2);
  std::thread worker([&] {
    auto t = ranks.transport(1);
    run_eval_worker(p, *t, "test-cpu x2");
  });
  auto coordinator = ranks.transport(0);
  EXPECT_EQ(coordinator->receive().tag, RankTag::kHello);
  coordinator->send(1, RankTag::kJob, job_text);
  const RankMessage m = coordinator->receive();
  worker.join();  // the worker stopped after reporting
  return m;
}

TEST_F(EvalRanks, AWorkersFailureNamesTheRankAndEndsTheRun) {
  const RankMessage m = worker_answer(small_profile(), "{not json");
  EXPECT_EQ(m.tag, RankTag::kError);
  EXPECT_NE(m.body.find("malformed job"), std::string::npos) << m.body;
}

TEST_F(EvalRanks, AJobOutsideTheProfileIsAnError) {
  EvalJob job;
  job.scene = 7;
  const RankMessage m = worker_answer(small_profile(), to_json(job));
  EXPECT_EQ(m.tag, RankTag::kError);
  EXPECT_NE(m.body.find("not in the profile"), std::string::npos) << m.body;
}

TEST(EvalJobMessages, RoundTripExactly) {
  EvalJob job;
  job.scene = 1;
  job.objective = 1;
  job.camera = 4;
  job.search = true;
  job.done_hardware = "cpu \"x\" x2";
  job.done = {{"a=1", true, 0.1 + 0.2, 1.0 / 3.0, 2e-300}, {"b=2", false, 0, 5, 6}};
  job.compare = {"backend=native", "x"};
  const EvalJob j = parse_eval_job(to_json(job));
  EXPECT_EQ(j.scene, 1);
  EXPECT_EQ(j.camera, 4);
  EXPECT_TRUE(j.search);
  EXPECT_EQ(j.done_hardware, job.done_hardware);
  ASSERT_EQ(j.done.size(), 2u);
  EXPECT_EQ(j.done[0].cost_s, 0.1 + 0.2);  // bit for bit: replays must see the measured bits
  EXPECT_EQ(j.done[0].build_ms, 1.0 / 3.0);
  EXPECT_EQ(j.done[0].render_ms, 2e-300);
  EXPECT_FALSE(j.done[1].ok);
  EXPECT_EQ(j.compare, job.compare);

  EvalJobResult r;
  r.camera = 3;
  r.hardware = "h";
  r.frames = job.done;
  r.comparison = EvalComparison{{"c", "d"}, {{1.0 / 7.0, 2.5}, {0.1 + 0.2, 3e-300}}, true};
  const EvalJobResult q = parse_eval_job_result(to_json(r));
  EXPECT_EQ(q.camera, 3);
  EXPECT_EQ(q.frames.size(), 2u);
  ASSERT_TRUE(q.comparison.has_value());
  EXPECT_EQ(q.comparison->configs, r.comparison->configs);
  EXPECT_EQ(q.comparison->costs, r.comparison->costs);  // bit for bit
  EXPECT_TRUE(q.comparison->within_target);
  r.comparison.reset();
  EXPECT_FALSE(parse_eval_job_result(to_json(r)).comparison.has_value());
  EXPECT_THROW(parse_eval_job_result("{\"scene\": 1}"), std::runtime_error);
}

TEST(RankCores, RankZeroCoordinatesAndTheWorkersSplitTheNode) {
  // 2 ranks on 2 cores: the only measuring rank gets both.
  auto split = split_node_cores({0, 1}, {0, 1});
  EXPECT_EQ(split.size(), 1u);
  EXPECT_EQ(split[1], (std::vector<int>{0, 1}));
  EXPECT_EQ(describe_node_cores({0, 1}, {0, 1}, split),
            "2 ranks on this node share 2 cores: rank 0 coordinates (no core of its own), rank 1 "
            "on cores 0-1");
  // 3 ranks on 2 cores: one core each.
  split = split_node_cores({0, 2, 1}, {0, 1});
  EXPECT_EQ(split[1], (std::vector<int>{0}));
  EXPECT_EQ(split[2], (std::vector<int>{1}));
  // A node without rank 0: 2 workers on 5 cores, disjoint and covering.
  split = split_node_cores({4, 3}, {2, 3, 4, 5, 6});
  EXPECT_EQ(split[3], (std::vector<int>{2, 3, 4}));
  EXPECT_EQ(split[4], (std::vector<int>{5, 6}));
  // More workers than cores: shared, and said so.
  split = split_node_cores({1, 2, 3}, {0, 1});
  EXPECT_EQ(split[3], (std::vector<int>{0}));
  EXPECT_NE(describe_node_cores({1, 2, 3}, {0, 1}, split).find("share cores"), std::string::npos);
  EXPECT_EQ(core_list_text({0, 1, 2, 5, 7, 8}), "0-2,5,7-8");
  // A node of rank 0 alone.
  EXPECT_EQ(describe_node_cores({0}, {0, 1}, split_node_cores({0}, {0, 1})),
            "1 rank on this node shares 2 cores: rank 0 coordinates (no core of its own)");
}

TEST(RankCores, ThisProcessHasCoresAndCanBePinnedToThem) {
  const std::vector<int> cores = process_cores();
  ASSERT_FALSE(cores.empty());
  pin_process(cores);  // a no-op pin; restoring the mask keeps the other tests unaffected
  EXPECT_EQ(process_cores(), cores);
  EXPECT_THROW(pin_process({-1}), std::runtime_error);
}

}  // namespace
}  // namespace tuneray
